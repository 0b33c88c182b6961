//! What can go wrong in a CLI request: the server unreachable, the server's
//! refusal (problem+json, with its own words and the fields it names), or
//! a local problem (a file, an unexpected answer).

use serde::Deserialize;

/// HTTP 401: no valid token was presented.
const UNAUTHORIZED: u16 = 401;
/// What a refused CLI request needs: the server wants a token.
pub const TOKEN_HINT: &str =
    "the server needs a token: pass --token TOKEN or set ROBOCAL_TOKEN (robocal token create prints one)";

#[derive(Debug, thiserror::Error)]
pub enum ClientError {
    #[error("cannot reach the server: {}", with_causes(.0))]
    Transport(#[from] reqwest::Error),
    #[error("{status}: {title}{}", detail_suffix(.detail, .fields))]
    Problem {
        status: u16,
        title: String,
        detail: String,
        fields: Vec<String>,
    },
    #[error("{0}")]
    Local(String),
}

/// An error and its causes: reqwest's own message hides why a connection
/// failed (refused, certificate not trusted...).
fn with_causes(e: &dyn std::error::Error) -> String {
    let mut out = e.to_string();
    let mut source = e.source();
    while let Some(cause) = source {
        out.push_str(": ");
        out.push_str(&cause.to_string());
        source = cause.source();
    }
    out
}

fn detail_suffix(detail: &str, fields: &[String]) -> String {
    let mut out = String::new();
    if !detail.is_empty() {
        out.push_str(" — ");
        out.push_str(detail);
    }
    for field in fields {
        out.push_str("\n  ");
        out.push_str(field);
    }
    out
}

impl ClientError {
    /// A refusal from its problem+json body (any other body: the status
    /// alone).
    pub fn of_problem(status: u16, body: &str) -> ClientError {
        let problem: Problem = serde_json::from_str(body).unwrap_or_default();
        let mut detail = problem.detail;
        if status == UNAUTHORIZED {
            if !detail.is_empty() {
                detail.push_str("; ");
            }
            detail.push_str(TOKEN_HINT);
        }
        ClientError::Problem {
            status,
            title: problem.title,
            detail,
            fields: problem
                .errors
                .into_iter()
                .map(|e| {
                    format!(
                        "{}: {}",
                        e.field.as_deref().unwrap_or("?"),
                        e.message.unwrap_or_default()
                    )
                })
                .collect(),
        }
    }
}

/// The parts of a problem+json answer the CLI shows.
#[derive(Debug, Default, Deserialize)]
struct Problem {
    #[serde(default)]
    title: String,
    #[serde(default)]
    detail: String,
    #[serde(default)]
    errors: Vec<ProblemField>,
}

#[derive(Debug, Deserialize)]
struct ProblemField {
    #[serde(default)]
    field: Option<String>,
    #[serde(default)]
    message: Option<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_401_says_how_to_give_a_token() {
        let e = ClientError::of_problem(
            401,
            r#"{"title": "Unauthorized", "detail": "missing bearer token"}"#,
        );
        let text = e.to_string();
        assert!(
            text.contains("missing bearer token; the server needs a token: pass --token"),
            "{text}"
        );
        assert!(text.contains("ROBOCAL_TOKEN"), "{text}");
        let other = ClientError::of_problem(404, r#"{"title": "Not Found"}"#).to_string();
        assert!(!other.contains("--token"), "{other}");
    }
}
