/// `openapi/openapi.json` is generated; regenerate it with
/// `cargo run -- openapi > openapi/openapi.json` when this fails.
#[test]
fn committed_openapi_document_is_current() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/openapi/openapi.json");
    let committed = std::fs::read_to_string(path).unwrap_or_default();
    let current = robocal::api::openapi_json();
    assert!(
        committed.trim() == current.trim(),
        "openapi/openapi.json is stale: run `cargo run -- openapi > openapi/openapi.json`"
    );
    for route in [
        "/v1/robots/{serial}",
        "/v1/sessions/{id}/poses",
        "/v1/sessions/{id}/dataset",
        "/v1/jobs/{id}",
        "/healthz",
    ] {
        assert!(
            current.contains(&format!("\"{route}\"")),
            "{route} documented"
        );
    }
}

/// What `/docs` shows is written for a client author: no internal ticket
/// numbers, and the service described as it is (several instruments and
/// boards), not as its first version was.
#[test]
fn openapi_descriptions_carry_no_ticket_numbers() {
    let current = robocal::api::openapi_json();
    let found: Vec<&str> = current
        .match_indices("issue ")
        .filter(|(i, _)| current[i + 6..].starts_with(|c: char| c.is_ascii_digit()))
        .map(|(i, _)| current.get(i.saturating_sub(40)..i + 8).unwrap_or("issue"))
        .collect();
    assert!(
        found.is_empty(),
        "ticket numbers in the OpenAPI document: {found:?}"
    );
    assert!(!current.contains("one flange camera, a dot-grid board"));
    assert!(
        current.contains("laser tracker"),
        "the description names every instrument"
    );
}
