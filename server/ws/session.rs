//! `Session`: what one websocket connection remembers between frames (its role once `hello`
//! was accepted, whether it must close, its run of refused triggers, its signalling allowance,
//! the writer's feed not yet handed over) and the routing of each client frame to its handler.
//! This is the only place that changes that state: a handler is lent the [`Client`] and
//! returns what the session must remember (an admitted role, a refused credential, what became
//! of a run of refusals), and the session records it here.

use std::time::Instant;

use tokio::sync::oneshot;
use tokio_util::sync::CancellationToken;

use crate::access::TokenBucket;
use crate::adapters::ScreenReport;
use crate::events::{ClientLeft, ClientRole, Ended, EventKind};
use crate::operator::Confirmation;
use crate::wire::ErrorCode;
use crate::ws::client::Client;
use crate::ws::diagnose::diagnose;
use crate::ws::hello::{self, Hello, Refused};
use crate::ws::protocol::{ClientFrame, MAX_FRAME_BYTES};
use crate::ws::triggers::{self, RefusedRun};
use crate::ws::writer::Feed;
use crate::ws::{attract, initiative, recording, reports, robot, signal};

/// One connection's state, changed only by its own methods below.
pub(super) struct Session {
    /// Who the client is and the way back to it: fixed, lent to the handlers.
    client: Client,
    /// The role, once `hello` was accepted.
    role: Option<ClientRole>,
    /// Hands the writer its subscription after `hello`.
    feed: Option<oneshot::Sender<Feed>>,
    /// Set when the connection must end after the frames queued so far (a refused hello).
    closing: Option<&'static str>,
    /// Whether this client's current run of refused triggers (rate-limited, or forbidden for
    /// its role) was logged already: one `trigger.refused` per run, so a flood cannot flood
    /// the corpus.
    refusals_logged: bool,
    /// This client's allowance for relayed signalling frames.
    signals: TokenBucket,
    /// The robot events an adapter said in its `hello` it sends.
    robot_events: Vec<String>,
}

impl Session {
    /// A session for a client that has not said `hello` yet; `feed` reaches its writer.
    pub(super) fn new(client: Client, feed: oneshot::Sender<Feed>) -> Self {
        Session {
            client,
            role: None,
            feed: Some(feed),
            closing: None,
            refusals_logged: false,
            signals: TokenBucket::signalling(Instant::now()),
            robot_events: Vec::new(),
        }
    }

    /// The reason the connection must end after the frames queued so far, if it must.
    pub(super) fn closing(&self) -> Option<&'static str> {
        self.closing
    }

    /// Cancelled when the client's outbox overflowed: the client is too slow to keep.
    pub(super) fn kicked(&self) -> CancellationToken {
        self.client.outbox.kicked().clone()
    }

    /// A text frame: parsed and handled, or answered with what is wrong with it.
    pub(super) fn on_text(&mut self, text: &str) {
        if let Some(frame) = self.parse(text) {
            self.on_frame(frame);
        }
    }

    /// A text frame parsed, or `None` after answering with what is wrong with it.
    pub(super) fn parse(&self, text: &str) -> Option<ClientFrame> {
        if text.len() > MAX_FRAME_BYTES {
            let message = format!("frames are limited to {MAX_FRAME_BYTES} bytes");
            let code = ErrorCode::FrameTooLarge;
            self.client.reply_error(code, &message, None, None);
            return None;
        }
        match serde_json::from_str::<ClientFrame>(text) {
            Ok(frame) => Some(frame),
            Err(e) => {
                let (code, message, reference) = diagnose(text, &e);
                (self.client).reply_error(code, &message, reference.as_deref(), None);
                None
            }
        }
    }

    /// The role, once `hello` was accepted.
    pub(super) fn role(&self) -> Option<ClientRole> {
        self.role
    }

    /// The way back to the client, for a transport that answers it itself.
    pub(super) fn client(&self) -> &Client {
        &self.client
    }

    /// A binary frame: the protocol is JSON text, so it is answered and otherwise ignored.
    pub(super) fn on_binary(&self) {
        let message = "send JSON text frames, not binary ones";
        (self.client).reply_error(ErrorCode::BinaryFrame, message, None, None);
    }

    /// A parsed frame, routed to its handler.
    pub(super) fn on_frame(&mut self, frame: ClientFrame) {
        let (client, role) = (&self.client, self.role);
        match frame {
            ClientFrame::Hello(frame) => self.hello(Hello::from(frame)),
            ClientFrame::Trigger(trigger) => {
                let run = triggers::trigger(client, role, trigger, self.refusals_logged);
                self.record(run);
            }
            ClientFrame::Stop { reference } => triggers::stop(client, role, reference),
            ClientFrame::Context { context, reference } => {
                triggers::set_context(client, role, context, reference);
            }
            ClientFrame::Language {
                language,
                reference,
            } => triggers::set_language(client, role, &language, reference),
            ClientFrame::Page { page, via, element } => {
                let run = triggers::page_shown(client, role, page, via, element);
                self.record(run);
            }
            ClientFrame::Attract { state, by } => attract::reported(client, role, state, by),
            ClientFrame::Propose {
                label,
                context,
                reason,
                reference,
            } => initiative::propose(client, role, label, context, reason, reference),
            ClientFrame::Accept {
                proposal,
                reference,
            } => initiative::accept(client, role, proposal, reference),
            ClientFrame::Dismiss {
                proposal,
                reference,
            } => initiative::dismiss(client, role, proposal, reference),
            ClientFrame::Mark {
                mark,
                value,
                confirm,
                reference,
            } => {
                let confirmed = if confirm {
                    Confirmation::Confirmed
                } else {
                    Confirmation::Unconfirmed
                };
                initiative::mark(client, role, mark, value, confirmed, reference);
            }
            ClientFrame::Signal { to, data } => self.signal(to, &data),
            ClientFrame::Started { id } => {
                reports::report(client, role, id, ScreenReport::Started);
            }
            ClientFrame::Done { id, held } => {
                reports::report(client, role, id, ScreenReport::Done { held });
            }
            ClientFrame::Failed { id, reason } => {
                let reason = reason.unwrap_or_else(|| "the adapter reported a failure".into());
                reports::report(client, role, id, ScreenReport::Failed(reason));
            }
            ClientFrame::Robot { event, data } => {
                robot::noticed(client, role, &self.robot_events, event, data);
            }
            ClientFrame::Clock { t0 } => recording::clock(client, role, t0),
            ClientFrame::RecordingStarted {
                recording: id,
                mime,
                mono_us,
                clock_error_us,
            } => recording::started(client, role, id, &mime, mono_us, clock_error_us),
            ClientFrame::RecordingStopped { recording: id } => {
                recording::stopped(client, role, id);
            }
            ClientFrame::RecordingFailed {
                recording: id,
                code,
                message,
            } => recording::failed(client, role, id, code, &message),
        }
    }

    /// `hello`: admitted, the client gets its role, then its welcome, then the writer its
    /// feed, then the server learns of it, in that order (see `hello`).
    pub(super) fn hello(&mut self, hello: Hello) {
        if self.role.is_some() {
            return self.client.reply_error(
                ErrorCode::AlreadyIntroduced,
                "hello was already received on this connection",
                None,
                None,
            );
        }
        let admitted = match hello::admit(&self.client, hello) {
            Ok(admitted) => admitted,
            Err(Refused::Credential) => {
                self.closing = Some("credential refused");
                return;
            }
            Err(Refused::NoVerbs) => return,
        };
        self.role = Some(admitted.role);
        self.robot_events = admitted.robot_events.clone();
        let feed = hello::welcome(&self.client, &admitted);
        if let (Some(feed), Some(tx)) = (feed, self.feed.take()) {
            let _ = tx.send(feed);
        }
        hello::join(&self.client, admitted);
    }

    /// Remembers what a frame did to the client's run of refused triggers.
    fn record(&mut self, run: RefusedRun) {
        match run {
            RefusedRun::Unchanged => {}
            RefusedRun::Logged => self.refusals_logged = true,
            RefusedRun::Over => self.refusals_logged = false,
        }
    }

    /// `signal`: the allowance is taken only for a frame the client may send at all.
    fn signal(&mut self, to: u64, data: &serde_json::Value) {
        let Some(role) = signal::signalling_role(&self.client, self.role, data) else {
            return;
        };
        if let Err(wait) = self.signals.take(Instant::now()) {
            return signal::refuse_too_many(&self.client, wait);
        }
        signal::relay(&self.client, role, to, data);
    }

    /// The connection ended for `reason`, `ended` by whom: whatever the client held is released (an adapter's
    /// commands fail, an operator's calls end, a dialog manager's proposals are withdrawn)
    /// and `client.left` is published. A client that never said `hello` left no trace.
    pub(super) fn leave(self, reason: &str, ended: Ended, code: Option<u16>) {
        let Some(role) = self.role else { return };
        let client = &self.client;
        let state = &client.state;
        if role == ClientRole::Adapter {
            state.devices.external.disconnect(client.id);
        }
        state.devices.display.left(role, client.id);
        let name = state.client_left(client.id).and_then(|info| info.name);
        if role == ClientRole::Operator {
            signal::hang_up_calls(client);
        }
        if role == ClientRole::Dm {
            initiative::withdraw_proposals(client);
        }
        let reason = reason.to_owned();
        state.hub.publish(EventKind::ClientLeft(ClientLeft {
            client: client.id,
            role,
            name,
            reason,
            ended: Some(ended),
            code,
        }));
    }
}
