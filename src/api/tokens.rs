//! Token management (`admin` scope): `/v1/tokens`. A token may expire
//! (`expires_in_secs`) and be revoked (`DELETE`); its row stays, so the list
//! shows revoked ones and anonymous access never comes back. The first token
//! created anonymously ends anonymous access, and its answer says so.

use axum::extract::{Path, State};
use axum::http::StatusCode;
use axum::{Extension, Json};
use serde::{Deserialize, Serialize};
use utoipa::ToSchema;
use utoipa_axum::router::OpenApiRouter;
use utoipa_axum::routes;

use super::auth::{generate_token, hash_token, Principal};
use super::error::{ApiError, ApiResult, Problem};
use super::extract::ApiJson;
use super::AppState;
use crate::domain::{now_unix_ms, rfc3339_of_unix_ms, Scope, TokenRecord};
use crate::store::DynStore;

pub fn router() -> OpenApiRouter<AppState> {
    OpenApiRouter::new()
        .routes(routes!(create_token, list_tokens))
        .routes(routes!(revoke_token))
}

/// Longest name, characters.
const MAX_NAME_LEN: usize = 100;
/// Longest expiry: ten years (a longer one is a token that never expires).
pub const MAX_EXPIRES_IN_SECS: i64 = 10 * 365 * 24 * 3600;

#[derive(Debug, Deserialize, ToSchema)]
#[serde(deny_unknown_fields)]
pub struct TokenBody {
    /// 1 to 100 characters: who or what uses the token.
    pub name: String,
    #[schema(value_type = String, example = "read")]
    pub scope: Scope,
    /// Seconds until the token is refused (absent: never expires).
    #[schema(minimum = 1, maximum = 315360000, example = 2592000)]
    pub expires_in_secs: Option<i64>,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct TokenOut {
    pub id: String,
    pub name: String,
    #[schema(value_type = String)]
    pub scope: Scope,
    pub created_at: String,
    /// When the token stops working; null: never.
    pub expires_at: Option<String>,
    /// When it was revoked; null: not revoked.
    pub revoked_at: Option<String>,
    /// Its last accepted use, to the minute; null: never used.
    pub last_used_at: Option<String>,
    /// `active`, `expired` or `revoked`.
    pub state: String,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct TokenList {
    pub items: Vec<TokenOut>,
}

#[derive(Debug, Serialize, ToSchema)]
pub struct TokenCreated {
    #[serde(flatten)]
    pub info: TokenOut,
    /// The bearer token; shown once, only its hash is kept.
    pub token: String,
    /// Set when this token ended anonymous access: from now on every `/v1`
    /// request needs a token.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub notice: Option<String>,
}

impl TokenOut {
    fn of(t: TokenRecord, now_ms: i64) -> TokenOut {
        let state = match t.check_usable(now_ms) {
            Ok(()) => "active",
            Err(crate::domain::TokenRefusal::Expired) => "expired",
            Err(crate::domain::TokenRefusal::Revoked) => "revoked",
        };
        TokenOut {
            id: t.id,
            name: t.name,
            scope: t.scope,
            created_at: t.created_at,
            expires_at: t.expires_ms.map(rfc3339_of_unix_ms),
            revoked_at: t.revoked_ms.map(rfc3339_of_unix_ms),
            last_used_at: t.last_used_ms.map(rfc3339_of_unix_ms),
            state: state.into(),
        }
    }
}

/// What a client or the CLI asks for: checked here for both.
pub struct NewToken<'a> {
    pub name: &'a str,
    pub scope: Scope,
    pub expires_in_secs: Option<i64>,
}

/// Stores a new token; returns it (the secret, once) with its record.
pub async fn create(store: &DynStore, new: &NewToken<'_>) -> ApiResult<(String, TokenRecord)> {
    let name = new.name.trim();
    if name.is_empty() || name.chars().count() > MAX_NAME_LEN {
        return Err(ApiError::invalid(
            "name",
            format!("1 to {MAX_NAME_LEN} characters"),
        ));
    }
    let expires_ms = match new.expires_in_secs {
        None => None,
        Some(s) if (1..=MAX_EXPIRES_IN_SECS).contains(&s) => Some(now_unix_ms() + s * 1000),
        Some(_) => {
            return Err(ApiError::invalid(
                "expires_in_secs",
                format!("1 to {MAX_EXPIRES_IN_SECS} seconds"),
            ))
        }
    };
    let token = generate_token();
    let record = store
        .create_token_expiring(name, &hash_token(&token), new.scope, expires_ms)
        .await?;
    Ok((token, record))
}

/// Create a token (shown once).
#[utoipa::path(post, path = "/v1/tokens", tag = "tokens", request_body = TokenBody,
    responses(
        (status = 201, body = TokenCreated, description = "The token, shown once; `notice` when it ended anonymous access"),
        (status = 401, body = Problem, content_type = "application/problem+json", description = "No valid token"),
        (status = 403, body = Problem, content_type = "application/problem+json", description = "The token is not `admin`"),
        (status = 422, body = Problem, content_type = "application/problem+json", description = "Invalid name, scope or expiry")))]
async fn create_token(
    State(state): State<AppState>,
    principal: Option<Extension<Principal>>,
    ApiJson(body): ApiJson<TokenBody>,
) -> ApiResult<(StatusCode, Json<TokenCreated>)> {
    let anonymous = matches!(principal.as_deref(), Some(Principal::Anonymous));
    let first = anonymous && state.store.count_tokens().await? == 0;
    let (token, record) = create(
        &state.store,
        &NewToken {
            name: &body.name,
            scope: body.scope,
            expires_in_secs: body.expires_in_secs,
        },
    )
    .await?;
    let notice = first.then(|| anonymous_ended_notice(record.scope));
    if let Some(notice) = &notice {
        tracing::warn!(token = %record.id, "{notice}");
    }
    Ok((
        StatusCode::CREATED,
        Json(TokenCreated {
            info: TokenOut::of(record, now_unix_ms()),
            token,
            notice,
        }),
    ))
}

fn anonymous_ended_notice(scope: Scope) -> String {
    let mut notice = "anonymous access has ended: this is the first token, and from now on \
                      every /v1 request needs `Authorization: Bearer <token>`"
        .to_string();
    if scope != Scope::Admin {
        notice.push_str(&format!(
            "; this token has scope {}, so managing tokens now needs an admin token \
             (`robocal token create --scope admin` on the server's database)",
            scope.as_str()
        ));
    }
    notice
}

/// List tokens (never their secrets), revoked and expired ones included.
#[utoipa::path(get, path = "/v1/tokens", tag = "tokens",
    responses(
        (status = 200, body = TokenList, description = "Every token, oldest first"),
        (status = 401, body = Problem, content_type = "application/problem+json", description = "No valid token"),
        (status = 403, body = Problem, content_type = "application/problem+json", description = "The token is not `admin`")))]
async fn list_tokens(State(state): State<AppState>) -> ApiResult<Json<TokenList>> {
    let now = now_unix_ms();
    let items = state.store.list_tokens().await?;
    Ok(Json(TokenList {
        items: items.into_iter().map(|t| TokenOut::of(t, now)).collect(),
    }))
}

/// Revoke a token: it is refused (401) from now on; its row stays listed.
#[utoipa::path(delete, path = "/v1/tokens/{id}", tag = "tokens",
    params(("id" = String, Path, description = "Token id (from the list, not the secret)")),
    responses(
        (status = 204, description = "Revoked (also when it was revoked already)"),
        (status = 401, body = Problem, content_type = "application/problem+json", description = "No valid token"),
        (status = 403, body = Problem, content_type = "application/problem+json", description = "The token is not `admin`"),
        (status = 404, body = Problem, content_type = "application/problem+json", description = "No token has this id"),
        (status = 409, body = Problem, content_type = "application/problem+json", description = "It is the last usable admin token (create another first)")))]
async fn revoke_token(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<StatusCode> {
    match state.store.revoke_token_keeping_an_admin(&id).await? {
        Some(_) => Ok(StatusCode::NO_CONTENT),
        None => Err(ApiError::not_found("token", &id)),
    }
}

async fn cli_store(database_url: &str) -> Result<DynStore, String> {
    crate::store::connect(database_url)
        .await
        .map_err(|e| e.to_string())
}

/// `robocal token create`: stores the hash, returns after printing the token once.
pub async fn create_from_cli(
    database_url: &str,
    name: &str,
    scope: Scope,
    expires_in: Option<std::time::Duration>,
) -> Result<(), String> {
    let store = cli_store(database_url).await?;
    let expires_in_secs = expires_in.map(|d| d.as_secs().min(i64::MAX as u64) as i64);
    let (token, record) = create(
        &store,
        &NewToken {
            name,
            scope,
            expires_in_secs,
        },
    )
    .await
    .map_err(|e| e.detail)?;
    let expiry = record
        .expires_ms
        .map(|ms| format!(", expires {}", rfc3339_of_unix_ms(ms)))
        .unwrap_or_default();
    eprintln!(
        "created token {} ({}, scope {}{expiry}); it is shown only now:",
        record.id,
        record.name,
        record.scope.as_str()
    );
    println!("{token}");
    Ok(())
}

/// `robocal tokens list`: one line per token, revoked and expired included.
pub async fn list_from_cli(database_url: &str) -> Result<(), String> {
    let store = cli_store(database_url).await?;
    let now = now_unix_ms();
    let tokens = store.list_tokens().await.map_err(|e| e.to_string())?;
    println!(
        "{:<36}  {:<20}  {:<5}  {:<7}  {:<24}  {:<24}  LAST USED",
        "ID", "NAME", "SCOPE", "STATE", "CREATED", "EXPIRES"
    );
    let or_dash = |s: Option<String>| s.unwrap_or_else(|| "-".into());
    for t in tokens {
        let t = TokenOut::of(t, now);
        println!(
            "{:<36}  {:<20}  {:<5}  {:<7}  {:<24}  {:<24}  {}",
            t.id,
            t.name,
            t.scope.as_str(),
            t.state,
            t.created_at,
            or_dash(t.expires_at),
            or_dash(t.last_used_at)
        );
    }
    Ok(())
}

/// `robocal tokens revoke ID`.
pub async fn revoke_from_cli(database_url: &str, id: &str) -> Result<(), String> {
    let store = cli_store(database_url).await?;
    match store.revoke_token(id).await.map_err(|e| e.to_string())? {
        Some(t) => {
            eprintln!("revoked token {} ({})", t.id, t.name);
            Ok(())
        }
        None => Err(format!("no token has id {id:?}")),
    }
}
