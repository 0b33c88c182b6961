//! What can go wrong in a CLI request: the server unreachable, the server's
//! refusal (problem+json, with its own words and the fields it names), or
//! a local problem (a file, an unexpected answer).

use serde::Deserialize;

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
        ClientError::Problem {
            status,
            title: problem.title,
            detail: problem.detail,
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
