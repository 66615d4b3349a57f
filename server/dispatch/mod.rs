//! The dialog act dispatcher (paper, Fig. 3): the single place that turns a triggered act into
//! commands and hands them to adapters. Every trigger source (HTTP, kiosk pages, operators, the
//! dialog manager, later page timers) comes through [`Dispatcher::trigger`].
//!
//! Resolution: the context (asked for, or the current one) picks a variant, falling back to
//! `Text`; one alternative is chosen at random, never the same twice in a row; it becomes a
//! `SAY` before the act's commands. Commands go to their output channels at once unless the act
//! has a `WAIT` (then `sequence` paces them); each channel (`channels`, `gate`) runs one command
//! at a time and settles the others by its policy and the sources' priorities. An act with
//! `DRIVE_STOP` preempts everything first; an interrupting trigger first clears speech of its
//! priority or lower. A kiosk's tap on an act already speaking is refused; visitors may stop
//! their own speech and leaving a page ends it (`visitors`).
//!
//! Everything this decides by sits in one `State` under one lock (`state`); a request holds it
//! as a `Turn`, with the bundle live then, from its first check to its last hand-over. What
//! clients are to be told is queued as a [`Notice`] in that turn, never called into. The small
//! rules a turn applies (a context known, a priority, the variant spoken) are in `rules`.

mod channels;
mod choose;
mod gate;
#[cfg(test)]
mod policy_tests;

/// A dispatcher over `bundle` with the `log` speech adapter and no hardware, for unit tests
/// elsewhere in the crate (`robot::reactions`, the policy tests).
#[cfg(test)]
pub(crate) fn log_dispatcher(bundle: crate::content::Bundle, hub: &Hub) -> Arc<Dispatcher> {
    let life = Lifecycle::new();
    let (_, router) = crate::adapters::Devices::start(
        &bundle.config,
        None,
        crate::content::config::AdapterKind::Log,
        crate::adapters::SpeechOutput::Audio,
        (hub, &crate::robot::RobotInbox::channel().0),
        &life,
    );
    Dispatcher::new(Arc::new(bundle), router, hub.clone(), Some(1), life)
}
mod language;
mod request;
mod rules;
mod sequence;
mod state;
mod visitors;

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use arc_swap::ArcSwap;

pub use channels::{LaneEntry, LaneStatus};
pub use gate::{Answer, Notice, Speaking};
pub use request::{ResolvedCommand, TriggerError, TriggerRequest, Triggered};

use crate::adapters::{AdapterStatus, CancelScope, Command, Router};
use crate::content::config::Channel;
use crate::content::{Args, Bundle, DEFAULT_VARIANT, Verb};
use crate::events::{ActRef, EventKind, Hub, Source};
use crate::lifecycle::Lifecycle;
use crate::sync::lock;
pub(crate) use language::texts_in;
pub use rules::variant_for;
use rules::{known_context, priority, resolved, speaking_act, suggest};
use sequence::Sequence;
use state::{State, Turn};

/// Resolves acts into commands and sends them to adapters.
pub struct Dispatcher {
    /// The bundle being served: read without a lock by every view, swapped only under the
    /// state's lock (so a [`Turn`] decides in one bundle).
    bundle: ArcSwap<Bundle>,
    router: Router,
    hub: Hub,
    life: Lifecycle,
    next_id: AtomicU64,
    /// Where clients learn about their commands (`gate.rs`, [`Notice`]).
    notices: OnceLock<tokio::sync::mpsc::UnboundedSender<Notice>>,
    /// Everything the dispatcher decides by, with one owner (`state.rs`).
    state: Mutex<State>,
}

impl Dispatcher {
    /// A dispatcher over `bundle`, sending through `router`.
    pub fn new(
        bundle: Arc<Bundle>,
        router: Router,
        hub: Hub,
        seed: Option<u64>,
        life: Lifecycle,
    ) -> Arc<Self> {
        let state = State::new(&bundle, seed, life.shutdown.child_token());
        Arc::new(Dispatcher {
            bundle: ArcSwap::new(bundle),
            router,
            hub,
            life,
            next_id: AtomicU64::new(1),
            notices: OnceLock::new(),
            state: Mutex::new(state),
        })
    }

    /// Takes the state's lock for one request, with the bundle live now.
    fn turn(&self) -> Turn<'_> {
        let state = lock(&self.state);
        Turn {
            state,
            bundle: self.bundle.load_full(),
        }
    }

    /// Takes the state's lock for a request that began its checks in `bundle` (live then, or
    /// replaced by a reload since): it goes on in that bundle, never in two.
    fn turn_in(&self, bundle: Arc<Bundle>) -> Turn<'_> {
        Turn {
            state: lock(&self.state),
            bundle,
        }
    }

    /// The bundle being served.
    pub fn bundle(&self) -> Arc<Bundle> {
        self.bundle.load_full()
    }

    /// Puts `bundle` live in place of the current one (live reload) and returns the one it
    /// replaced. Triggers from now on resolve in `bundle`; acts already running keep the
    /// commands they resolved. A current context the new bundle lacks falls back to `Text`,
    /// and the change is published.
    pub fn replace_bundle(&self, bundle: Arc<Bundle>) -> Arc<Bundle> {
        // Swapped under the state's lock: a request holding a turn keeps its bundle.
        let mut state = lock(&self.state);
        let known = bundle.contexts.contains(&state.context);
        let old = self.bundle.swap(Arc::clone(&bundle));
        if !known {
            state.context = DEFAULT_VARIANT.to_owned();
            self.hub.publish(EventKind::ContextChanged {
                source: Source::Server,
                context: DEFAULT_VARIANT.to_owned(),
            });
        }
        self.keep_language(&mut state, &bundle);
        old
    }

    /// The event hub.
    pub fn hub(&self) -> &Hub {
        &self.hub
    }

    /// Triggers an act: resolves it, starts its commands, and says what was resolved. The
    /// whole trigger is one turn: checked, resolved, logged and handed over in one bundle.
    pub fn trigger(self: &Arc<Self>, req: TriggerRequest) -> Result<Triggered, TriggerError> {
        self.trigger_in(self.bundle(), req)
    }

    /// [`Dispatcher::trigger`] in `bundle`, the one the caller checked the request against
    /// (the kiosk's page offers, its session settings): a request never mixes two bundles.
    pub fn trigger_in(
        self: &Arc<Self>,
        bundle: Arc<Bundle>,
        req: TriggerRequest,
    ) -> Result<Triggered, TriggerError> {
        let mut turn = self.turn_in(bundle);
        let bundle = Arc::clone(&turn.bundle);
        // A visitor tapping an act already speaking gets an answer, not the text twice.
        if req.source == Source::Kiosk && speaking_act(&turn.state, &req.label) {
            let label = req.label.clone();
            return Err(self.refuse(&req, TriggerError::AlreadySpeaking { label }));
        }
        let Some(&index) = bundle.index.get(&req.label) else {
            let suggestion = suggest(&req.label, bundle.labels());
            return Err(self.refuse(
                &req,
                TriggerError::UnknownAct {
                    label: req.label.clone(),
                    suggestion,
                },
            ));
        };
        let context = match req.context.as_deref() {
            Some(c) => known_context(&bundle, c).map_err(|e| self.refuse(&req, e))?,
            None => turn.state.context.clone(),
        };
        let act = &bundle.acts[index];
        let variant = variant_for(act, &context);
        let visitor_language = turn.state.language.clone();
        let choice = variant.map(|v| {
            let texts = language::texts_in(&bundle, v, &visitor_language);
            let count = texts.alternatives.len();
            let alt = turn
                .state
                .chooser
                .pick(&act.label, &texts.chooser_key, count);
            (
                v,
                alt,
                texts.alternatives[alt].value.as_str(),
                texts.language,
            )
        });
        let default_language = bundle.config.languages.default_language();
        let trigger = self.next_id();
        let act_ref = Arc::new(ActRef {
            trigger,
            source: req.source,
            client: req.client,
            reference: req.reference,
            label: act.label.as_str().into(),
            at: format!("{}:{}", act.pos.file, act.pos.line),
        });
        let mut commands = Vec::with_capacity(act.commands.len() + 1);
        if let Some((_, _, text, language)) = &choice {
            let say = Args::Say {
                text: (*text).to_owned(),
                language: Some(language.clone()),
            };
            commands.push(self.command(&act_ref, Verb::Say, Some(text), say));
        }
        for c in &act.commands {
            let spec = &c.value;
            let args = match &spec.args {
                // A SAY among the commands is written in the default language.
                Args::Say { text, .. } => Args::Say {
                    text: text.clone(),
                    language: Some(default_language.clone()),
                },
                args => args.clone(),
            };
            commands.push(self.command(&act_ref, spec.verb.clone(), spec.arg.as_deref(), args));
        }
        let triggered = Triggered {
            trigger,
            reference: act_ref.reference.clone(),
            label: act.label.clone(),
            context: context.clone(),
            variant: choice.as_ref().map(|(v, _, _, _)| v.name.clone()),
            alternative: choice.as_ref().map(|(_, alt, _, _)| *alt),
            text: choice.as_ref().map(|(_, _, text, _)| (*text).to_owned()),
            language: choice.as_ref().map(|(_, _, _, language)| language.clone()),
            commands: commands.iter().map(resolved).collect(),
        };
        self.hub.publish(EventKind::ActTriggered {
            act: Arc::clone(&act_ref),
            context,
            variant: triggered.variant.clone(),
            alternative: triggered.alternative,
            text: triggered.text.clone(),
            language: triggered.language.clone(),
            interrupt: req.interrupt,
            bundle_hash: bundle.fingerprint.clone(),
        });
        self.start(&mut turn, commands, &act_ref, req.interrupt);
        Ok(triggered)
    }

    fn start(
        self: &Arc<Self>,
        turn: &mut Turn,
        commands: Vec<Command>,
        act: &ActRef,
        interrupt: bool,
    ) {
        let priority = priority(&turn.bundle, act.source);
        if interrupt {
            self.interrupt_speech(turn, act, priority);
        }
        if act.source == Source::Kiosk && commands.iter().any(|c| visitors::moves_on(&c.verb)) {
            self.visitor_moved_on(turn, act);
        }
        let first_wait = commands.iter().position(|c| c.verb == Verb::Wait);
        let before_wait = &commands[..first_wait.unwrap_or(commands.len())];
        // Preempt before sending anything, so the act's own speech survives its DRIVE_STOP.
        if before_wait.iter().any(|c| c.verb == Verb::DriveStop) {
            self.stop_in(
                turn,
                act.source,
                &format!("DRIVE_STOP in act {}", act.label),
            );
        }
        let stop = turn.state.epoch.clone();
        let speech = (turn.state.speech_epochs.entry(priority))
            .or_default()
            .clone();
        Sequence::new(Arc::clone(self), stop, speech, first_wait.is_some()).start(turn, commands);
    }

    /// Clears queued and current speech of `priority` or lower, and such speech that acts
    /// waiting at a `WAIT` would say: higher-priority speech is never interrupted.
    fn interrupt_speech(self: &Arc<Self>, turn: &mut Turn, act: &ActRef, priority: u8) {
        let epochs = &mut turn.state.speech_epochs;
        let higher = epochs.split_off(&(priority + 1));
        for old in std::mem::replace(epochs, higher).into_values() {
            old.cancel();
        }
        let reason = format!("interrupted by act {}", act.label);
        let trigger = act.trigger;
        let lower = |c: &Command, p: u8| p <= priority && c.act.trigger != trigger;
        self.cancel_where(turn, Some(&Channel::Speech), lower, &reason);
    }

    /// Spawns tracked tasks.
    pub(crate) fn life(&self) -> &Lifecycle {
        &self.life
    }

    /// Stops everything: sequences end, every queue is cleared, speech is killed and the drive
    /// stops.
    pub fn stop(&self, source: Source, reason: &str) {
        self.stop_in(&mut self.turn(), source, reason);
    }

    /// [`Dispatcher::stop`], within a turn.
    pub(crate) fn stop_in(&self, turn: &mut Turn, source: Source, reason: &str) {
        let fresh = self.life.shutdown.child_token();
        let old = std::mem::replace(&mut turn.state.epoch, fresh);
        self.hub.publish(EventKind::Stop {
            source,
            reason: reason.to_owned(),
        });
        old.cancel();
        // Waiting commands first, so that none starts when the running ones end.
        let waiting: Vec<channels::Waiting> = (turn.state.lanes.values_mut())
            .flat_map(|lane| lane.cancel_where(|_, _| true, reason).dropped)
            .map(|(waiting, _)| waiting)
            .collect();
        for waiting in waiting {
            let outcome = crate::adapters::Outcome::Cancelled(reason.to_owned());
            self.report(&turn.state, waiting.command, waiting.waiter, outcome);
        }
        for adapter in self.router.adapters() {
            adapter.cancel(CancelScope::All, reason);
        }
    }

    /// The current context.
    pub fn context(&self) -> String {
        lock(&self.state).context.clone()
    }

    /// Changes the current context.
    pub fn set_context(&self, context: &str, source: Source) -> Result<(), TriggerError> {
        // Checked and changed in one turn, against the bundle live then: a reload cannot slip
        // in between and leave a context its bundle does not have.
        let mut turn = self.turn();
        let context = known_context(&turn.bundle, context)?;
        turn.state.context = context.clone();
        // Logged in the turn, so the log's last change is the context in force.
        self.hub
            .publish(EventKind::ContextChanged { source, context });
        Ok(())
    }

    /// The name of the adapter serving `verb` (as written), if any.
    pub fn adapter_for(&self, verb: &str) -> Option<&'static str> {
        let verb = Verb::built_in(verb).unwrap_or_else(|| Verb::Site(verb.into()));
        self.router.adapter_for(&verb).map(|a| a.name())
    }

    /// Queue length and current command of every adapter, by name.
    pub fn adapter_status(&self) -> BTreeMap<&'static str, AdapterStatus> {
        self.router
            .adapters()
            .iter()
            .map(|a| (a.name(), a.status()))
            .collect()
    }

    /// Whether `label` (in `context`) could be triggered now, without triggering it: how a
    /// proposal is checked before an operator sees it.
    pub fn check(&self, label: &str, context: Option<&str>) -> Result<(), TriggerError> {
        let bundle = self.bundle.load();
        if bundle.act(label).is_none() {
            return Err(TriggerError::UnknownAct {
                label: label.to_owned(),
                suggestion: suggest(label, bundle.labels()),
            });
        }
        match context {
            Some(c) => known_context(&bundle, c).map(drop),
            None => Ok(()),
        }
    }

    fn refuse(&self, req: &TriggerRequest, error: TriggerError) -> TriggerError {
        self.hub.publish(EventKind::TriggerRefused {
            source: req.source,
            client: req.client,
            label: req.label.clone(),
            code: error.code().into(),
            message: error.to_string(),
        });
        error
    }

    fn command(&self, act: &Arc<ActRef>, verb: Verb, arg: Option<&str>, args: Args) -> Command {
        Command {
            id: self.next_id(),
            act: Arc::clone(act),
            verb,
            arg: arg.map(Into::into),
            args: Arc::new(args),
        }
    }

    pub(crate) fn next_id(&self) -> u64 {
        self.next_id.fetch_add(1, Ordering::Relaxed)
    }
}
