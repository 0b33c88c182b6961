//! The CLI's HTTP client: a thin typed layer over the REST contract
//! (api.md) for `robocal upload`, `calibrate` and `report`. Problem+json
//! answers become [`ClientError::Problem`] with the server's own words.

use std::path::Path;
use std::time::Duration;

use serde_json::Value;

use crate::report::Report;

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

/// How long one request may take; uploads of whole campaigns get longer.
const REQUEST_TIMEOUT: Duration = Duration::from_secs(60);
const UPLOAD_TIMEOUT: Duration = Duration::from_secs(3600);

pub struct Client {
    http: reqwest::Client,
    base: String,
    token: Option<String>,
}

impl Client {
    pub fn new(base_url: &str, token: Option<String>) -> Result<Self, ClientError> {
        Self::with_ca_cert(base_url, token, None)
    }

    /// `ca_cert`: PEM file of certificates trusted for `https://` besides the
    /// public roots (a private CA or a self-signed server certificate).
    pub fn with_ca_cert(
        base_url: &str,
        token: Option<String>,
        ca_cert: Option<&Path>,
    ) -> Result<Self, ClientError> {
        let mut builder = reqwest::Client::builder()
            .use_rustls_tls()
            .timeout(REQUEST_TIMEOUT);
        if let Some(path) = ca_cert {
            let pem = std::fs::read(path)
                .map_err(|e| ClientError::Local(format!("{}: {e}", path.display())))?;
            let certs = reqwest::Certificate::from_pem_bundle(&pem).map_err(|e| {
                ClientError::Local(format!("{}: not PEM certificates: {e}", path.display()))
            })?;
            if certs.is_empty() {
                return Err(ClientError::Local(format!(
                    "{}: holds no PEM certificate",
                    path.display()
                )));
            }
            for cert in certs {
                builder = builder.add_root_certificate(cert);
            }
        }
        let http = builder.build()?;
        Ok(Self {
            http,
            base: base_url.trim_end_matches('/').to_string(),
            token,
        })
    }

    fn request(&self, method: reqwest::Method, path: &str) -> reqwest::RequestBuilder {
        let builder = self.http.request(method, format!("{}{}", self.base, path));
        match &self.token {
            Some(token) => builder.bearer_auth(token),
            None => builder,
        }
    }

    async fn send(&self, builder: reqwest::RequestBuilder) -> Result<Value, ClientError> {
        let response = builder.send().await?;
        let status = response.status();
        let body: Value = response.json().await.unwrap_or(Value::Null);
        if status.is_success() {
            return Ok(body);
        }
        let text = |key: &str| {
            body.get(key)
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_string()
        };
        let fields = body
            .get("errors")
            .and_then(Value::as_array)
            .map(|errors| {
                errors
                    .iter()
                    .map(|e| {
                        format!(
                            "{}: {}",
                            e.get("field").and_then(Value::as_str).unwrap_or("?"),
                            e.get("message").and_then(Value::as_str).unwrap_or("")
                        )
                    })
                    .collect()
            })
            .unwrap_or_default();
        Err(ClientError::Problem {
            status: status.as_u16(),
            title: text("title"),
            detail: text("detail"),
            fields,
        })
    }

    pub async fn put_robot(
        &self,
        serial: &str,
        body: &impl serde::Serialize,
    ) -> Result<Value, ClientError> {
        self.send(
            self.request(reqwest::Method::PUT, &format!("/v1/robots/{serial}"))
                .json(body),
        )
        .await
    }

    /// The robot, or `None` when the server has no robot of that serial.
    pub async fn get_robot(&self, serial: &str) -> Result<Option<Value>, ClientError> {
        match self
            .send(self.request(reqwest::Method::GET, &format!("/v1/robots/{serial}")))
            .await
        {
            Ok(robot) => Ok(Some(robot)),
            Err(ClientError::Problem { status: 404, .. }) => Ok(None),
            Err(e) => Err(e),
        }
    }

    pub async fn get_session(&self, session_id: &str) -> Result<Value, ClientError> {
        self.send(self.request(reqwest::Method::GET, &format!("/v1/sessions/{session_id}")))
            .await
    }

    /// `POST …/parameter-sets/{version}/{operation}` (`forward` or
    /// `compensate`); `version = None` asks for the latest.
    pub async fn evaluate(
        &self,
        serial: &str,
        version: Option<i64>,
        operation: &str,
        body: &Value,
    ) -> Result<Value, ClientError> {
        let version = version.map_or("latest".to_string(), |v| v.to_string());
        self.send(
            self.request(
                reqwest::Method::POST,
                &format!("/v1/robots/{serial}/parameter-sets/{version}/{operation}"),
            )
            .json(body),
        )
        .await
    }

    pub async fn create_session(&self, serial: &str, body: &Value) -> Result<String, ClientError> {
        let created = self
            .send(
                self.request(
                    reqwest::Method::POST,
                    &format!("/v1/robots/{serial}/sessions"),
                )
                .json(body),
            )
            .await?;
        id_of(&created, "id")
    }

    /// Streams a zip archive from disk (never whole in memory).
    pub async fn upload_dataset(&self, session_id: &str, zip: &Path) -> Result<Value, ClientError> {
        let file = tokio::fs::File::open(zip)
            .await
            .map_err(|e| ClientError::Local(format!("{}: {e}", zip.display())))?;
        let length = file
            .metadata()
            .await
            .map_err(|e| ClientError::Local(e.to_string()))?
            .len();
        let body = reqwest::Body::wrap_stream(tokio_util::io::ReaderStream::new(file));
        self.send(
            self.request(
                reqwest::Method::POST,
                &format!("/v1/sessions/{session_id}/dataset"),
            )
            .header(reqwest::header::CONTENT_TYPE, "application/zip")
            .header(reqwest::header::CONTENT_LENGTH, length)
            .timeout(UPLOAD_TIMEOUT)
            .body(body),
        )
        .await
    }

    pub async fn start_calibration(
        &self,
        session_id: &str,
        options: &Value,
    ) -> Result<String, ClientError> {
        let accepted = self
            .send(
                self.request(
                    reqwest::Method::POST,
                    &format!("/v1/sessions/{session_id}/calibrations"),
                )
                .json(options),
            )
            .await?;
        id_of(&accepted, "job_id")
    }

    pub async fn job(&self, job_id: &str) -> Result<Value, ClientError> {
        self.send(self.request(reqwest::Method::GET, &format!("/v1/jobs/{job_id}")))
            .await
    }

    /// One page of `GET /v1/jobs` (newest first).
    pub async fn jobs(&self, limit: u32, cursor: Option<&str>) -> Result<Value, ClientError> {
        let mut query = vec![("limit", limit.to_string())];
        if let Some(cursor) = cursor {
            query.push(("cursor", cursor.to_string()));
        }
        self.send(self.request(reqwest::Method::GET, "/v1/jobs").query(&query))
            .await
    }

    /// A parameter set exported (`urdf`, `dh-json`, `csv`): the raw bytes.
    pub async fn export(
        &self,
        serial: &str,
        version: Option<i64>,
        format: &str,
    ) -> Result<Vec<u8>, ClientError> {
        let version = version.map_or("latest".to_string(), |v| v.to_string());
        let path = format!("/v1/robots/{serial}/parameter-sets/{version}/export");
        let response = self
            .request(reqwest::Method::GET, &path)
            .query(&[("format", format)])
            .send()
            .await?;
        if response.status().is_success() {
            return Ok(response.bytes().await?.to_vec());
        }
        // A refusal is problem+json: read it as every other call does.
        let again = self
            .request(reqwest::Method::GET, &path)
            .query(&[("format", format)]);
        self.send(again).await.map(|_| Vec::new())
    }

    /// `POST /v1/robots/{serial}/campaign-plans`: the plan document.
    pub async fn create_campaign_plan(
        &self,
        serial: &str,
        body: &Value,
    ) -> Result<Value, ClientError> {
        self.send(
            self.request(
                reqwest::Method::POST,
                &format!("/v1/robots/{serial}/campaign-plans"),
            )
            .json(body),
        )
        .await
    }

    /// A stored campaign plan in `format` (`json`, `csv`, `urscript`,
    /// `rapid`, `krl`): the raw bytes.
    pub async fn campaign_plan(
        &self,
        serial: &str,
        id: &str,
        format: &str,
    ) -> Result<Vec<u8>, ClientError> {
        let path = format!("/v1/robots/{serial}/campaign-plans/{id}");
        let response = self
            .request(reqwest::Method::GET, &path)
            .query(&[("format", format)])
            .send()
            .await?;
        if response.status().is_success() {
            return Ok(response.bytes().await?.to_vec());
        }
        let again = self
            .request(reqwest::Method::GET, &path)
            .query(&[("format", format)]);
        self.send(again).await.map(|_| Vec::new())
    }

    /// `version = None` asks for the latest.
    pub async fn report(&self, serial: &str, version: Option<i64>) -> Result<Report, ClientError> {
        let version = version.map_or("latest".to_string(), |v| v.to_string());
        let body = self
            .send(self.request(
                reqwest::Method::GET,
                &format!("/v1/robots/{serial}/parameter-sets/{version}/report"),
            ))
            .await?;
        serde_json::from_value(body)
            .map_err(|e| ClientError::Local(format!("unexpected report shape: {e}")))
    }
}

fn id_of(body: &Value, key: &str) -> Result<String, ClientError> {
    body.get(key)
        .and_then(Value::as_str)
        .map(str::to_string)
        .ok_or_else(|| ClientError::Local(format!("the server's answer has no `{key}`")))
}
