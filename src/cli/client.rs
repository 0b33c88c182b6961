//! The CLI's HTTP client: a thin typed layer over the REST contract
//! (api.md) for `robocal upload`, `calibrate` and `report`. Problem+json
//! answers become [`ClientError::Problem`] with the server's own words.
//! Answers are read into the types the caller names, or handed over as the
//! server's text where the CLI prints them as they are.

use std::path::Path;
use std::time::Duration;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

pub use super::client_error::ClientError;
use crate::report::Report;

/// The id of what a request created.
#[derive(Debug, Deserialize)]
struct Created {
    id: Option<String>,
}

/// The job a calibration request queued.
#[derive(Debug, Deserialize)]
struct Accepted {
    job_id: Option<String>,
}

/// How many poses a dataset upload stored.
#[derive(Debug, Deserialize)]
pub struct DatasetStored {
    #[serde(default)]
    pub poses_created: u64,
    /// Dots found per image at upload.
    #[serde(default)]
    pub detected_points: Vec<u64>,
    /// What the server warns of (e.g. no image shows the session's target).
    #[serde(default)]
    pub warnings: Vec<String>,
}

/// The media type of a streamed answer: one JSON document per line.
const NDJSON: &str = "application/x-ndjson";

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

    /// The answer's body as the server wrote it, or its problem+json as a
    /// [`ClientError::Problem`].
    async fn send_text(&self, builder: reqwest::RequestBuilder) -> Result<String, ClientError> {
        let response = builder.send().await?;
        let status = response.status();
        let body = response.text().await.unwrap_or_default();
        if status.is_success() {
            return Ok(body);
        }
        Err(ClientError::of_problem(status.as_u16(), &body))
    }

    /// The answer read as `T`.
    async fn send<T: DeserializeOwned>(
        &self,
        builder: reqwest::RequestBuilder,
    ) -> Result<T, ClientError> {
        let text = self.send_text(builder).await?;
        answer_of(&text)
    }

    pub async fn put_robot(&self, serial: &str, body: &impl Serialize) -> Result<(), ClientError> {
        self.send_text(
            self.request(reqwest::Method::PUT, &format!("/v1/robots/{serial}"))
                .json(body),
        )
        .await
        .map(drop)
    }

    /// Whether the server has a robot of that serial.
    pub async fn robot_exists(&self, serial: &str) -> Result<bool, ClientError> {
        match self
            .send_text(self.request(reqwest::Method::GET, &format!("/v1/robots/{serial}")))
            .await
        {
            Ok(_) => Ok(true),
            Err(ClientError::Problem { status: 404, .. }) => Ok(false),
            Err(e) => Err(e),
        }
    }

    /// The session, read as the fields `T` names.
    pub async fn get_session<T: DeserializeOwned>(
        &self,
        session_id: &str,
    ) -> Result<T, ClientError> {
        self.send(self.request(reqwest::Method::GET, &format!("/v1/sessions/{session_id}")))
            .await
    }

    /// `POST …/parameter-sets/{version}/{operation}` (`forward`,
    /// `compensate` or `filter`); `version = None` asks for the latest. The
    /// answer as the server wrote it.
    pub async fn evaluate(
        &self,
        serial: &str,
        version: Option<i64>,
        operation: &str,
        body: &impl Serialize,
    ) -> Result<String, ClientError> {
        let version = version.map_or("latest".to_string(), |v| v.to_string());
        self.send_text(
            self.request(
                reqwest::Method::POST,
                &format!("/v1/robots/{serial}/parameter-sets/{version}/{operation}"),
            )
            .json(body),
        )
        .await
    }

    /// `compensate` or `filter` streamed (`Accept: application/x-ndjson`):
    /// `on_line` gets each answer line (one target) as it arrives, so a long
    /// target list is printed as it is solved and never held whole.
    pub async fn evaluate_lines(
        &self,
        serial: &str,
        version: Option<i64>,
        operation: &str,
        body: &impl Serialize,
        mut on_line: impl FnMut(&str) -> Result<(), ClientError>,
    ) -> Result<(), ClientError> {
        let version = version.map_or("latest".to_string(), |v| v.to_string());
        let mut response = self
            .request(
                reqwest::Method::POST,
                &format!("/v1/robots/{serial}/parameter-sets/{version}/{operation}"),
            )
            .header(reqwest::header::ACCEPT, NDJSON)
            .json(body)
            .send()
            .await?;
        let status = response.status();
        if !status.is_success() {
            let body = response.text().await.unwrap_or_default();
            return Err(ClientError::of_problem(status.as_u16(), &body));
        }
        let mut pending = Vec::new();
        while let Some(chunk) = response.chunk().await? {
            pending.extend_from_slice(&chunk);
            while let Some(end) = memchr::memchr(b'\n', &pending) {
                let line: Vec<u8> = pending.drain(..=end).collect();
                let line = std::str::from_utf8(&line).map_err(|e| {
                    ClientError::Local(format!("unexpected answer from the server: {e}"))
                })?;
                on_line(line.trim_end())?;
            }
        }
        if pending.iter().any(|b| !b.is_ascii_whitespace()) {
            return Err(ClientError::Local(
                "the server's answer ended in the middle of a line".into(),
            ));
        }
        Ok(())
    }

    pub async fn create_session(
        &self,
        serial: &str,
        body: &impl Serialize,
    ) -> Result<String, ClientError> {
        let created: Created = self
            .send(
                self.request(
                    reqwest::Method::POST,
                    &format!("/v1/robots/{serial}/sessions"),
                )
                .json(body),
            )
            .await?;
        created.id.ok_or_else(|| no_field("id"))
    }

    /// Streams a zip archive from disk (never whole in memory).
    pub async fn upload_dataset(
        &self,
        session_id: &str,
        zip: &Path,
    ) -> Result<DatasetStored, ClientError> {
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
        options: &impl Serialize,
    ) -> Result<String, ClientError> {
        let accepted: Accepted = self
            .send(
                self.request(
                    reqwest::Method::POST,
                    &format!("/v1/sessions/{session_id}/calibrations"),
                )
                .json(options),
            )
            .await?;
        accepted.job_id.ok_or_else(|| no_field("job_id"))
    }

    /// The job document as the server wrote it.
    pub async fn job(&self, job_id: &str) -> Result<String, ClientError> {
        self.send_text(self.request(reqwest::Method::GET, &format!("/v1/jobs/{job_id}")))
            .await
    }

    /// One page of `GET /v1/jobs` (newest first), read as `T`; `filters`
    /// are its query filters (`serial`, `state`, `kind`).
    pub async fn jobs<T: DeserializeOwned>(
        &self,
        limit: u32,
        cursor: Option<&str>,
        filters: &[(&str, String)],
    ) -> Result<T, ClientError> {
        let mut query = vec![("limit", limit.to_string())];
        if let Some(cursor) = cursor {
            query.push(("cursor", cursor.to_string()));
        }
        query.extend(filters.iter().map(|(k, v)| (*k, v.clone())));
        self.send(self.request(reqwest::Method::GET, "/v1/jobs").query(&query))
            .await
    }

    /// Any JSON request of the contract (`body` sent as JSON when given):
    /// the answer's text, or its problem+json as an error.
    pub async fn call(
        &self,
        method: reqwest::Method,
        path: &str,
        body: Option<&serde_json::Value>,
    ) -> Result<String, ClientError> {
        let mut builder = self.request(method, path);
        if let Some(body) = body {
            builder = builder.json(body);
        }
        self.send_text(builder).await
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
        self.send_text(again).await.map(|_| Vec::new())
    }

    /// `POST /v1/robots/{serial}/campaign-plans` with a JSON request as
    /// the user wrote it: the plan document, read as `T`.
    pub async fn create_campaign_plan<T: DeserializeOwned>(
        &self,
        serial: &str,
        request_json: String,
    ) -> Result<T, ClientError> {
        self.send(
            self.request(
                reqwest::Method::POST,
                &format!("/v1/robots/{serial}/campaign-plans"),
            )
            .header(reqwest::header::CONTENT_TYPE, "application/json")
            .body(request_json),
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
        self.send_text(again).await.map(|_| Vec::new())
    }

    /// `version = None` asks for the latest.
    pub async fn report(&self, serial: &str, version: Option<i64>) -> Result<Report, ClientError> {
        let version = version.map_or("latest".to_string(), |v| v.to_string());
        self.send(self.request(
            reqwest::Method::GET,
            &format!("/v1/robots/{serial}/parameter-sets/{version}/report"),
        ))
        .await
    }
}

/// A successful answer's text read as `T`.
pub fn answer_of<T: DeserializeOwned>(text: &str) -> Result<T, ClientError> {
    serde_json::from_str(text)
        .map_err(|e| ClientError::Local(format!("unexpected answer from the server: {e}")))
}

fn no_field(key: &str) -> ClientError {
    ClientError::Local(format!("the server's answer has no `{key}`"))
}
