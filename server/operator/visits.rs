//! Visitor sessions: the unit of the corpus. A session starts when an operator or a dialog
//! manager marks it, or (by default) at a visitor's first touch; one that a touch started ends
//! after the site's idle time without a touch; any ends when it is marked, when the next one
//! starts, or at shutdown. Every start and end is published here, under the same lock that
//! changes the state, so that the log's order is the order things happened.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::sync::Notify;
use tokio::time::Instant;
use tokio_util::sync::CancellationToken;

use crate::adapters::Display;
use crate::content::config::{CorpusSettings, SessionStart};
use crate::events::{
    Consent, ConsentChanged, EventKind, Hub, SessionEnd, SessionEnded, SessionStarted, Source,
};
use crate::sync::lock;

/// What the screens show now (the display state's snapshot).
pub type Shown = Box<dyn Fn() -> Display + Send + Sync>;

/// What a session's end does in the same step, after `session.ended` is published: the next
/// visitors start in the bundle's default language (`Dispatcher::back_to_default`). A step,
/// not a follower of the hub, so no end can be missed or come late.
pub type AfterEnd = Box<dyn Fn() + Send + Sync>;

/// The visitor groups an operator can note.
pub const VISITOR_GROUPS: [&str; 3] = ["single", "group", "children"];

/// Why a consent mark was refused.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum ConsentRefused {
    /// No session runs.
    #[error("no visitor session is running; start one first")]
    NoSession,
    /// It was withdrawn before.
    #[error(
        "this session's consent was withdrawn, which cannot be undone; start a new session to record again"
    )]
    Withdrawn,
    /// A refusal of consent that deletes the session's recordings, not confirmed.
    #[error(
        "declining or withdrawing consent deletes this session's recordings, so it must be \
         confirmed (`confirm: true` on the mark); nothing changed"
    )]
    Unconfirmed,
}

/// Whether an operator confirmed a consent change that deletes a session's recordings (the
/// `mark` frame's `confirm: true`): a slip of the keyboard or a script's stray frame must not
/// delete what visitors agreed to have recorded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Confirmation {
    /// The operator confirmed it.
    Confirmed,
    /// Nothing said it was meant.
    Unconfirmed,
}

/// The current visitor session.
pub struct Visits {
    hub: Hub,
    /// What the screens show now: a session's start says it, so its pages begin there.
    shown: Shown,
    /// What every session's end does too.
    after_end: AfterEnd,
    inner: Mutex<Inner>,
    /// A session started by a touch: the idle watch has a new deadline to keep.
    started_by_touch: Notify,
}

/// How many ended sessions' final consent is remembered: a recording's last chunks may
/// arrive after its session ended, and are taken only if that consent was `recorded`.
const ENDED_REMEMBERED: usize = 16;

#[derive(Debug, Default)]
struct Inner {
    last: u64,
    current: Option<Current>,
    /// The latest sessions that ended, with their final consent, oldest first.
    ended: VecDeque<(u64, Consent)>,
}

impl Inner {
    /// Takes the running session away, remembering its final consent.
    fn take_current(&mut self) -> Option<Current> {
        let ended = self.current.take()?;
        if self.ended.len() == ENDED_REMEMBERED {
            self.ended.pop_front();
        }
        self.ended.push_back((ended.number, ended.consent));
        Some(ended)
    }
}

#[derive(Debug)]
struct Current {
    number: u64,
    consent: Consent,
    /// Started by a visitor's touch: it ends after the idle time.
    by_touch: bool,
    last_touch: Instant,
}

impl Visits {
    /// No session yet; starts and ends are published to `hub`, each start with what `shown`
    /// says the screens show, and each end followed by `after_end`.
    pub fn new(hub: Hub, shown: Shown, after_end: AfterEnd) -> Self {
        Visits {
            hub,
            shown,
            after_end,
            inner: Mutex::default(),
            started_by_touch: Notify::new(),
        }
    }

    /// Starts a new session (ending the running one, if any, first) with the site's
    /// `settings`; returns its number.
    pub fn start(&self, settings: &CorpusSettings, source: Source, client: Option<u64>) -> u64 {
        let mut inner = lock(&self.inner);
        self.begin(&mut inner, settings, source, client, false)
    }

    /// Notes what the running session's visitors agreed to; returns the session's number.
    /// Consent once withdrawn stays so: a new session records again. A change from
    /// `recorded` to a refusal deletes the session's recordings, so it must be `confirmed`.
    pub fn set_consent(
        &self,
        consent: Consent,
        confirmed: Confirmation,
        source: Source,
        client: u64,
    ) -> Result<u64, ConsentRefused> {
        let mut inner = lock(&self.inner);
        let current = inner.current.as_mut().ok_or(ConsentRefused::NoSession)?;
        if current.consent == Consent::Withdrawn && consent != Consent::Withdrawn {
            return Err(ConsentRefused::Withdrawn);
        }
        if current.consent == Consent::Recorded
            && consent != Consent::Recorded
            && confirmed == Confirmation::Unconfirmed
        {
            return Err(ConsentRefused::Unconfirmed);
        }
        current.consent = consent;
        self.hub.publish(EventKind::ConsentChanged(ConsentChanged {
            session: current.number,
            consent,
            source,
            client,
        }));
        Ok(current.number)
    }

    /// Ends the running session, if any, and returns its number.
    pub fn end(&self, source: Source, client: Option<u64>, reason: SessionEnd) -> Option<u64> {
        let mut inner = lock(&self.inner);
        let ended = inner.take_current()?;
        self.publish_end(ended.number, source, client, reason);
        Some(ended.number)
    }

    /// The running session.
    pub fn current(&self) -> Option<u64> {
        lock(&self.inner).current.as_ref().map(|c| c.number)
    }

    /// The running session's consent.
    pub fn consent(&self) -> Option<Consent> {
        lock(&self.inner).current.as_ref().map(|c| c.consent)
    }

    /// Session `number`'s consent as it stands: the running session's, or the one an ended
    /// session ended with. `None` for a session not known (long ended, or never started):
    /// nothing of it may be recorded.
    pub fn consent_of(&self, number: u64) -> Option<Consent> {
        let inner = lock(&self.inner);
        match &inner.current {
            Some(current) if current.number == number => Some(current.consent),
            _ => (inner.ended.iter())
                .rev()
                .find(|(n, _)| *n == number)
                .map(|(_, consent)| *consent),
        }
    }

    /// A visitor touched the screen of kiosk `client` (a trigger, a page): starts a session
    /// when none runs and the site starts them so; keeps one going that a touch started.
    /// Called before the touch's own events, so that they are in the session.
    pub fn touched(&self, settings: &CorpusSettings, client: u64) {
        let mut inner = lock(&self.inner);
        match &mut inner.current {
            Some(current) => current.last_touch = Instant::now(),
            None if settings.session_start == SessionStart::Touch => {
                self.begin(&mut inner, settings, Source::Kiosk, Some(client), true);
                self.started_by_touch.notify_one();
            }
            None => {}
        }
    }

    /// The robot noticed `event` (adapter process `client`): starts a session when none runs,
    /// the site starts them by touch and `start_events` names it (source `adapter`); keeps
    /// one going that started on its own (a touch or such an event), as a touch does. Called
    /// before the event's own line, so that it is in the session.
    pub fn robot_noticed(
        &self,
        settings: &CorpusSettings,
        start_events: &[String],
        client: Option<u64>,
        event: &str,
    ) {
        if !start_events.iter().any(|e| e == event) {
            return;
        }
        let mut inner = lock(&self.inner);
        match &mut inner.current {
            Some(current) => current.last_touch = Instant::now(),
            None if settings.session_start == SessionStart::Touch => {
                self.begin(&mut inner, settings, Source::Adapter, client, true);
                self.started_by_touch.notify_one();
            }
            None => {}
        }
    }

    /// Ends a session that a touch started once `settings()` idle time passed without a
    /// touch, until `shutdown`. The settings are read anew each time (live reload).
    pub async fn end_idle_sessions(
        self: Arc<Self>,
        settings: impl Fn() -> CorpusSettings,
        shutdown: CancellationToken,
    ) {
        loop {
            let deadline = self.idle_deadline(settings().session_idle);
            let wait = async {
                match deadline {
                    Some(deadline) => tokio::time::sleep_until(deadline).await,
                    None => std::future::pending().await,
                }
            };
            tokio::select! {
                () = wait => {}
                () = self.started_by_touch.notified() => continue,
                () = shutdown.cancelled() => return,
            }
            let idle = settings().session_idle;
            let mut inner = lock(&self.inner);
            let overdue = (inner.current.as_ref()).is_some_and(|c| {
                c.by_touch && !idle.is_zero() && c.last_touch + idle <= Instant::now()
            });
            if overdue && let Some(ended) = inner.take_current() {
                self.publish_end(ended.number, Source::Server, None, SessionEnd::Idle);
            }
        }
    }

    /// When the running session ends for want of touches, if it is one a touch started.
    fn idle_deadline(&self, idle: Duration) -> Option<Instant> {
        let inner = lock(&self.inner);
        let current = inner.current.as_ref()?;
        (current.by_touch && !idle.is_zero()).then(|| current.last_touch + idle)
    }

    fn begin(
        &self,
        inner: &mut Inner,
        settings: &CorpusSettings,
        source: Source,
        client: Option<u64>,
        by_touch: bool,
    ) -> u64 {
        if let Some(ended) = inner.take_current() {
            self.publish_end(ended.number, source, client, SessionEnd::NextSession);
        }
        inner.last += 1;
        let number = inner.last;
        inner.current = Some(Current {
            number,
            consent: settings.consent,
            by_touch,
            last_touch: Instant::now(),
        });
        let shown = (self.shown)();
        self.hub.publish(EventKind::SessionStarted(SessionStarted {
            session: number,
            source,
            client,
            consent: settings.consent,
            page: shown.page,
            projector: shown.projector,
        }));
        number
    }

    fn publish_end(&self, session: u64, source: Source, client: Option<u64>, reason: SessionEnd) {
        self.hub.publish(EventKind::SessionEnded(SessionEnded {
            session,
            source,
            client,
            reason,
        }));
        (self.after_end)();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn touch_starts(idle: Duration) -> CorpusSettings {
        CorpusSettings {
            session_start: SessionStart::Touch,
            session_idle: idle,
            ..CorpusSettings::default()
        }
    }

    #[test]
    fn starting_a_session_ends_the_running_one() {
        let (hub, _feed) = Hub::new();
        let visits = Visits::new(hub, Box::new(Display::default), Box::new(|| {}));
        let settings = CorpusSettings::default();
        assert_eq!(visits.current(), None);
        assert_eq!(visits.start(&settings, Source::Operator, Some(1)), 1);
        assert_eq!(visits.start(&settings, Source::Operator, Some(1)), 2);
        assert_eq!(visits.current(), Some(2));
        assert_eq!(
            visits.end(Source::Operator, Some(1), SessionEnd::Marked),
            Some(2)
        );
        assert_eq!(
            visits.end(Source::Operator, Some(1), SessionEnd::Marked),
            None
        );
        assert_eq!(visits.start(&settings, Source::Dm, None), 3);
    }

    #[test]
    fn every_end_of_a_session_is_followed_by_its_step_at_once() {
        let (hub, _corpus) = Hub::new();
        let steps = Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let counted = Arc::clone(&steps);
        let after_end = Box::new(move || {
            counted.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        });
        let visits = Visits::new(hub, Box::new(Display::default), after_end);
        let settings = CorpusSettings::default();
        let ends = || steps.load(std::sync::atomic::Ordering::SeqCst);
        visits.start(&settings, Source::Operator, None);
        assert_eq!(ends(), 0, "a start ends nothing");
        visits.start(&settings, Source::Operator, None);
        assert_eq!(ends(), 1, "the next session ended the first");
        visits.end(Source::Operator, None, SessionEnd::Marked);
        assert_eq!(ends(), 2);
        assert_eq!(visits.end(Source::Operator, None, SessionEnd::Marked), None);
        assert_eq!(ends(), 2, "no session, no end");
    }

    #[test]
    fn consent_needs_a_session_and_once_withdrawn_stays_withdrawn() {
        let (hub, _feed) = Hub::new();
        let visits = Visits::new(hub, Box::new(Display::default), Box::new(|| {}));
        let set = |consent, confirmed| visits.set_consent(consent, confirmed, Source::Operator, 1);
        let refused = set(Consent::Declined, Confirmation::Confirmed);
        assert_eq!(refused, Err(ConsentRefused::NoSession));
        visits.start(&CorpusSettings::default(), Source::Operator, Some(1));
        assert_eq!(set(Consent::Declined, Confirmation::Confirmed), Ok(1));
        assert_eq!(set(Consent::Recorded, Confirmation::Unconfirmed), Ok(1));
        assert_eq!(set(Consent::Withdrawn, Confirmation::Confirmed), Ok(1));
        let again = set(Consent::Recorded, Confirmation::Unconfirmed);
        assert_eq!(again, Err(ConsentRefused::Withdrawn));
    }

    #[test]
    fn a_refusal_that_deletes_recordings_needs_confirming_and_one_that_deletes_nothing_does_not() {
        let (hub, _feed) = Hub::new();
        let visits = Visits::new(hub, Box::new(Display::default), Box::new(|| {}));
        let set = |consent, confirmed| visits.set_consent(consent, confirmed, Source::Operator, 1);
        visits.start(&CorpusSettings::default(), Source::Operator, Some(1));
        for refusal in [Consent::Declined, Consent::Withdrawn] {
            let slip = set(refusal, Confirmation::Unconfirmed);
            assert_eq!(slip, Err(ConsentRefused::Unconfirmed));
            assert_eq!(visits.consent(), Some(Consent::Recorded), "nothing changed");
        }
        assert_eq!(set(Consent::Declined, Confirmation::Confirmed), Ok(1));
        // From declined nothing was recorded: withdrawing deletes nothing more.
        assert_eq!(set(Consent::Withdrawn, Confirmation::Unconfirmed), Ok(1));
    }

    #[test]
    fn a_touch_starts_a_session_only_when_the_site_says_so() {
        let (hub, _feed) = Hub::new();
        let visits = Visits::new(hub, Box::new(Display::default), Box::new(|| {}));
        let marked = CorpusSettings {
            session_start: SessionStart::Marked,
            ..touch_starts(Duration::from_secs(60))
        };
        visits.touched(&marked, 7);
        assert_eq!(visits.current(), None);
        visits.touched(&touch_starts(Duration::from_secs(60)), 7);
        assert_eq!(visits.current(), Some(1));
        visits.touched(&touch_starts(Duration::from_secs(60)), 8);
        assert_eq!(visits.current(), Some(1), "a running session goes on");
    }

    #[tokio::test(start_paused = true)]
    async fn a_session_a_touch_started_ends_after_the_idle_time_without_a_touch() {
        let (hub, _feed) = Hub::new();
        let mut events = hub.subscribe();
        let visits = Arc::new(Visits::new(
            hub,
            Box::new(Display::default),
            Box::new(|| {}),
        ));
        let idle = Duration::from_secs(120);
        let shutdown = CancellationToken::new();
        let watch = tokio::spawn(
            Arc::clone(&visits).end_idle_sessions(move || touch_starts(idle), shutdown.clone()),
        );
        visits.touched(&touch_starts(idle), 7);
        let began = Instant::now();
        tokio::time::sleep(Duration::from_secs(100)).await;
        visits.touched(&touch_starts(idle), 7);
        assert_eq!(visits.current(), Some(1), "kept going by the touch");
        loop {
            let event = events.recv().await.unwrap();
            if let EventKind::SessionEnded(SessionEnded { reason, source, .. }) = &event.kind {
                assert_eq!((*reason, *source), (SessionEnd::Idle, Source::Server));
                break;
            }
        }
        assert_eq!(
            began.elapsed(),
            Duration::from_secs(220),
            "120 s after the last touch"
        );
        assert_eq!(visits.current(), None);
        // A marked session does not end for want of touches.
        visits.start(&touch_starts(idle), Source::Operator, Some(1));
        tokio::time::sleep(Duration::from_secs(1000)).await;
        assert_eq!(visits.current(), Some(2));
        shutdown.cancel();
        watch.await.unwrap();
    }
}
