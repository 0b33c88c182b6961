//! The webhook documents of `/v1/webhooks`.

use serde::{Deserialize, Serialize};
use utoipa::ToSchema;

/// `POST /v1/webhooks`.
#[derive(Debug, Clone, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct WebhookBody {
    /// Where events are POSTed: an `http` or `https` URL of another
    /// service (not this one), without user name or password.
    #[schema(example = "https://hooks.example.com/robocal")]
    pub url: String,
    /// The events to send: `job.finished`, `check.finished`, `set.approved`.
    #[schema(example = json!(["job.finished"]))]
    pub events: Vec<String>,
}

/// How many of a webhook's events are in each delivery state.
#[derive(Debug, Clone, Default, Serialize, ToSchema)]
pub struct DeliveryCounts {
    /// Not yet answered 2xx (waiting for a retry, or in flight).
    pub pending: i64,
    pub delivered: i64,
    /// Given up after the last retry.
    pub failed: i64,
}

/// A webhook as listed (its secret is shown only when it is created).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct WebhookOut {
    pub id: String,
    pub url: String,
    pub events: Vec<String>,
    pub created_at: String,
    pub deliveries: DeliveryCounts,
}

/// A webhook just created, with its secret (shown this once).
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct WebhookCreated {
    pub id: String,
    pub url: String,
    pub events: Vec<String>,
    pub created_at: String,
    /// The HMAC-SHA256 key of the `X-Robocal-Signature` header
    /// (`sha256=` and the hex HMAC of the request body). Store it now: it
    /// is never shown again.
    pub secret: String,
}

/// `GET /v1/webhooks`.
#[derive(Debug, Clone, Serialize, ToSchema)]
pub struct WebhookList {
    pub items: Vec<WebhookOut>,
}
