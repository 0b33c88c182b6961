//! Token management (`admin` scope): `/v1/tokens`.

use axum::extract::State;
use axum::http::StatusCode;
use axum::Json;
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::auth::{generate_token, hash_token};
use super::error::{ApiError, ApiResult, Problem};
use super::extract::ApiJson;
use super::AppState;
use crate::domain::{Scope, TokenRecord};

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new().routes(routes!(create_token, list_tokens))
}

#[derive(Debug, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TokenBody {
    pub name: String,
    #[schema(value_type = String, example = "read")]
    pub scope: Scope,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct TokenOut {
    pub id: String,
    pub name: String,
    #[schema(value_type = String)]
    pub scope: Scope,
    pub created_at: String,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct TokenCreated {
    #[serde(flatten)]
    pub info: TokenOut,
    /// The bearer token; shown once, only its hash is kept.
    pub token: String,
}

impl From<TokenRecord> for TokenOut {
    fn from(t: TokenRecord) -> TokenOut {
        TokenOut {
            id: t.id,
            name: t.name,
            scope: t.scope,
            created_at: t.created_at,
        }
    }
}

/// Create a token (shown once).
#[utoipa::path(post, path = "/v1/tokens", tag = "tokens", request_body = TokenBody,
    responses((status = 201, description = "The token, shown this once (only its hash is stored)", body = TokenCreated), (status = 403, body = Problem, content_type = "application/problem+json")))]
async fn create_token(
    State(state): State<AppState>,
    ApiJson(body): ApiJson<TokenBody>,
) -> ApiResult<(StatusCode, Json<TokenCreated>)> {
    if body.name.trim().is_empty() || body.name.len() > 100 {
        return Err(ApiError::invalid("name", "1 to 100 characters"));
    }
    let token = generate_token();
    let record = state
        .store
        .create_token(body.name.trim(), &hash_token(&token), body.scope)
        .await?;
    Ok((
        StatusCode::CREATED,
        Json(TokenCreated {
            info: record.into(),
            token,
        }),
    ))
}

/// List tokens (never their secrets).
#[utoipa::path(get, path = "/v1/tokens", tag = "tokens",
    responses((status = 200, description = "Every token's name, scope and creation date (never the token)", body = Vec<TokenOut>), (status = 403, body = Problem, content_type = "application/problem+json")))]
async fn list_tokens(State(state): State<AppState>) -> ApiResult<Json<Vec<TokenOut>>> {
    Ok(Json(
        state
            .store
            .list_tokens()
            .await?
            .into_iter()
            .map(Into::into)
            .collect(),
    ))
}

/// `robocal token create`: stores the hash, returns after printing the token once.
pub async fn create_from_cli(database_url: &str, name: &str, scope: Scope) -> Result<(), String> {
    let store = crate::store::connect(database_url)
        .await
        .map_err(|e| e.to_string())?;
    let token = generate_token();
    let record = store
        .create_token(name, &hash_token(&token), scope)
        .await
        .map_err(|e| e.to_string())?;
    eprintln!(
        "created token {} ({}, scope {}); it is shown only now:",
        record.id,
        record.name,
        record.scope.as_str()
    );
    println!("{token}");
    Ok(())
}
