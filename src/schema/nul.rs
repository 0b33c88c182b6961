//! Strings with a NUL character are refused wherever JSON comes in (request
//! bodies, archive manifests): PostgreSQL cannot store one in text, and
//! SQLite would store what no other tool reads back.

use serde_json::Value;

/// The message of the 422 naming a field that holds a NUL.
pub const NUL_MESSAGE: &str = "must not contain the NUL character (U+0000)";

/// The path (`a.b[2].c`, as serde reports fields) of the first string or
/// object key in `bytes` holding a NUL; `None` without one. JSON can only
/// carry NUL as the escape `\u0000`, so documents without it skip the walk.
pub fn json_nul_field(bytes: &[u8]) -> Option<String> {
    let escaped = bytes
        .windows(6)
        .any(|w| w[0] == b'\\' && w[1] == b'u' && w[2..].iter().all(|b| *b == b'0'));
    if !escaped {
        return None;
    }
    let value: Value = serde_json::from_slice(bytes).ok()?;
    find_nul(&value, String::new())
}

fn find_nul(value: &Value, at: String) -> Option<String> {
    let named = |at: &str| {
        if at.is_empty() {
            "body".to_string()
        } else {
            at.to_string()
        }
    };
    match value {
        Value::String(s) if s.contains('\0') => Some(named(&at)),
        Value::Array(items) => items
            .iter()
            .enumerate()
            .find_map(|(i, v)| find_nul(v, format!("{at}[{i}]"))),
        Value::Object(map) => map.iter().find_map(|(k, v)| {
            let field = if at.is_empty() {
                k.clone()
            } else {
                format!("{at}.{k}")
            };
            if k.contains('\0') {
                return Some(named(&at));
            }
            find_nul(v, field)
        }),
        _ => None,
    }
}
