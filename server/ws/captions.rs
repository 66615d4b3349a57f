//! Captions: what the robot says, shown while it is said. Follows the hub: a `SAY` is
//! captioned from its `command.started` (the speech device began: espeak's process, the
//! `log` adapter's pacing, a websocket adapter's or the browser's `started`) to its end
//! (`command.done`, `failed` or `cancelled`), with the text of its `command.sent`, the text
//! actually spoken. At every change the screens get a `caption` frame (docs/PROTOCOL.md):
//! kiosks when the live bundle's `captions: kiosk` is on (the default), projectors when
//! `captions: projector` is. A screen whose captions are off gets `text: null`, so one turned
//! off by a reload clears. Operators follow the same events in their event stream (the
//! console's caption line), so a client that declined events gets no frames it did not ask for.
//! A client that joins is told the caption in force, under the same lock as the changes, so
//! it never gets an older one after a newer.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use tokio::sync::broadcast::{self, error::RecvError};
use tokio_util::sync::CancellationToken;

use crate::content::Verb;
use crate::content::config::CaptionSettings;
use crate::events::{
    ClientRole, CommandCancelled, CommandDone, CommandFailed, CommandSent, CommandStarted, Event,
    EventKind,
};
use crate::state::ClientLinks;
use crate::sync::lock;
use crate::wire::outbox::Frame;
use crate::ws::protocol::caption_frame;

/// The roles that are told captions: the screens.
const CAPTIONED: [ClientRole; 2] = [ClientRole::Kiosk, ClientRole::Projector];

/// The caption in force and the clients it goes to.
pub struct Captions {
    links: ClientLinks,
    now: Mutex<Now>,
}

/// What is being said, from the events seen so far.
#[derive(Default)]
struct Now {
    /// The text of each `SAY` sent and not ended yet (bounded by the speech channel's queue).
    texts: HashMap<u64, Arc<str>>,
    /// The `SAY` being said: its id and text.
    shown: Option<(u64, Arc<str>)>,
    /// The command each role of [`CAPTIONED`] was last told (`Some(None)`: no caption), so
    /// only changes are sent.
    told: [Option<Option<u64>>; CAPTIONED.len()],
}

impl Now {
    /// Takes one event; true when the caption in force changed.
    fn take(&mut self, kind: &EventKind) -> bool {
        match kind {
            EventKind::CommandSent(CommandSent {
                command,
                verb,
                arg,
                args,
                ..
            }) if verb == Verb::Say.as_str() => {
                let text = args.say_text().or(arg.as_deref()).unwrap_or_default();
                self.texts.insert(*command, Arc::from(text));
                false
            }
            EventKind::CommandStarted(CommandStarted { command, .. }) => {
                match self.texts.get(command) {
                    Some(text) => {
                        self.shown = Some((*command, Arc::clone(text)));
                        true
                    }
                    None => false,
                }
            }
            EventKind::CommandDone(CommandDone { command, .. })
            | EventKind::CommandFailed(CommandFailed { command, .. })
            | EventKind::CommandCancelled(CommandCancelled { command, .. }) => {
                self.texts.remove(command);
                if self.shown.as_ref().is_some_and(|(id, _)| id == command) {
                    self.shown = None;
                    return true;
                }
                false
            }
            _ => false,
        }
    }

    /// Starts again from what the speech channel runs now (`saying`), after events were
    /// missed: the texts of `SAY`s queued meanwhile are gone, so those are not captioned.
    fn resync(&mut self, saying: Option<(u64, Arc<str>)>) {
        self.texts.clear();
        self.shown = saying;
    }

    /// The caption `role` is to show under `settings`: id and text, or none.
    fn for_role(&self, role: ClientRole, settings: CaptionSettings) -> Option<(u64, &str)> {
        let on = match role {
            ClientRole::Kiosk => settings.kiosk,
            ClientRole::Projector => settings.projector,
            _ => false,
        };
        (self.shown.as_ref())
            .filter(|_| on)
            .map(|(id, text)| (*id, &**text))
    }
}

impl Captions {
    /// Captions sent through `links`.
    pub fn new(links: ClientLinks) -> Arc<Self> {
        Arc::new(Captions {
            links,
            now: Mutex::default(),
        })
    }

    /// Follows `events` until `shutdown`; `settings` reads the live bundle's `captions:`,
    /// `saying` the `SAY` the speech channel runs now (read when the events were too many to
    /// follow). Subscribe before any client connects, so that no `SAY` is missed.
    pub async fn follow(
        self: Arc<Self>,
        mut events: broadcast::Receiver<Arc<Event>>,
        settings: impl Fn() -> CaptionSettings + Send + 'static,
        saying: impl Fn() -> Option<(u64, Arc<str>)> + Send + 'static,
        shutdown: CancellationToken,
    ) {
        loop {
            let event = tokio::select! {
                () = shutdown.cancelled() => return,
                event = events.recv() => event,
            };
            match event {
                Ok(event) => self.take(&event.kind, settings()),
                Err(RecvError::Lagged(missed)) => {
                    // The events missed cannot be replayed: the caption is read from what
                    // the speech channel runs now, and the texts are followed afresh.
                    tracing::warn!(
                        missed,
                        "captions fell behind the events; caption read from the speech channel"
                    );
                    let mut now = lock(&self.now);
                    now.resync(saying());
                    self.tell_changes(&mut now, settings());
                }
                Err(RecvError::Closed) => return,
            }
        }
    }

    fn take(&self, kind: &EventKind, settings: CaptionSettings) {
        let mut now = lock(&self.now);
        if now.take(kind) {
            self.tell_changes(&mut now, settings);
        }
    }

    /// Sends each role its caption, if it changed for that role.
    fn tell_changes(&self, now: &mut Now, settings: CaptionSettings) {
        for (index, role) in CAPTIONED.into_iter().enumerate() {
            let caption = now.for_role(role, settings);
            let id = caption.map(|(id, _)| id);
            if now.told[index] == Some(id) {
                continue;
            }
            let frame = Frame::from(caption_frame(caption));
            now.told[index] = Some(id);
            // Only queues (outboxes never wait), so holding the lock keeps the order.
            self.links.send_to_role(role, &frame);
        }
    }

    /// Tells a client that just joined as `role` the caption in force (nothing when none:
    /// a new client shows none yet).
    pub fn tell_joined(
        &self,
        role: ClientRole,
        settings: CaptionSettings,
        send: impl FnOnce(Frame),
    ) {
        if !CAPTIONED.contains(&role) {
            return;
        }
        let now = lock(&self.now);
        if let Some(caption) = now.for_role(role, settings) {
            send(Frame::from(caption_frame(Some(caption))));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::content::Args;
    use crate::events::{ActRef, Source};

    fn act() -> Arc<ActRef> {
        Arc::new(ActRef {
            trigger: 1,
            label: Arc::from("HELLO"),
            source: Source::Kiosk,
            client: None,
            reference: None,
            at: "acts.yaml:1".to_owned(),
        })
    }

    fn sent(command: u64, verb: &str, text: &str) -> EventKind {
        EventKind::CommandSent(CommandSent {
            command,
            act: act(),
            verb: verb.to_owned(),
            arg: Some(text.to_owned()),
            args: Arc::new(Args::Say {
                text: text.to_owned(),
                language: None,
            }),
            adapter: "log".into(),
        })
    }

    fn started(command: u64) -> EventKind {
        EventKind::CommandStarted(CommandStarted {
            command,
            act: act(),
            verb: "SAY".to_owned(),
        })
    }

    fn done(command: u64) -> EventKind {
        EventKind::CommandDone(CommandDone {
            command,
            act: act(),
            verb: "SAY".to_owned(),
        })
    }

    const ALL_ON: CaptionSettings = CaptionSettings {
        kiosk: true,
        projector: true,
    };

    #[test]
    fn a_say_is_captioned_from_its_start_to_its_end_not_from_when_it_was_sent() {
        let mut now = Now::default();
        assert!(!now.take(&sent(4, "SAY", "Welcome!")));
        assert_eq!(
            now.for_role(ClientRole::Kiosk, ALL_ON),
            None,
            "queued, not said yet"
        );
        assert!(now.take(&started(4)));
        assert_eq!(
            now.for_role(ClientRole::Kiosk, ALL_ON),
            Some((4, "Welcome!"))
        );
        assert!(now.take(&done(4)));
        assert_eq!(now.for_role(ClientRole::Kiosk, ALL_ON), None);
        assert!(now.texts.is_empty());
    }

    #[test]
    fn the_end_of_an_earlier_say_leaves_the_caption_of_the_one_being_said() {
        let mut now = Now::default();
        now.take(&sent(1, "SAY", "one"));
        now.take(&sent(2, "SAY", "two"));
        now.take(&started(1));
        now.take(&started(2)); // 1 was cut short; its cancellation is logged after 2 started
        assert!(!now.take(&done(1)));
        assert_eq!(
            now.for_role(ClientRole::Projector, ALL_ON),
            Some((2, "two"))
        );
    }

    #[test]
    fn after_missed_events_the_caption_is_what_the_speech_channel_runs_until_it_ends() {
        let mut now = Now::default();
        now.take(&sent(1, "SAY", "one"));
        now.take(&started(1));
        // Events of 1's end and 2's start were missed; the speech channel runs 2.
        now.resync(Some((2, Arc::from("two"))));
        assert_eq!(now.for_role(ClientRole::Kiosk, ALL_ON), Some((2, "two")));
        assert!(!now.take(&done(1)), "an end missed before does not clear");
        assert!(now.take(&done(2)));
        assert_eq!(now.for_role(ClientRole::Kiosk, ALL_ON), None);
        now.resync(None);
        assert_eq!(now.for_role(ClientRole::Kiosk, ALL_ON), None);
    }

    #[test]
    fn other_verbs_are_never_captioned() {
        let mut now = Now::default();
        now.take(&sent(7, "DISPLAY_PAGE", "map.html"));
        assert!(!now.take(&started(7)));
        assert_eq!(now.for_role(ClientRole::Kiosk, ALL_ON), None);
    }

    #[test]
    fn a_screen_whose_captions_are_off_gets_none_and_other_roles_never_get_one() {
        let mut now = Now::default();
        now.take(&sent(3, "SAY", "Hello"));
        now.take(&started(3));
        let defaults = CaptionSettings::default();
        assert_eq!(
            now.for_role(ClientRole::Kiosk, defaults),
            Some((3, "Hello"))
        );
        assert_eq!(now.for_role(ClientRole::Projector, defaults), None);
        let off = CaptionSettings {
            kiosk: false,
            projector: false,
        };
        assert_eq!(now.for_role(ClientRole::Kiosk, off), None);
        assert_eq!(now.for_role(ClientRole::Operator, ALL_ON), None);
    }
}
