//! The frame every fleet page shares: one self-contained HTML document
//! (inline CSS, no script, no outside asset), readable on a phone
//! (viewport meta, one column below 40em), and the login page.

use std::fmt::Write;

use crate::report::format::escape_xml;

/// Inline style sheet: cards that wrap to one column on a phone, tables
/// that scroll sideways inside their box rather than widening the page.
const STYLE: &str = r#"
:root { --ok: #1d7a36; --warn: #a35200; --bad: #b3261e; --rule: #d0d0d0; --muted: #5f5f5f; --accent: #1f5fa8; }
* { box-sizing: border-box; }
body { font-family: system-ui, -apple-system, 'Segoe UI', 'DejaVu Sans', Arial, sans-serif; margin: 0;
  color: #1f1f1f; background: #f6f7f9; line-height: 1.4; font-size: 16px; }
header { display: flex; align-items: center; justify-content: space-between; gap: 12px;
  padding: 10px 16px; background: #1f2a37; color: #fff; }
header a { color: #fff; text-decoration: none; font-weight: 600; }
header form { margin: 0; }
main { max-width: 1100px; margin: 0 auto; padding: 16px; }
h1 { font-size: 1.5rem; margin: 4px 0 12px; }
h2 { font-size: 1.15rem; margin: 24px 0 8px; }
a { color: var(--accent); }
.muted { color: var(--muted); }
.cards { display: grid; grid-template-columns: repeat(auto-fill, minmax(17rem, 1fr)); gap: 12px; }
.card { background: #fff; border: 1px solid var(--rule); border-radius: 8px; padding: 12px 14px; }
.card h2 { margin: 0 0 6px; font-size: 1.2rem; overflow-wrap: anywhere; }
.card dl { display: grid; grid-template-columns: max-content 1fr; gap: 3px 12px; margin: 0; }
.card dt { color: var(--muted); }
.card dd { margin: 0; overflow-wrap: anywhere; }
.verdict { font-weight: 600; }
.verdict.pass { color: var(--ok); } .verdict.drift { color: var(--bad); } .verdict.base_moved { color: var(--warn); } .verdict.controller_changed { color: var(--bad); }
.state-running { color: var(--accent); font-weight: 600; } .state-failed { color: var(--bad); }
.state-succeeded { color: var(--ok); }
.release-approved { color: var(--ok); } .release-candidate { color: var(--warn); font-weight: 600; }
.release-rejected { color: var(--bad); font-weight: 600; }
.card.failed { border-color: var(--bad); border-width: 2px; } .stale { color: var(--warn); }
td.error { white-space: normal; min-width: 16rem; }
.scroll { overflow-x: auto; background: #fff; border: 1px solid var(--rule); border-radius: 8px; }
table { border-collapse: collapse; width: 100%; }
th, td { text-align: left; padding: 6px 10px; border-bottom: 1px solid var(--rule); white-space: nowrap; }
th { background: #eef1f5; font-weight: 600; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
button { font: inherit; padding: 6px 14px; border-radius: 6px; border: 1px solid #888; background: #fff; cursor: pointer; }
header button { background: transparent; color: #fff; border-color: #9aa5b1; }
.login { max-width: 26rem; margin: 10vh auto; }
.login input { width: 100%; font: inherit; padding: 8px; margin: 6px 0 12px; border: 1px solid #888; border-radius: 6px; }
.error { color: var(--bad); font-weight: 600; }
@media (max-width: 40em) { main { padding: 10px; } h1 { font-size: 1.3rem; } th, td { padding: 5px 7px; } }
"#;

/// A complete page: `body` (already escaped HTML) under a header that
/// links home, and a logout button when `logout` (a signed-in session).
pub fn page(title: &str, body: &str, logout: bool) -> String {
    let mut html = String::with_capacity(body.len() + STYLE.len() + 600);
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<header><a href=\"/\">robocal fleet</a>",
        escape_xml(title)
    );
    if logout {
        html.push_str(
            "<form method=\"post\" action=\"/logout\"><button type=\"submit\">Log out</button></form>",
        );
    }
    html.push_str("</header>\n<main>\n");
    html.push_str(body);
    html.push_str("\n</main>\n</body>\n</html>\n");
    html
}

/// The login form (`POST /login` with a token of any scope); `error`
/// says why the last attempt was refused.
pub fn login_page(error: Option<&str>, nonce: &str) -> String {
    let mut body = String::from("<div class=\"login card\">\n<h1>Sign in</h1>\n");
    if let Some(e) = error {
        let _ = writeln!(body, "<p class=\"error\">{}</p>", escape_xml(e));
    }
    body.push_str(
        "<form method=\"post\" action=\"/login\">\n\
         <label for=\"token\">API token (read scope is enough)</label>\n\
         <input id=\"token\" name=\"token\" type=\"password\" autocomplete=\"current-password\" required>\n",
    );
    let _ = writeln!(
        body,
        "<input type=\"hidden\" name=\"nonce\" value=\"{}\">",
        escape_xml(nonce)
    );
    body.push_str(
        "<button type=\"submit\">Sign in</button>\n</form>\n\
         <p class=\"muted\">The token is checked once; the browser then keeps a session cookie, \
         never the token.</p>\n</div>",
    );
    page("Sign in · robocal", &body, false)
}

/// A short error page (unknown robot, no such report).
pub fn message_page(title: &str, message: &str, logout: bool) -> String {
    let body = format!(
        "<h1>{}</h1>\n<p>{}</p>\n<p><a href=\"/\">Back to the fleet</a></p>",
        escape_xml(title),
        escape_xml(message)
    );
    page(title, &body, logout)
}

const JUST_NOW: &str = "just now";

/// How long ago `created_at` (RFC 3339) was, from `now_ms`: `"3 d"`,
/// `"5 h"`, `"12 min"`, `"just now"`; `"?"` for an unreadable time.
pub fn age(created_at: &str, now_ms: i64) -> String {
    const MINUTE_MS: i64 = 60_000;
    const HOUR_MS: i64 = 60 * MINUTE_MS;
    const DAY_MS: i64 = 24 * HOUR_MS;
    let Ok(then) = humantime::parse_rfc3339_weak(created_at) else {
        return "?".into();
    };
    let then_ms = then
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_millis() as i64)
        .unwrap_or(0);
    let ago = (now_ms - then_ms).max(0);
    if ago >= DAY_MS {
        format!("{} d", ago / DAY_MS)
    } else if ago >= HOUR_MS {
        format!("{} h", ago / HOUR_MS)
    } else if ago >= MINUTE_MS {
        format!("{} min", ago / MINUTE_MS)
    } else {
        JUST_NOW.into()
    }
}

/// `"3 d ago"`, or `"just now"`.
pub fn ago(created_at: &str, now_ms: i64) -> String {
    with_suffix(age(created_at, now_ms), "ago")
}

/// `"3 d old"`, or `"just now"`.
pub fn old(created_at: &str, now_ms: i64) -> String {
    with_suffix(age(created_at, now_ms), "old")
}

fn with_suffix(age: String, suffix: &str) -> String {
    if age == JUST_NOW || age == "?" {
        age
    } else {
        format!("{age} {suffix}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ages_in_the_largest_whole_unit() {
        let t = "2026-11-20T10:00:00.000Z";
        let base = humantime::parse_rfc3339_weak(t)
            .unwrap()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_millis() as i64;
        assert_eq!(age(t, base + 30_000), "just now");
        assert_eq!(age(t, base + 12 * 60_000), "12 min");
        assert_eq!(age(t, base + 5 * 3_600_000 + 1), "5 h");
        assert_eq!(age(t, base + 3 * 86_400_000), "3 d");
        assert_eq!(age("yesterday", base), "?");
        assert_eq!(ago(t, base + 3 * 86_400_000), "3 d ago");
        assert_eq!(old(t, base), "just now");
    }

    #[test]
    fn pages_are_self_contained_and_fit_a_phone() {
        for html in [login_page(Some("<bad>"), "n"), message_page("x", "y", true)] {
            assert!(html.contains("name=\"viewport\""));
            assert!(
                !html.contains("http://") && !html.contains("https://"),
                "{html}"
            );
            assert!(!html.contains("<script"));
            assert!(!html.contains("<bad>"));
        }
    }
}
