//! Test helpers: a real Docent server on `127.0.0.1:0`, HTTP and websocket clients, the same
//! server's routes called in process without a socket (`app.rs`, [`TestApp`]), temporary
//! bundles, and reading the corpus log. Waiting is always for an event, with a generous
//! deadline only so that a broken build fails instead of hanging.

#![allow(dead_code)] // `tests/flood.rs`, a binary of its own, uses a small part of them.

pub mod app;
pub mod channels;
pub mod check;
pub mod corpus;
pub mod languages;
pub mod load;
pub mod mac_copy;
pub mod mount;
pub mod process;

#[allow(unused_imports)] // As `dead_code` above.
pub use app::TestApp;
#[allow(unused_imports)] // As `dead_code` above.
pub use corpus::{corpus_text, json_lines, read_corpus, session_dirs};

use std::path::{Path, PathBuf};
use std::time::Duration;

use docent::access::{AccessMode, Credentials, Secret};
use docent::content::load_bundle;
use docent::serve::{ServeOptions, Server, run};
use futures_util::{SinkExt, StreamExt};
use serde_json::{Value, json};
use tokio::net::TcpStream;
use tokio::sync::oneshot;
use tokio::task::JoinHandle;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream, connect_async};

/// The operator credential of every test server (unless a test sets another).
pub const OPERATOR_TOKEN: &str = "test-operator-credential";
/// The dialog-manager credential of every test server.
pub const DM_TOKEN: &str = "test-dialog-manager-credential";

/// The access mode test servers run with: guarded by the two test credentials.
pub fn test_access() -> AccessMode {
    AccessMode::Guarded(Credentials {
        operator: Secret::new(OPERATOR_TOKEN),
        dm: Secret::new(DM_TOKEN),
    })
}

/// How long any single wait may take before the test fails.
pub const DEADLINE: Duration = Duration::from_secs(20);

/// The repository root.
pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A bundle shipped in `dialogs/` or `tests/fixtures/`.
pub fn bundle(path: &str) -> PathBuf {
    repo().join(path)
}

/// A bundle written into a temporary folder.
pub struct TempBundle {
    pub dir: tempfile::TempDir,
}

impl TempBundle {
    /// A bundle with this acts file and no other files.
    pub fn new(acts: &str) -> Self {
        let dir = tempfile::tempdir().expect("temp dir");
        std::fs::write(dir.path().join("acts.yaml"), acts).expect("write acts");
        std::fs::create_dir_all(dir.path().join("pages")).expect("pages");
        std::fs::create_dir_all(dir.path().join("media")).expect("media");
        std::fs::write(
            dir.path().join("pages/index.html"),
            "<!doctype html><title>home</title>",
        )
        .expect("home");
        TempBundle { dir }
    }

    /// Adds or replaces a file.
    pub fn with_file(self, rel: &str, contents: &str) -> Self {
        let path = self.dir.path().join(rel);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("mkdir");
        std::fs::write(path, contents).expect("write");
        self
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        self.dir.path()
    }
}

/// The server for `bundle`, with seed 1, the test credentials and a fresh corpus folder (kept
/// while the returned folder lives), after `adjust` changed the options.
pub fn start_server(
    bundle: &Path,
    adjust: impl FnOnce(&mut ServeOptions),
) -> (Server, tempfile::TempDir) {
    let report = load_bundle(bundle);
    let loaded = report
        .bundle
        .unwrap_or_else(|| panic!("bundle has errors: {:#?}", report.diagnostics));
    let corpus_dir = tempfile::tempdir().expect("corpus dir");
    let mut options = ServeOptions {
        seed: Some(1),
        corpus_dir: corpus_dir.path().to_owned(),
        corpus_sync: docent::corpus::DEFAULT_SYNC_INTERVAL,
        speech_wav: None,
        access: test_access(),
        limits: None,
        media_cache: corpus_dir.path().join("media-cache"),
        media_tools: docent::media::Tools::find(),
    };
    adjust(&mut options);
    let server = Server::start(loaded, &options).expect("server starts");
    (server, corpus_dir)
}

/// A running server.
pub struct TestServer {
    pub addr: std::net::SocketAddr,
    /// The corpus folder (absolute).
    pub corpus: PathBuf,
    pub corpus_dir: tempfile::TempDir,
    shutdown: Option<oneshot::Sender<()>>,
    task: Option<JoinHandle<std::io::Result<()>>>,
    http: reqwest::Client,
}

impl TestServer {
    /// Serves `bundle` with seed 1.
    pub async fn start(bundle: &Path) -> Self {
        Self::start_with(bundle, |_| {}).await
    }

    /// Serves `bundle`, letting the test adjust the options.
    pub async fn start_with(bundle: &Path, adjust: impl FnOnce(&mut ServeOptions)) -> Self {
        Self::start_prepared(bundle, adjust, |_| {}).await
    }

    /// Serves `bundle` with adjusted options, letting the test prepare the started server
    /// before it serves (e.g. watch the bundle).
    pub async fn start_prepared(
        bundle: &Path,
        adjust: impl FnOnce(&mut ServeOptions),
        prepare: impl FnOnce(&Server),
    ) -> Self {
        let (server, corpus_dir) = start_server(bundle, adjust);
        prepare(&server);
        let corpus = server.corpus_path();
        let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
            .await
            .expect("bind");
        let addr = listener.local_addr().expect("addr");
        let (tx, rx) = oneshot::channel::<()>();
        let task = tokio::spawn(run(listener, server, async move {
            let _ = rx.await;
        }));
        TestServer {
            addr,
            corpus,
            corpus_dir,
            shutdown: Some(tx),
            task: Some(task),
            http: reqwest::Client::new(),
        }
    }

    /// `http://addr/path`
    pub fn url(&self, path: &str) -> String {
        format!("http://{}{}", self.addr, path)
    }

    /// GET with the operator credential, returning status and JSON body.
    pub async fn get(&self, path: &str) -> (u16, Value) {
        let request = self.http.get(self.url(path)).bearer_auth(OPERATOR_TOKEN);
        let r = request.send().await.expect("GET");
        let status = r.status().as_u16();
        (status, r.json().await.unwrap_or(Value::Null))
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
        let mut req = self.http.post(self.url(path));
        if let Some(token) = token {
            req = req.bearer_auth(token);
        }
        if let Some(body) = body {
            req = req.json(&body);
        }
        let r = req.send().await.expect("POST");
        let status = r.status().as_u16();
        (status, r.json().await.unwrap_or(Value::Null))
    }

    /// PUT JSON.
    pub async fn put(&self, path: &str, body: Value) -> (u16, Value) {
        let r = self
            .http
            .put(self.url(path))
            .bearer_auth(OPERATOR_TOKEN)
            .json(&body)
            .send()
            .await
            .expect("PUT");
        let status = r.status().as_u16();
        (status, r.json().await.unwrap_or(Value::Null))
    }

    /// Triggers `label` over HTTP, expecting 202.
    pub async fn trigger(&self, label: &str, body: Value) -> Value {
        let (status, body) = self
            .post(&format!("/api/acts/{label}/trigger"), Some(body))
            .await;
        assert_eq!(status, 202, "trigger {label}: {body}");
        body
    }

    /// A websocket client that has said hello with `hello` and read its welcome. Operator
    /// and dialog-manager hellos without a `token` get the test credential of their role.
    pub async fn client(&self, mut hello: Value) -> WsClient {
        let token = match hello["role"].as_str() {
            Some("operator") => Some(OPERATOR_TOKEN),
            Some("dm") => Some(DM_TOKEN),
            _ => None,
        };
        if let (Some(token), None) = (token, hello.get("token")) {
            hello["token"] = token.into();
        }
        let mut c = self.connect().await;
        c.send(hello).await;
        let welcome = c.recv_type("welcome").await;
        c.welcome = welcome;
        c
    }

    /// A websocket client that has said nothing yet.
    pub async fn connect(&self) -> WsClient {
        WsClient::connect(&format!("ws://{}/ws", self.addr)).await
    }

    /// An operator client (receives every event).
    pub async fn operator(&self) -> WsClient {
        self.client(json!({"type": "hello", "role": "operator", "name": "test"}))
            .await
    }

    /// Shuts down gracefully and returns every corpus line.
    pub async fn stop(mut self) -> Vec<Value> {
        if let Some(tx) = self.shutdown.take() {
            let _ = tx.send(());
        }
        if let Some(task) = self.task.take() {
            within(DEADLINE, task)
                .await
                .expect("shutdown in time")
                .expect("join")
                .expect("run");
        }
        read_corpus(&self.corpus)
    }
}

/// `fut`'s output, or `Err` after `limit` of real time. Not `tokio::time::timeout`: under a
/// paused clock (`start_paused`), tokio moves time on whenever the runtime waits, also while
/// it waits on a thread it cannot see (the corpus writer), so a tokio deadline can pass in no
/// real time at all. A real-time deadline leaves the paused clock to the server's own timers.
pub async fn within<F: Future>(limit: Duration, fut: F) -> Result<F::Output, Elapsed> {
    tokio::select! {
        out = fut => Ok(out),
        () = futures_timer::Delay::new(limit) => Err(Elapsed(limit)),
    }
}

/// A real-time deadline passed ([`within`]).
#[derive(Debug)]
pub struct Elapsed(pub Duration);

/// A raw websocket client speaking JSON frames.
pub struct WsClient {
    stream: WebSocketStream<MaybeTlsStream<TcpStream>>,
    pub welcome: Value,
}

impl WsClient {
    /// An operator signed in to the server at `addr` (`host:port`), after its `welcome`.
    pub async fn operator_at(addr: &str) -> Self {
        let mut op = WsClient::connect(&format!("ws://{addr}/ws")).await;
        op.send(json!({"type": "hello", "role": "operator", "token": OPERATOR_TOKEN}))
            .await;
        op.welcome = op.recv_type("welcome").await;
        op
    }

    /// Connects without saying anything.
    pub async fn connect(url: &str) -> Self {
        let (stream, _) = connect_async(url).await.expect("websocket connects");
        WsClient {
            stream,
            welcome: Value::Null,
        }
    }

    /// Sends a JSON frame.
    pub async fn send(&mut self, frame: Value) {
        self.send_text(&frame.to_string()).await;
    }

    /// Sends a raw text frame.
    pub async fn send_text(&mut self, text: &str) {
        self.stream.send(Message::text(text)).await.expect("send");
    }

    /// Sends a raw message.
    pub async fn send_message(&mut self, message: Message) {
        self.stream.send(message).await.expect("send");
    }

    /// The next JSON frame.
    pub async fn recv(&mut self) -> Value {
        loop {
            let msg = within(DEADLINE, self.stream.next())
                .await
                .expect("a frame within the deadline")
                .expect("connection open")
                .expect("frame");
            match msg {
                Message::Text(t) => return serde_json::from_str(&t).expect("JSON frame"),
                Message::Close(c) => panic!("connection closed: {c:?}"),
                _ => continue,
            }
        }
    }

    /// Every JSON frame until the server closes the connection.
    pub async fn frames_until_closed(&mut self) -> Vec<Value> {
        let mut frames = Vec::new();
        loop {
            let next = within(DEADLINE, self.stream.next())
                .await
                .expect("the server closes within the deadline");
            match next {
                Some(Ok(Message::Text(t))) => {
                    frames.push(serde_json::from_str(&t).expect("JSON frame"));
                }
                Some(Ok(Message::Close(_))) | None | Some(Err(_)) => return frames,
                Some(Ok(_)) => {}
            }
        }
    }

    /// The next frame of `type`, skipping others.
    pub async fn recv_type(&mut self, kind: &str) -> Value {
        self.recv_where(|f| f["type"] == kind).await
    }

    /// The next frame matching `pred`, skipping others, within one deadline for the whole
    /// search (frames that do not match, such as other events, do not extend it).
    pub async fn recv_where(&mut self, pred: impl Fn(&Value) -> bool) -> Value {
        let search = async {
            loop {
                let frame = self.recv().await;
                if pred(&frame) {
                    return frame;
                }
            }
        };
        within(DEADLINE, search)
            .await
            .expect("a matching frame within the deadline")
    }

    /// The next event (operator clients) matching `pred`.
    pub async fn event_where(&mut self, pred: impl Fn(&Value) -> bool) -> Value {
        self.recv_where(|f| f["type"] == "event" && pred(&f["event"]))
            .await["event"]
            .clone()
    }

    /// The next event of type `kind`.
    pub async fn event(&mut self, kind: &str) -> Value {
        self.event_where(|e| e["type"] == kind).await
    }

    /// Events up to and including the first matching `pred`.
    pub async fn events_until(&mut self, pred: impl Fn(&Value) -> bool) -> Vec<Value> {
        let mut seen = Vec::new();
        let search = async {
            loop {
                let frame = self.recv_type("event").await;
                let event = frame["event"].clone();
                let last = pred(&event);
                seen.push(event);
                if last {
                    return;
                }
            }
        };
        within(DEADLINE, search)
            .await
            .expect("the awaited event within the deadline");
        seen
    }
}
