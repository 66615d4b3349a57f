//! Starting and running a server: [`Server::start`] wires a checked bundle to its adapters,
//! dispatcher and corpus writer; [`run`] serves HTTP and websockets on a listener the caller
//! bound (tests bind `127.0.0.1:0`), within the connection limits (`http::connections`),
//! until the shutdown future completes, then winds down: connections closed, tasks awaited,
//! the corpus flushed last.

use std::future::Future;
use std::io;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use tokio::net::TcpListener;

use crate::access::{Access, AccessMode, TrustedProxies};
use crate::adapters::{Devices, SpeechOutput, speech_adapter};
use crate::content::config::ServerLimits;
use crate::content::{Bundle, BundleArea, resolve_in_bundle};
use crate::corpus::CorpusWriter;
use crate::dispatch::Dispatcher;
use crate::events::{EventKind, Hub, SessionEnd, Source, StopReason};
use crate::http::{ConnectionLimits, app, make_room, serve_connections};
use crate::lifecycle::Lifecycle;
use crate::media::Media;
use crate::reload::ReloadOptions;
use crate::robot::RobotInbox;
use crate::state::{AppState, Limits};

/// Threads tokio may start for blocking work (tower-http's file reads, recording chunks with
/// their `fsync`, exports, reports), beyond its workers; tokio's default is 512. Disk work
/// does not go faster with more threads than this, and each thread keeps its own stack and
/// allocator arena for as long as it lives: with 50 kiosks uploading recordings the server
/// held 50 of them, and its memory grew through a day of reloads (bench/README.md, "Soak").
/// Work beyond the limit waits in tokio's queue.
pub const BLOCKING_THREADS: usize = 8;

/// How long shutdown waits for connections and adapters to finish.
const SHUTDOWN_GRACE: Duration = Duration::from_secs(5);

/// What `docent serve` was asked for, beyond the bundle itself.
#[derive(Clone, Debug)]
pub struct ServeOptions {
    /// Seed for the choice of alternatives; random when absent.
    pub seed: Option<u64>,
    /// Folder for the corpus log.
    pub corpus_dir: PathBuf,
    /// How often the corpus log is synced to disk ([`crate::corpus::DEFAULT_SYNC_INTERVAL`]).
    pub corpus_sync: Duration,
    /// Write espeak-ng speech as WAV files into this folder instead of playing it.
    pub speech_wav: Option<PathBuf>,
    /// Credentials for operators and dialog managers, or an open development server.
    pub access: AccessMode,
    /// Time limits for slow clients and caps on connections instead of the bundle's
    /// (`server:` in `docent.yaml`); `None`: the bundle's. Tests use it for limits no file
    /// may write (a header time limit of 300 ms).
    pub limits: Option<ConnectionLimits>,
    /// The media cache: converted media files ([`crate::media`]).
    pub media_cache: PathBuf,
    /// The converters media files are converted with ([`crate::media::Tools::find`] on `PATH`).
    pub media_tools: crate::media::Tools,
}

/// A server ready to run.
pub struct Server {
    state: AppState,
    corpus: CorpusWriter,
    limits: ConnectionLimits,
    /// Start-up warnings for the person starting it (e.g. espeak-ng missing).
    pub warnings: Vec<String>,
}

impl Server {
    /// Starts the corpus writer, adapters and dispatcher for `bundle`.
    pub fn start(mut bundle: Bundle, options: &ServeOptions) -> io::Result<Server> {
        let life = Lifecycle::new();
        let (hub, feed) = Hub::new();
        let corpus = CorpusWriter::start(&options.corpus_dir, feed, options.corpus_sync)?;
        let mut warnings = Vec::new();
        let limits = limits_in_force(&bundle.config.server.limits, options.limits, &mut warnings);
        // Before this run records anything: a crash may have left bytes no kiosk was told are
        // stored.
        let (cuts, problems) = crate::recording::cut_unacknowledged(corpus.dir());
        for cut in cuts {
            warnings.push(format!(
                "{} held {} bytes a crash left unacknowledged; cut back to its last acknowledged chunk",
                cut.file.display(),
                cut.bytes
            ));
        }
        warnings.extend(
            problems
                .into_iter()
                .map(|p| format!("a recording could not be checked: {p}")),
        );
        // Consent is final: media a crash left after a refusal go now, before anyone reads them.
        let (removed, problems) = crate::recording::remove_unconsented(corpus.dir());
        for file in removed {
            warnings.push(format!(
                "{} was removed: its visitors declined or withdrew consent, and a crash had \
                 left it",
                file.display()
            ));
        }
        warnings.extend(problems.into_iter().map(|p| {
            format!("a recording whose visitors withdrew consent could not be removed: {p}; remove it by hand")
        }));
        let output = match &options.speech_wav {
            Some(dir) => {
                std::fs::create_dir_all(dir)?;
                SpeechOutput::Wav(dir.canonicalize()?)
            }
            None => SpeechOutput::Audio,
        };
        let speech = speech_adapter(&bundle.config.speech, &output, &mut warnings);
        // The kiosk starts on the home page only if the bundle has one (`check` warns otherwise).
        let home = Some(bundle.config.home.clone())
            .filter(|h| resolve_in_bundle(&bundle.root, BundleArea::Pages, h).is_ok());
        let (robot_inbox, robot_intake) = RobotInbox::channel();
        let (devices, router) = Devices::start(
            &bundle.config,
            home,
            speech,
            output,
            (&hub, &robot_inbox),
            &life,
        );
        let bundle_hash = crate::content::corpus_fingerprint(&bundle.root);
        bundle.fingerprint = bundle_hash.as_deref().map(Arc::from);
        hub.publish(EventKind::ServerStarted {
            bundle: bundle.root.display().to_string(),
            bundle_hash,
            version: env!("CARGO_PKG_VERSION").into(),
            seed: options.seed,
        });
        let media = Media::start(
            options.media_cache.clone(),
            options.media_tools.clone(),
            hub.clone(),
            &life,
        );
        // A file that cannot be converted here is told in the log at start-up.
        media.plan(&bundle);
        let proxies = TrustedProxies::new(bundle.config.server.trusted_proxies.clone());
        let dispatcher = Dispatcher::new(Arc::new(bundle), router, hub, options.seed, life.clone());
        let access = Access::new(options.access.clone(), proxies);
        let corpus_dir = corpus.dir().to_owned();
        let folders = corpus.session_folders();
        let mut state = AppState::new(
            dispatcher,
            Arc::new(devices),
            life,
            access,
            corpus_dir,
            folders,
        );
        state.media = media;
        state.limits = limits;
        state.life.spawn(crate::ws::tell_media(state.clone()));
        let intake = crate::robot::run_intake(state.clone(), robot_intake);
        state.life.spawn(intake);
        let live = Arc::clone(&state.dispatcher);
        let notices = crate::ws::deliver_notices(
            state.dispatcher.notices(),
            state.links(),
            Arc::clone(&state.captions),
            move || live.bundle().config.captions,
            state.life.shutdown.clone(),
        );
        state.life.spawn(notices);
        Ok(Server {
            state,
            corpus,
            limits: ConnectionLimits::from(&limits.server),
            warnings,
        })
    }

    /// Watches the bundle folder and puts every good save live (see [`crate::reload`]). Call
    /// within the tokio runtime, before [`run`]; without it the bundle stays as started.
    pub fn watch(&self, options: ReloadOptions) {
        crate::reload::watch(&self.state, options);
    }

    /// The shared state (for tests and embedding).
    pub fn state(&self) -> &AppState {
        &self.state
    }

    /// The corpus folder, absolute.
    pub fn corpus_path(&self) -> PathBuf {
        self.corpus.dir().to_owned()
    }

    /// The route table over this server's state, to call in process: tests send it requests
    /// with `tower::ServiceExt::oneshot`, no socket needed. [`run`] serves the same table.
    pub fn router(&self) -> axum::Router {
        app(self.state.clone())
    }

    /// Stops a server that [`run`] is not serving (one called through
    /// [`router`](Self::router)) as `run` stops its own: commands end with their outcomes
    /// logged, tasks finish, the corpus is flushed last.
    pub async fn stop(self) -> io::Result<()> {
        announce_stop(&self.state.dispatcher);
        let closing = Closing::of(&self.state);
        drop(self.state);
        wind_down(closing, self.corpus).await
    }
}

/// Every queued or running command ends first, with its outcome in the log; connections and
/// tasks are told to finish after this.
fn announce_stop(dispatcher: &Dispatcher) {
    dispatcher.hub().publish(EventKind::ServerStopping);
    dispatcher.stop(Source::Server, "the server is shutting down");
}

/// What winding down needs of a server's state, taken before the route table (and with it the
/// rest of the state) is dropped, as `run` always did.
struct Closing {
    /// Not used, only kept: the dispatcher outlives the corpus flush.
    dispatcher: Arc<Dispatcher>,
    life: Lifecycle,
    recordings: Arc<crate::recording::Recordings>,
    visits: Arc<crate::operator::Visits>,
    hub: Hub,
}

impl Closing {
    fn of(state: &AppState) -> Self {
        Closing {
            dispatcher: Arc::clone(&state.dispatcher),
            life: state.life.clone(),
            recordings: Arc::clone(&state.recordings),
            visits: Arc::clone(&state.visits),
            hub: state.hub.clone(),
        }
    }
}

/// After the connections closed: the tasks are awaited, recordings and the visitor session
/// closed, and the corpus flushed last.
async fn wind_down(closing: Closing, corpus: CorpusWriter) -> io::Result<()> {
    let Closing {
        dispatcher: _kept,
        life,
        recordings,
        visits,
        hub,
    } = closing;
    // axum's graceful shutdown does not wait for websocket tasks (tokio-rs/axum#3003).
    life.shutdown.cancel();
    life.tracker.close();
    if tokio::time::timeout(SHUTDOWN_GRACE, life.tracker.wait())
        .await
        .is_err()
    {
        tracing::warn!("some tasks did not finish within {SHUTDOWN_GRACE:?}");
    }
    // Kiosks can upload no more: what each recording acknowledged is what it holds.
    recordings.close_all(StopReason::ServerStopping);
    // After every client left, so that their leaving is in the session's log.
    visits.end(Source::Server, None, SessionEnd::ServerStopping);
    hub.close_corpus();
    let logged = tokio::task::spawn_blocking(move || corpus.finish())
        .await
        .map_err(|e| io::Error::other(format!("corpus writer: {e}")))??;
    tracing::info!(events = logged, "corpus log flushed");
    Ok(())
}

/// The limits this run keeps: the bundle's, with `chosen` connection limits instead when
/// given; the open-files limit raised for the connections, with a warning when it stays too
/// low.
fn limits_in_force(
    bundle: &ServerLimits,
    chosen: Option<ConnectionLimits>,
    warnings: &mut Vec<String>,
) -> Limits {
    let mut server = *bundle;
    if let Some(chosen) = chosen {
        server.per_address = chosen.per_address;
        server.total = chosen.total;
        server.header_timeout = chosen.header_timeout;
        server.body_timeout = chosen.body_timeout;
    }
    let room = make_room(server.total);
    warnings.extend(room.warning);
    Limits {
        server,
        open_files: room.limit,
    }
}

/// Serves until `shutdown` completes, then shuts down in order and flushes the corpus.
pub async fn run(
    listener: TcpListener,
    server: Server,
    shutdown: impl Future<Output = ()> + Send + 'static,
) -> io::Result<()> {
    let Server {
        state,
        corpus,
        limits,
        ..
    } = server;
    let stop = state.life.shutdown.clone();
    let stopping = Arc::clone(&state.dispatcher);
    let signal = async move {
        tokio::select! {
            () = shutdown => {}
            () = stop.cancelled() => {}
        }
        announce_stop(&stopping);
        stop.cancel();
    };
    let proxies = state.access.proxies().clone();
    let closing = Closing::of(&state);
    serve_connections(listener, app(state), limits, proxies, signal).await;
    wind_down(closing, corpus).await
}
