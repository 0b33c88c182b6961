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
