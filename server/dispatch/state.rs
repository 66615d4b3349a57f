//! The dispatcher's state, with one owner: everything a trigger, a stop, a command's end or a
//! change of context or language reads and changes sits in one [`State`] under one lock, and
//! a request holds it as a [`Turn`] from its first check to its last hand-over. So no order of
//! locks exists to keep, two requests never interleave their decisions, and adapters are handed
//! cancellations and commands in the order the decisions were made (adapters only queue and
//! never call back into the dispatcher, so the hand-over cannot nest).

use std::collections::BTreeMap;
use std::sync::{Arc, MutexGuard};

use tokio_util::sync::CancellationToken;

use crate::content::{Bundle, DEFAULT_VARIANT, Language};
use crate::dispatch::Speaking;
use crate::dispatch::channels::Lanes;
use crate::dispatch::choose::Chooser;
use crate::dispatch::visitors::VisitorCuts;

/// What the dispatcher decides by: the robot's dialog state and its channels.
pub(crate) struct State {
    /// Picks one alternative text, never the same twice in a row.
    pub chooser: Chooser,
    /// The current context.
    pub context: String,
    /// The visitor's language (`language.rs`).
    pub language: Language,
    /// Whether the language changed since this server started: a reconnecting kiosk's
    /// language is taken only until then (`language.rs`).
    pub language_changed: bool,
    /// Cancelled and replaced by every stop: sequences started before a stop end with it.
    pub epoch: CancellationToken,
    /// One token per source priority, cancelled and replaced by every interrupting trigger of
    /// that priority or higher: sequences drop their unsent speech.
    pub speech_epochs: BTreeMap<u8, CancellationToken>,
    /// Each output channel's running and waiting commands.
    pub lanes: Lanes,
    /// Who speaks, as the kiosks were last told.
    pub speaking_told: Option<Speaking>,
    /// Since when visitors' speech is cut off (a visitor's stop, a page left).
    pub visitor_cuts: VisitorCuts,
}

impl State {
    /// The state a server starts in: context `Text`, the bundle's default language.
    pub fn new(bundle: &Bundle, seed: Option<u64>, epoch: CancellationToken) -> Self {
        State {
            chooser: Chooser::new(seed),
            context: DEFAULT_VARIANT.to_owned(),
            language: bundle.config.languages.default_language().clone(),
            language_changed: false,
            epoch,
            speech_epochs: BTreeMap::new(),
            lanes: Lanes::default(),
            speaking_told: None,
            visitor_cuts: VisitorCuts::default(),
        }
    }
}

/// One request's hold on the dispatcher: its state under the one lock, and the bundle that
/// was live when the lock was taken. A reload swaps the bundle under the same lock, so a
/// request that holds a turn decides everything in one bundle.
pub(crate) struct Turn<'d> {
    /// The state, locked.
    pub state: MutexGuard<'d, State>,
    /// The bundle live for this request.
    pub bundle: Arc<Bundle>,
}
