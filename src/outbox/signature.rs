//! The signature of a webhook request: `X-Robocal-Signature: sha256=<hex>`,
//! the HMAC-SHA256 of the exact body under the webhook's secret. A receiver
//! recomputes it over the bytes it got and compares in constant time.

use hmac::{Hmac, Mac};
use sha2::Sha256;

/// The header holding the signature.
pub const SIGNATURE_HEADER: &str = "x-robocal-signature";
/// The header naming the event (`job.finished`, …).
pub const EVENT_HEADER: &str = "x-robocal-event";
/// The header holding the event's id: the same on every retry, so a
/// receiver can drop repeats (delivery is at least once).
pub const DELIVERY_HEADER: &str = "x-robocal-delivery";

/// `sha256=` and the hex HMAC-SHA256 of `body` under `secret`.
pub fn sign(secret: &str, body: &[u8]) -> String {
    let mut mac =
        Hmac::<Sha256>::new_from_slice(secret.as_bytes()).expect("HMAC takes keys of any length");
    mac.update(body);
    format!("sha256={}", hex::encode(mac.finalize().into_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rfc_4231_case_2() {
        // RFC 4231 test case 2: key "Jefe", data "what do ya want for nothing?".
        assert_eq!(
            sign("Jefe", b"what do ya want for nothing?"),
            "sha256=5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"
        );
    }
}
