//! The failure answers every operation shares, added to the OpenAPI document
//! in one place instead of repeated on every `#[utoipa::path]`: the
//! middleware (auth, body limits, extractors) answers them on any route, so
//! a client generated from the document must know them everywhere.
//!
//! Which ones an operation gets follows from what it has: `/v1/` routes need
//! a token (401, 403); a request body can be malformed (400), too large
//! (413), of the wrong media type (415) or invalid (422); path parameters
//! name something that may not exist (404); query parameters can be out of
//! range (422). An answer the route documents itself is left as it is, only
//! an empty description is filled.

use utoipa::openapi::path::{Operation, ParameterIn};
use utoipa::openapi::response::{Response, ResponseBuilder};
use utoipa::openapi::schema::{Schema, SchemaType, Type};
use utoipa::openapi::{ContentBuilder, OpenApi, Ref, RefOr};

use super::error::PROBLEM_JSON;

/// A failure answer: status and what it means.
struct Failure {
    status: &'static str,
    description: &'static str,
}

const UNAUTHORIZED: Failure = Failure {
    status: "401",
    description: "No valid bearer token (anonymous access is only granted on a loopback bind with no token in the database)",
};
const FORBIDDEN: Failure = Failure {
    status: "403",
    description: "The token's scope does not allow this operation (read: GET; write: also writes and jobs; admin: also tokens)",
};
const MALFORMED: Failure = Failure {
    status: "400",
    description:
        "The body cannot be read: malformed JSON, multipart or archive (`errors` names the part)",
};
const BAD_QUERY: Failure = Failure {
    status: "400",
    description: "The query string cannot be read (e.g. a parameter given twice)",
};
const NOT_FOUND: Failure = Failure {
    status: "404",
    description: "A resource named in the path does not exist",
};
const TOO_LARGE: Failure = Failure {
    status: "413",
    description: "The body is larger than the server's limit (`--max-json-bytes`, `--max-image-bytes` or `--max-archive-bytes`)",
};
const UNSUPPORTED: Failure = Failure {
    status: "415",
    description: "The body's Content-Type is not one this operation reads",
};
const INVALID: Failure = Failure {
    status: "422",
    description: "A field or parameter is invalid: `errors` names each one with the reason",
};

const BODY_TIMEOUT: Failure = Failure {
    status: "408",
    description: "The body went silent, or arrived slower than the server's minimum rate (`--body-idle-timeout-secs`, `--min-body-bytes-per-sec`)",
};
const BUSY: Failure = Failure {
    status: "503",
    description: "Every connection is in a request and this one is reserved for health checks and authenticated requests, or the client holds its maximum of connections or event streams: retry after `Retry-After` seconds",
};
/// Probes always pass the reserved lane.
const PROBE_PATHS: [&str; 2] = ["/healthz", "/readyz"];

/// Descriptions of answers a route documents without one.
fn default_description(status: &str) -> &'static str {
    match status {
        "200" => "OK",
        "201" => "Created",
        "202" => "Accepted",
        "204" => "No content",
        "409" => "Conflicts with the resource's current state",
        "429" => "Too many requests: retry after `Retry-After` seconds",
        other => [
            &UNAUTHORIZED,
            &FORBIDDEN,
            &MALFORMED,
            &NOT_FOUND,
            &TOO_LARGE,
            &UNSUPPORTED,
            &INVALID,
            &BODY_TIMEOUT,
            &BUSY,
        ]
        .into_iter()
        .find(|f| f.status == other)
        .map_or("See the problem document", |f| f.description),
    }
}

fn problem_response(description: &str) -> Response {
    ResponseBuilder::new()
        .description(description)
        .content(
            PROBLEM_JSON,
            ContentBuilder::new()
                .schema(Some(Ref::from_schema_name("Problem")))
                .build(),
        )
        .build()
}

/// The one route outside `/v1/` that may need a token.
const METRICS_PATH: &str = "/metrics";

/// The failures `operation` on `path` can answer.
fn failures_of(method: &str, path: &str, operation: &Operation) -> Vec<&'static Failure> {
    let mut out = Vec::new();
    // `/metrics` needs a read token once tokens exist (unless the server
    // runs with `--public-metrics`).
    if path.starts_with("/v1/") || path == METRICS_PATH {
        out.extend([&UNAUTHORIZED, &FORBIDDEN]);
    }
    let params = operation.parameters.as_deref().unwrap_or_default();
    let has = |place: ParameterIn| params.iter().any(|p| p.parameter_in == place);
    // A PUT creates what its path names: it never answers 404.
    if has(ParameterIn::Path) && method != "put" {
        out.push(&NOT_FOUND);
    }
    if !PROBE_PATHS.contains(&path) {
        out.push(&BUSY);
    }
    if operation.request_body.is_some() {
        out.extend([
            &MALFORMED,
            &TOO_LARGE,
            &UNSUPPORTED,
            &INVALID,
            &BODY_TIMEOUT,
        ]);
    } else {
        if has(ParameterIn::Query) {
            out.push(&BAD_QUERY);
        }
        if has(ParameterIn::Query) || has(ParameterIn::Path) {
            out.push(&INVALID);
        }
    }
    out
}

/// An optional body is one that may be left out, not a JSON `null`:
/// `Option<T>` bodies are documented as `T`, not required.
fn unwrap_optional_body(operation: &mut Operation) {
    let Some(body) = operation.request_body.as_mut() else {
        return;
    };
    for content in body.content.values_mut() {
        if let Some(RefOr::T(Schema::OneOf(one_of))) = &content.schema {
            let mut rest = one_of.items.iter().filter(|s| !is_null(s));
            if let (Some(only), None) = (rest.next(), rest.next()) {
                content.schema = Some(only.clone());
            }
        }
    }
}

fn is_null(schema: &RefOr<Schema>) -> bool {
    matches!(schema, RefOr::T(Schema::Object(o)) if o.schema_type == SchemaType::Type(Type::Null))
}

fn complete(method: &str, path: &str, operation: &mut Operation) {
    unwrap_optional_body(operation);
    let failures = failures_of(method, path, operation);
    let responses = &mut operation.responses.responses;
    for failure in failures {
        responses
            .entry(failure.status.to_string())
            .or_insert_with(|| RefOr::T(problem_response(failure.description)));
    }
    for (status, response) in responses.iter_mut() {
        if let RefOr::T(r) = response {
            if r.description.is_empty() {
                r.description = default_description(status).to_string();
            }
        }
    }
}

/// Adds the shared failure answers to every operation of `doc`.
pub fn add_shared_responses(doc: &mut OpenApi) {
    for (path, item) in doc.paths.paths.iter_mut() {
        for (method, operation) in [
            ("get", &mut item.get),
            ("put", &mut item.put),
            ("post", &mut item.post),
            ("delete", &mut item.delete),
            ("patch", &mut item.patch),
        ] {
            if let Some(operation) = operation {
                complete(method, path, operation);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use serde_json::Value;

    fn resolve<'a>(doc: &'a Value, schema: &'a Value) -> &'a Value {
        match schema["$ref"].as_str() {
            Some(r) => {
                let name = r.trim_start_matches("#/components/schemas/");
                resolve(doc, &doc["components"]["schemas"][name])
            }
            None => schema,
        }
    }

    /// Fails when an `allOf` joins a closed schema (`additionalProperties:
    /// false`) with another that adds properties: no document satisfies both.
    fn check_satisfiable(doc: &Value, schema: &Value, at: &str, seen: &mut BTreeSet<String>) {
        if let Some(r) = schema["$ref"].as_str() {
            if !seen.insert(r.to_string()) {
                return;
            }
        }
        let schema = resolve(doc, schema);
        if let Some(parts) = schema["allOf"].as_array() {
            for part in parts {
                let closed = resolve(doc, part)["additionalProperties"] == Value::Bool(false);
                assert!(
                    !(closed && parts.len() > 1),
                    "{at}: allOf joins a closed schema {part}"
                );
            }
        }
        for key in ["allOf", "oneOf", "anyOf"] {
            for part in schema[key].as_array().into_iter().flatten() {
                check_satisfiable(doc, part, at, seen);
            }
        }
        for (name, property) in schema["properties"].as_object().into_iter().flatten() {
            check_satisfiable(doc, property, &format!("{at}.{name}"), seen);
        }
        if schema.get("items").is_some() {
            check_satisfiable(doc, &schema["items"], &format!("{at}[]"), seen);
        }
    }

    /// The session answer once reused the request schema (closed by
    /// `deny_unknown_fields`) and added `id`: no session could validate.
    #[test]
    fn every_success_response_schema_can_be_satisfied() {
        let doc: Value = serde_json::from_str(&super::super::openapi_json()).unwrap();
        for (path, item) in doc["paths"].as_object().unwrap() {
            for (method, op) in item.as_object().unwrap() {
                for (status, response) in op["responses"].as_object().unwrap() {
                    if !status.starts_with('2') {
                        continue;
                    }
                    for (media, content) in response["content"].as_object().into_iter().flatten() {
                        let at = format!("{method} {path} {status} {media}");
                        check_satisfiable(&doc, &content["schema"], &at, &mut BTreeSet::new());
                    }
                }
            }
        }
    }

    #[test]
    fn every_response_has_a_description_and_routes_their_failures() {
        let doc: serde_json::Value = serde_json::from_str(&super::super::openapi_json()).unwrap();
        for (path, item) in doc["paths"].as_object().unwrap() {
            for (method, op) in item.as_object().unwrap() {
                for (status, response) in op["responses"].as_object().unwrap() {
                    let d = response["description"].as_str().unwrap_or_default();
                    assert!(!d.is_empty(), "{method} {path} {status}: no description");
                }
                if path.starts_with("/v1/") {
                    for status in ["401", "403"] {
                        assert!(
                            op["responses"].get(status).is_some(),
                            "{method} {path} {status}"
                        );
                    }
                }
                if op.get("requestBody").is_some() {
                    for status in ["400", "413", "415", "422"] {
                        assert!(
                            op["responses"].get(status).is_some(),
                            "{method} {path} {status}"
                        );
                    }
                }
                if path.contains('{') && method != "put" {
                    assert!(op["responses"].get("404").is_some(), "{method} {path} 404");
                }
            }
        }
    }
}
