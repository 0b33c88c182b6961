//! `/v1/webhooks`: subscriptions to the service's events (`job.finished`,
//! `check.finished`, `set.approved`), delivered from the durable outbox
//! (`src/outbox/`) with retries, each request signed. Admin scope: a webhook
//! sends data to any URL it names.

use axum::extract::{Path, State};
use axum::http::{header, HeaderMap, StatusCode};
use axum::Json;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::error::{ApiResult, Problem};
use super::extract::ApiJson;
use super::AppState;
use crate::schema::webhook::{WebhookBody, WebhookCreated, WebhookList, WebhookOut};
use crate::service::webhooks::{self, SelfAddress};

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(create_webhook, list_webhooks))
        .routes(routes!(get_webhook, delete_webhook))
}

/// Subscribes `url` to `events`. Each event is POSTed as JSON
/// (`{"id","type","created_at","data"}`) with `X-Robocal-Event`,
/// `X-Robocal-Delivery` (the event id: the same on every retry) and
/// `X-Robocal-Signature: sha256=<hex HMAC-SHA256 of the body under the
/// secret>`; a 2xx answer ends it, anything else is retried with
/// exponential backoff. At least once: receivers drop repeated ids.
#[utoipa::path(post, path = "/v1/webhooks", tag = "webhooks",
    request_body = WebhookBody,
    responses((status = 201, body = WebhookCreated, description = "The webhook with its signing secret, shown this once"),
              (status = 403, body = Problem, content_type = "application/problem+json", description = "The token is not admin"),
              (status = 422, body = Problem, content_type = "application/problem+json", description = "`url` is not http(s), holds credentials or points at this service; `events` is empty or names an unknown event")))]
async fn create_webhook(
    State(state): State<AppState>,
    headers: HeaderMap,
    ApiJson(body): ApiJson<WebhookBody>,
) -> ApiResult<(StatusCode, Json<WebhookCreated>)> {
    let me = SelfAddress {
        bind: state.config.bind,
        host: headers
            .get(header::HOST)
            .and_then(|h| h.to_str().ok())
            .map(str::to_string),
        tls: state.config.tls_enabled(),
        guard: state.config.address_guard(),
    };
    let created = webhooks::create(&state.store, body, &me).await?;
    Ok((StatusCode::CREATED, Json(created)))
}

/// Every webhook with its deliveries counted (secrets are not shown).
#[utoipa::path(get, path = "/v1/webhooks", tag = "webhooks",
    responses((status = 200, body = WebhookList, description = "Every webhook, oldest first"),
              (status = 403, body = Problem, content_type = "application/problem+json", description = "The token is not admin")))]
async fn list_webhooks(State(state): State<AppState>) -> ApiResult<Json<WebhookList>> {
    Ok(Json(webhooks::list(&state.store).await?))
}

/// One webhook with its deliveries counted.
#[utoipa::path(get, path = "/v1/webhooks/{id}", tag = "webhooks",
    params(("id" = String, Path, description = "Webhook id")),
    responses((status = 200, body = WebhookOut, description = "The webhook"),
              (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn get_webhook(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<Json<WebhookOut>> {
    Ok(Json(webhooks::get(&state.store, &id).await?))
}

/// Deletes the webhook; its undelivered events are dropped.
#[utoipa::path(delete, path = "/v1/webhooks/{id}", tag = "webhooks",
    params(("id" = String, Path, description = "Webhook id")),
    responses((status = 204, description = "Deleted"),
              (status = 404, body = Problem, content_type = "application/problem+json")))]
async fn delete_webhook(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<StatusCode> {
    webhooks::delete(&state.store, &id).await?;
    Ok(StatusCode::NO_CONTENT)
}
