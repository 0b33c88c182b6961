//! Webhook subscriptions: checked once here (the URL is another service's,
//! the events exist), stored with a fresh signing secret.

use std::net::{IpAddr, SocketAddr};

use base64::Engine;
use rand::RngCore;

use super::error::{ServiceError, ServiceResult};
use crate::domain::{new_id, now_rfc3339, DomainEvent};
use crate::outbox::address_guard::AddressGuard;
use crate::schema::webhook::{
    DeliveryCounts, WebhookBody, WebhookCreated, WebhookList, WebhookOut,
};
use crate::store::{DynStore, WebhookRecord};

/// Longest accepted webhook URL, bytes.
pub const MAX_URL_BYTES: usize = 2048;
/// Random bytes of a signing secret.
const SECRET_BYTES: usize = 32;
/// Prefix of a signing secret, so a leaked one is recognisable.
const SECRET_PREFIX: &str = "whsec_";

/// How this service is reached, to refuse webhooks that call it back.
#[derive(Debug, Clone)]
pub struct SelfAddress {
    /// The bound address (port 0 resolved).
    pub bind: SocketAddr,
    /// The `Host` the request came in with (`name[:port]`).
    pub host: Option<String>,
    pub tls: bool,
    /// Which addresses receivers may have (`--webhook-allow-networks`).
    pub guard: AddressGuard,
}

impl SelfAddress {
    /// True when `host:port` names this service: the name the request used,
    /// or a loopback, unspecified or bound address on the bound port.
    fn is_self(&self, host: &str, port: u16) -> bool {
        let host = host.trim_start_matches('[').trim_end_matches(']');
        if let Some(request_host) = &self.host {
            let default_port = if self.tls { 443 } else { 80 };
            let (name, given) = match request_host.rsplit_once(':') {
                Some((n, p)) if !p.contains(']') => (n, p.parse().unwrap_or(default_port)),
                _ => (request_host.as_str(), default_port),
            };
            let name = name.trim_start_matches('[').trim_end_matches(']');
            if name.eq_ignore_ascii_case(host) && given == port {
                return true;
            }
        }
        if port != self.bind.port() {
            return false;
        }
        match host.parse::<IpAddr>() {
            Ok(ip) => ip.is_loopback() || ip.is_unspecified() || ip == self.bind.ip(),
            Err(_) => host.eq_ignore_ascii_case("localhost"),
        }
    }
}

fn check_url(url: &str, me: &SelfAddress) -> ServiceResult<String> {
    let bad = |why: &str| ServiceError::invalid("url", why);
    if url.len() > MAX_URL_BYTES {
        return Err(bad("longer than 2048 bytes"));
    }
    let parsed = reqwest::Url::parse(url).map_err(|e| bad(&format!("not a URL: {e}")))?;
    if !matches!(parsed.scheme(), "http" | "https") {
        return Err(bad("must be an http:// or https:// URL"));
    }
    if !parsed.username().is_empty() || parsed.password().is_some() {
        return Err(bad("must not hold a user name or password"));
    }
    let host = parsed.host_str().ok_or_else(|| bad("names no host"))?;
    let port = parsed
        .port_or_known_default()
        .ok_or_else(|| bad("names no port"))?;
    if me.is_self(host, port) {
        return Err(bad("points at this service itself"));
    }
    // Addresses written in the URL are checked now (names at every delivery,
    // after resolving them); `localhost.` is `localhost`.
    let bare = host.trim_start_matches('[').trim_end_matches(']');
    let literal = match bare.trim_end_matches('.').to_ascii_lowercase().as_str() {
        "localhost" => Some(IpAddr::from([127, 0, 0, 1])),
        _ => bare.parse::<IpAddr>().ok(),
    };
    if let Some(why) = literal.and_then(|ip| me.guard.refusal(ip, port)) {
        return Err(bad(&format!("refused receiver: {why}")));
    }
    Ok(parsed.to_string())
}

fn check_events(events: &[String]) -> ServiceResult<Vec<String>> {
    let known = DomainEvent::NAMES.join(", ");
    if events.is_empty() {
        return Err(ServiceError::invalid(
            "events",
            format!("name at least one of {known}"),
        ));
    }
    let mut checked: Vec<String> = Vec::new();
    for e in events {
        if !DomainEvent::is_name(e) {
            return Err(ServiceError::invalid(
                "events",
                format!("unknown event {e:?}: expected {known}"),
            ));
        }
        if !checked.contains(e) {
            checked.push(e.clone());
        }
    }
    Ok(checked)
}

fn fresh_secret() -> String {
    let mut bytes = [0u8; SECRET_BYTES];
    rand::rng().fill_bytes(&mut bytes);
    format!(
        "{SECRET_PREFIX}{}",
        base64::engine::general_purpose::URL_SAFE_NO_PAD.encode(bytes)
    )
}

/// Checks and stores a subscription; its secret is answered this once.
pub async fn create(
    store: &DynStore,
    body: WebhookBody,
    me: &SelfAddress,
) -> ServiceResult<WebhookCreated> {
    let url = check_url(&body.url, me)?;
    let events = check_events(&body.events)?;
    let record = WebhookRecord {
        id: new_id(),
        url,
        events,
        secret: fresh_secret(),
        created_at: now_rfc3339(),
    };
    store.create_webhook(&record).await?;
    Ok(WebhookCreated {
        id: record.id,
        url: record.url,
        events: record.events,
        created_at: record.created_at,
        secret: record.secret,
    })
}

async fn out(store: &DynStore, w: WebhookRecord) -> ServiceResult<WebhookOut> {
    let mut deliveries = DeliveryCounts::default();
    for (state, n) in store.outbox_counts(&w.id).await? {
        match state.as_str() {
            "pending" => deliveries.pending = n,
            "delivered" => deliveries.delivered = n,
            _ => deliveries.failed += n,
        }
    }
    Ok(WebhookOut {
        id: w.id,
        url: w.url,
        events: w.events,
        created_at: w.created_at,
        deliveries,
    })
}

/// Every webhook, oldest first, with its deliveries counted.
pub async fn list(store: &DynStore) -> ServiceResult<WebhookList> {
    let mut items = Vec::new();
    for w in store.list_webhooks().await? {
        items.push(out(store, w).await?);
    }
    Ok(WebhookList { items })
}

pub async fn get(store: &DynStore, id: &str) -> ServiceResult<WebhookOut> {
    let w = store
        .get_webhook(id)
        .await?
        .ok_or_else(|| ServiceError::not_found("webhook", id))?;
    out(store, w).await
}

/// Deletes the webhook and its undelivered events (404 when absent).
pub async fn delete(store: &DynStore, id: &str) -> ServiceResult<()> {
    if store.delete_webhook(id).await? {
        Ok(())
    } else {
        Err(ServiceError::not_found("webhook", id))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn me(host: Option<&str>) -> SelfAddress {
        SelfAddress {
            bind: "127.0.0.1:8080".parse().unwrap(),
            host: host.map(str::to_string),
            tls: false,
            guard: AddressGuard {
                bind: "127.0.0.1:8080".parse().unwrap(),
                allow: vec!["127.0.0.0/8".parse().unwrap()],
            },
        }
    }

    #[test]
    fn urls_of_this_service_are_refused() {
        let m = me(Some("robocal.plant:8080"));
        for url in [
            "http://127.0.0.1:8080/x",
            "http://localhost:8080/",
            "http://[::1]:8080/",
            "http://0.0.0.0:8080/",
            "http://robocal.plant:8080/hook",
            "http://ROBOCAL.plant:8080/hook",
            "http://[::ffff:127.0.0.1]:8080/",
            "http://localhost.:8080/",
            "http://169.254.169.254/latest/meta-data/",
            "http://[fe80::1]/",
            "http://10.0.0.5/hook",
        ] {
            assert!(check_url(url, &m).is_err(), "{url}");
        }
        for url in [
            "http://127.0.0.1:9000/x",
            "https://hooks.example.com/robocal",
            "http://robocal.plant:9000/",
        ] {
            assert!(check_url(url, &m).is_ok(), "{url}");
        }
        for url in [
            "ftp://example.com/",
            "file:///etc/passwd",
            "not a url",
            "http://u:p@example.com/",
        ] {
            assert!(check_url(url, &m).is_err(), "{url}");
        }
    }

    #[test]
    fn events_are_known_names() {
        assert!(check_events(&[]).is_err());
        assert!(check_events(&["job.started".into()]).is_err());
        let ok = check_events(&["job.finished".into(), "job.finished".into()]).unwrap();
        assert_eq!(ok, ["job.finished"]);
    }
}
