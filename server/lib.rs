//! Docent: presents dialog acts on a robot or kiosk. Triggers come from touchscreen pages,
//! timers, a remote operator and a dialog manager; the dispatcher resolves each act into
//! commands for device adapters and every event goes to the corpus log.
//!
//! This is the runtime and the command line, on top of the workspace's three other crates:
//! `docent-content` (bundles), `docent-protocol` (formats other programs read) and
//! `docent-corpus` (the corpus folder). The modules below depend on one another through
//! [`state::AppState`], the axum `AppState` pattern; `ARCHITECTURE.md` has the whole picture.
//!
//! Module map:
//! - [`access`]: credentials, failed-attempt lockout and the kiosk trigger allowance.
//! - [`content`]: the `docent-content` crate (`server/content/`), re-exported: loading and
//!   checking content bundles (acts files, `docent.yaml`, pages, media).
//! - [`dispatch`]: the dialog act dispatcher, the only path from a trigger to a device.
//! - [`adapters`]: speech, display, drive and external (websocket) adapters, and the router.
//! - [`events`]: the hub that stamps events and fans them out, and how far the log is
//!   written; the event types are `docent-protocol`'s, re-exported.
//! - [`corpus`]: the `docent-corpus` crate (`server/corpus/`), re-exported: the JSON Lines
//!   corpus writer, reading it back, recordings' files and every export.
//! - [`cli`]: `docent corpus`, printed for people.
//! - [`http`]: the route table and HTTP handlers; [`ws`]: the websocket protocol.
//! - [`wire`]: what goes to a client, shared by [`ws`] and [`adapters`]: the bounded outbox
//!   and lingering notices ([`wire::ErrorCode`] re-exported from `docent-protocol`).
//! - [`operator`]: pending proposals (mixed initiative) and visitor-session marks.
//! - [`recording`]: the kiosk's microphone and camera recorded into a session's `media/`.
//! - [`fleet`]: many robots over one MQTT broker: each robot's bridge, the fleet view.
//! - [`robot`]: robot events from adapter processes and ROS topics: logged, sessions, reactions.
//! - [`translations`]: `docent translations export|import`, the texts as a table for a
//!   translator (CSV or XLIFF) and the filled table written back into the acts files.
//! - [`media`]: media files Chromium cannot show, converted with ffmpeg in the background and
//!   served under their own names.
//! - [`reload`]: live reload: watching the bundle folder, swapping in a good save, refusing a
//!   broken one.
//! - [`serve`]: wiring it together and running with graceful shutdown.
//! - [`state`], [`lifecycle`], [`sync`]: shared handles, shutdown plumbing, a poison-free lock.

pub mod access;
pub mod adapters;
pub use docent_content as content;
pub use docent_content::translations;
pub mod cli;
pub use docent_corpus as corpus;
pub mod dispatch;
pub mod events;
pub mod fleet;
pub mod http;
pub mod lifecycle;
pub mod media;
pub mod operator;
pub mod recording;
pub mod reload;
pub mod robot;
pub mod serve;
pub mod state;
pub mod sync;
pub mod wire;
pub mod ws;
