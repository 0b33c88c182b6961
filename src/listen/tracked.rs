//! The per-connection service: hands each request its connection
//! ([`ConnRef`], a request extension, for the reserved lane and event
//! streams) and marks the connection busy until the answer is fully sent,
//! so only idle connections are ever displaced.

use std::convert::Infallible;
use std::future::Future;
use std::pin::Pin;
use std::task::{Context, Poll};

use axum::body::{Body, Bytes, HttpBody};
use axum::Router;
use http_body::Frame;
use hyper::body::Incoming;
use hyper::{Request, Response};
use hyper_util::service::TowerToHyperService;

use super::registry::{BusyGuard, ConnRef};

#[derive(Clone)]
pub struct Tracked {
    inner: TowerToHyperService<Router>,
    conn: ConnRef,
}

impl Tracked {
    pub fn new(app: Router, conn: ConnRef) -> Tracked {
        Tracked {
            inner: TowerToHyperService::new(app),
            conn,
        }
    }
}

type BoxFuture = Pin<Box<dyn Future<Output = Result<Response<Body>, Infallible>> + Send>>;

impl hyper::service::Service<Request<Incoming>> for Tracked {
    type Response = Response<Body>;
    type Error = Infallible;
    type Future = BoxFuture;

    fn call(&self, mut req: Request<Incoming>) -> BoxFuture {
        let busy = self.conn.begin_request();
        req.extensions_mut().insert(self.conn.clone());
        let answer = self.inner.call(req);
        Box::pin(async move {
            let response = answer.await?;
            Ok(response.map(|body| {
                Body::new(BusyBody {
                    inner: body,
                    _busy: busy,
                })
            }))
        })
    }
}

/// An answer's body that keeps its connection busy until sent (or dropped).
struct BusyBody {
    inner: Body,
    _busy: BusyGuard,
}

impl HttpBody for BusyBody {
    type Data = Bytes;
    type Error = axum::Error;

    fn poll_frame(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<Frame<Bytes>, axum::Error>>> {
        Pin::new(&mut self.inner).poll_frame(cx)
    }

    fn is_end_stream(&self) -> bool {
        self.inner.is_end_stream()
    }

    fn size_hint(&self) -> http_body::SizeHint {
        self.inner.size_hint()
    }
}
