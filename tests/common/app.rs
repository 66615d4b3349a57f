//! [`TestApp`]: a server's route table called in process with `tower::ServiceExt::oneshot`,
//! for tests of HTTP requests and answers that need no socket (no websocket, no connection
//! limits, no peer other than loopback). Each request seems to come from `127.0.0.1`, as a
//! [`TestServer`](super::TestServer)'s client does; the methods are that server's.

use std::net::SocketAddr;
use std::path::{Path, PathBuf};

use axum::Router;
use axum::body::{Body, Bytes};
use axum::extract::ConnectInfo;
use axum::http::{HeaderMap, Method, Request, StatusCode, header};
use docent::serve::{ServeOptions, Server};
use serde_json::Value;
use tower::ServiceExt;

use super::{DEADLINE, OPERATOR_TOKEN, read_corpus, within};

/// A started server whose routes are called without a listener.
pub struct TestApp {
    server: Server,
    router: Router,
    /// The corpus folder (absolute).
    pub corpus: PathBuf,
    pub corpus_dir: tempfile::TempDir,
}

/// An answer: status, headers and body.
pub struct Answer {
    pub status: StatusCode,
    pub headers: HeaderMap,
    pub body: Bytes,
}

impl Answer {
    /// The body as JSON (`Null` when it is not JSON).
    pub fn json(&self) -> Value {
        serde_json::from_slice(&self.body).unwrap_or(Value::Null)
    }

    /// The body as text.
    pub fn text(&self) -> &str {
        std::str::from_utf8(&self.body).expect("a UTF-8 body")
    }

    /// A header's value as text, empty when absent.
    pub fn header(&self, name: &str) -> &str {
        (self.headers.get(name))
            .and_then(|v| v.to_str().ok())
            .unwrap_or_default()
    }
}

impl TestApp {
    /// Serves `bundle` with seed 1.
    pub async fn start(bundle: &Path) -> Self {
        Self::start_with(bundle, |_| {}).await
    }

    /// Serves `bundle`, letting the test adjust the options.
    pub async fn start_with(bundle: &Path, adjust: impl FnOnce(&mut ServeOptions)) -> Self {
        let (server, corpus_dir) = super::start_server(bundle, adjust);
        TestApp {
            router: server.router(),
            corpus: server.corpus_path(),
            server,
            corpus_dir,
        }
    }

    /// The server (its state, start-up warnings).
    pub fn server(&self) -> &Server {
        &self.server
    }

    /// Sends `request` through the route table, from a loopback peer.
    pub async fn send(&self, mut request: Request<Body>) -> Answer {
        let peer = SocketAddr::from(([127, 0, 0, 1], 40000));
        request.extensions_mut().insert(ConnectInfo(peer));
        let answer = within(DEADLINE, self.router.clone().oneshot(request))
            .await
            .expect("an answer within the deadline")
            .expect("the router never fails");
        let (parts, body) = answer.into_parts();
        let body = within(DEADLINE, axum::body::to_bytes(body, usize::MAX))
            .await
            .expect("a body within the deadline")
            .expect("a body");
        Answer {
            status: parts.status,
            headers: parts.headers,
            body,
        }
    }

    /// A request of `method` to `path`, with `token` as bearer credential (none when `None`)
    /// and a JSON body when given.
    pub async fn call(
        &self,
        method: Method,
        path: &str,
        body: Option<Value>,
        token: Option<&str>,
    ) -> Answer {
        let mut request = Request::builder().method(method).uri(path);
        if let Some(token) = token {
            request = request.header(header::AUTHORIZATION, format!("Bearer {token}"));
        }
        let body = match body {
            Some(json) => {
                request = request.header(header::CONTENT_TYPE, "application/json");
                Body::from(json.to_string())
            }
            None => Body::empty(),
        };
        self.send(request.body(body).expect("a request")).await
    }

    /// GET without a credential, with these headers (a browser's `Accept`, a `Referer`).
    pub async fn get_with(&self, path: &str, headers: &[(&str, &str)]) -> Answer {
        let mut request = Request::builder().method(Method::GET).uri(path);
        for (name, value) in headers {
            request = request.header(*name, *value);
        }
        self.send(request.body(Body::empty()).expect("a request"))
            .await
    }

    /// GET with the operator credential, returning status and JSON body.
    pub async fn get(&self, path: &str) -> (u16, Value) {
        let answer = self
            .call(Method::GET, path, None, Some(OPERATOR_TOKEN))
            .await;
        (answer.status.as_u16(), answer.json())
    }

    /// POST JSON (or nothing) with the operator credential, returning status and JSON body.
    pub async fn post(&self, path: &str, body: Option<Value>) -> (u16, Value) {
        self.post_with(path, body, Some(OPERATOR_TOKEN)).await
    }

    /// POST JSON (or nothing) with `token` as bearer credential (none when `None`).
    pub async fn post_with(
        &self,
        path: &str,
        body: Option<Value>,
        token: Option<&str>,
    ) -> (u16, Value) {
        let answer = self.call(Method::POST, path, body, token).await;
        (answer.status.as_u16(), answer.json())
    }

    /// PUT JSON with the operator credential.
    pub async fn put(&self, path: &str, body: Value) -> (u16, Value) {
        let answer = (self.call(Method::PUT, path, Some(body), Some(OPERATOR_TOKEN))).await;
        (answer.status.as_u16(), answer.json())
    }

    /// Triggers `label` over HTTP, expecting 202.
    pub async fn trigger(&self, label: &str, body: Value) -> Value {
        let (status, body) = self
            .post(&format!("/api/acts/{label}/trigger"), Some(body))
            .await;
        assert_eq!(status, 202, "trigger {label}: {body}");
        body
    }

    /// Stops the server as `docent serve` stops and returns every corpus line.
    pub async fn stop(self) -> Vec<Value> {
        let TestApp {
            server,
            router,
            corpus,
            corpus_dir,
        } = self;
        drop(router);
        within(DEADLINE, server.stop())
            .await
            .expect("shutdown in time")
            .expect("stopped");
        let lines = read_corpus(&corpus);
        drop(corpus_dir);
        lines
    }
}
