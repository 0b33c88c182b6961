//! Where webhooks may be delivered. An admin-supplied URL must not turn the
//! service into a proxy for cloud metadata or the internal network: every
//! delivery resolves its host, checks every address, and connects only to
//! the addresses it checked (no second lookup an attacker's DNS could
//! answer differently; redirects are never followed). Refused always: this
//! service itself, link-local (`169.254.0.0/16`, `fe80::/10`, where cloud
//! metadata lives), the metadata addresses of other clouds, unspecified,
//! multicast and broadcast addresses. Refused unless listed in
//! `--webhook-allow-networks`: loopback, private and shared
//! (`100.64.0.0/10`) ranges. IPv4-mapped IPv6 addresses
//! (`[::ffff:127.0.0.1]`) are checked as the IPv4 address they are.

use std::net::{IpAddr, Ipv4Addr, Ipv6Addr, SocketAddr};

/// Metadata services outside link-local (Alibaba Cloud; AWS over IPv6).
const METADATA: [IpAddr; 2] = [
    IpAddr::V4(Ipv4Addr::new(100, 100, 100, 200)),
    IpAddr::V6(Ipv6Addr::new(0xfd00, 0x0ec2, 0, 0, 0, 0, 0, 0x0254)),
];

/// An address range, `address/prefix`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Network {
    addr: IpAddr,
    prefix: u8,
}

impl std::str::FromStr for Network {
    type Err = String;

    fn from_str(text: &str) -> Result<Network, String> {
        let (addr, prefix) = text.trim().split_once('/').unwrap_or((text.trim(), ""));
        let addr: IpAddr = addr
            .parse()
            .map_err(|_| format!("{text:?} is not an address or address/prefix"))?;
        let max = if addr.is_ipv4() { 32 } else { 128 };
        let prefix = if prefix.is_empty() {
            max
        } else {
            prefix
                .parse::<u8>()
                .ok()
                .filter(|p| *p <= max)
                .ok_or_else(|| format!("{text:?}: the prefix must be 0 to {max}"))?
        };
        Ok(Network { addr, prefix })
    }
}

impl Network {
    fn contains(&self, ip: IpAddr) -> bool {
        match (self.addr, ip) {
            (IpAddr::V4(net), IpAddr::V4(ip)) => {
                masked(u32::from(net) as u128, 32, self.prefix)
                    == masked(u32::from(ip) as u128, 32, self.prefix)
            }
            (IpAddr::V6(net), IpAddr::V6(ip)) => {
                masked(u128::from(net), 128, self.prefix)
                    == masked(u128::from(ip), 128, self.prefix)
            }
            _ => false,
        }
    }
}

fn masked(bits: u128, width: u8, prefix: u8) -> u128 {
    if prefix == 0 {
        0
    } else {
        bits >> (width - prefix)
    }
}

/// The delivery policy for addresses.
#[derive(Debug, Clone)]
pub struct AddressGuard {
    /// This service's bound address: never a receiver on its port.
    pub bind: SocketAddr,
    /// Internal ranges an operator allowed for receivers.
    pub allow: Vec<Network>,
}

/// An IPv4-mapped IPv6 address as the IPv4 address it is.
fn canonical(ip: IpAddr) -> IpAddr {
    match ip {
        IpAddr::V6(v6) => v6.to_ipv4_mapped().map_or(ip, IpAddr::V4),
        v4 => v4,
    }
}

fn always_refused(ip: IpAddr) -> Option<&'static str> {
    if METADATA.contains(&ip) {
        return Some("a cloud metadata address");
    }
    match ip {
        IpAddr::V4(v4) if v4.is_link_local() => Some("a link-local address (cloud metadata)"),
        IpAddr::V4(v4) if v4.is_broadcast() || v4.is_multicast() => {
            Some("a broadcast or multicast address")
        }
        IpAddr::V6(v6) if (v6.segments()[0] & 0xffc0) == 0xfe80 => {
            Some("a link-local address (cloud metadata)")
        }
        IpAddr::V6(v6) if v6.is_multicast() => Some("a multicast address"),
        _ if ip.is_unspecified() => Some("an unspecified address"),
        _ => None,
    }
}

/// Shared address space (carrier-grade NAT), internal like the private ranges.
const SHARED: Network = Network {
    addr: IpAddr::V4(Ipv4Addr::new(100, 64, 0, 0)),
    prefix: 10,
};

fn internal(ip: IpAddr) -> bool {
    match ip {
        IpAddr::V4(v4) => v4.is_loopback() || v4.is_private() || SHARED.contains(ip),
        IpAddr::V6(v6) => v6.is_loopback() || (v6.segments()[0] & 0xfe00) == 0xfc00,
    }
}

impl AddressGuard {
    /// Why a receiver at `ip:port` is refused, if it is.
    pub fn refusal(&self, ip: IpAddr, port: u16) -> Option<String> {
        let ip = canonical(ip);
        let bound = canonical(self.bind.ip());
        let is_self =
            port == self.bind.port() && (ip == bound || ip.is_loopback() || bound.is_unspecified());
        if is_self {
            return Some(format!("{ip}:{port} is this service itself"));
        }
        if let Some(why) = always_refused(ip) {
            return Some(format!("{ip} is {why}"));
        }
        if internal(ip) && !self.allow.iter().any(|n| n.contains(ip)) {
            return Some(format!(
                "{ip} is an internal address (allow it with --webhook-allow-networks)"
            ));
        }
        None
    }

    /// Resolves `host:port` and checks every address; the addresses to
    /// connect to, or why the receiver is refused.
    pub async fn resolve(&self, host: &str, port: u16) -> Result<Vec<SocketAddr>, String> {
        let bare = host.trim_start_matches('[').trim_end_matches(']');
        let addrs: Vec<SocketAddr> = match bare.parse::<IpAddr>() {
            Ok(ip) => vec![SocketAddr::new(ip, port)],
            Err(_) => tokio::net::lookup_host((bare, port))
                .await
                .map_err(|e| format!("cannot resolve {host}: {e}"))?
                .collect(),
        };
        if addrs.is_empty() {
            return Err(format!("{host} resolves to no address"));
        }
        for a in &addrs {
            if let Some(why) = self.refusal(a.ip(), a.port()) {
                return Err(format!("refused receiver {host}: {why}"));
            }
        }
        Ok(addrs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn guard(allow: &[&str]) -> AddressGuard {
        AddressGuard {
            bind: "127.0.0.1:8080".parse().unwrap(),
            allow: allow.iter().map(|a| a.parse().unwrap()).collect(),
        }
    }

    #[test]
    fn metadata_link_local_self_and_internal_are_refused() {
        let g = guard(&[]);
        let refused = |ip: &str, port| g.refusal(ip.parse().unwrap(), port).is_some();
        assert!(refused("169.254.169.254", 80));
        assert!(refused("fe80::1", 80));
        assert!(refused("fd00:ec2::254", 80));
        assert!(refused("100.100.100.200", 80));
        assert!(refused("::ffff:127.0.0.1", 8080), "mapped self");
        assert!(refused("127.0.0.1", 9000), "loopback without allow-list");
        assert!(refused("10.1.2.3", 443));
        assert!(refused("0.0.0.0", 80));
        assert!(!refused("93.184.216.34", 443));
        let g = guard(&["127.0.0.0/8", "10.0.0.0/8"]);
        let refused = |ip: &str, port| g.refusal(ip.parse().unwrap(), port).is_some();
        assert!(!refused("127.0.0.1", 9000));
        assert!(!refused("::ffff:10.1.2.3", 443));
        assert!(refused("127.0.0.1", 8080), "self stays refused");
        assert!(refused("169.254.169.254", 80), "metadata stays refused");
        assert!("10.0.0.0/33".parse::<Network>().is_err());
    }
}
