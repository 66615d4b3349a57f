"""What the example dialog manager decides, apart from how it talks to Docent (dm.py).

It watches Docent's event stream and decides three things a museum robot's operator does
by hand today, so that an operator can hand them over one by one (the paper's migration
path from Wizard of Oz to autonomy):

- greet a person who comes close: a `robot` event (`person.near`) closer than a distance,
  while no visitor session runs or at its start, at most once per visitor session;
- move the tour on when a video ends: the `PROJECT` command of a listed act is done (the
  projector reports the film's end), so the next act of the tour follows;
- offer help after a visitor has been idle on a page: a visitor session runs, the kiosk
  shows a page other than the home page, and nothing happened there (no touch, no speech,
  no page change) for a while; offered once per page shown.

Each decision is an `Action`: the act, and the reason an operator reads in mixed-initiative
mode. The policy never sends anything itself, so it can be tested without a server.
"""

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Action:
    """An act the dialog manager wants, and why (shown to the operator with a proposal)."""

    label: str
    reason: str


@dataclass
class Settings:
    """What the behaviours react to; every act label is checked against the bundle at start."""

    greet_act: str = "GREETING"
    greet_event: str = "person.near"
    greet_within_m: float = 1.5
    after_video: dict = field(default_factory=lambda: {"VIDEO_CARD_PUNCH": "GO_TO_HOME_COMPUTER"})
    help_act: str = "ANY_QUESTIONS"
    idle_seconds: float = 45.0
    home_page: str = "index.html"

    def labels(self):
        """Every act label these settings name."""
        return {self.greet_act, self.help_act, *self.after_video, *self.after_video.values()}


class Policy:
    """Follows the event stream (`observe`) and the clock (`tick`); both return actions."""

    def __init__(self, settings: Settings):
        self.settings = settings
        self.session = None  # the running visitor session's id
        self.greeted_in = set()  # sessions (or None: between sessions) already greeted
        self.page = None  # the page the kiosk shows
        self.last_activity = None  # when something last happened on it (seconds, monotonic)
        self.helped_on = None  # the page help was last offered on (once per page shown)
        self.video_acts = {}  # trigger id -> act label, for the acts whose film ends the step

    def observe(self, event: dict, now: float, live: bool = True) -> list:
        """Takes one event; `live` is false for the history a joining client is sent, which
        sets the state (a session already running) but triggers nothing."""
        kind = event.get("type")
        actions = []
        if kind == "session.started":
            self.session = event.get("session")
            self.last_activity = now
        elif kind == "session.ended":
            self.session = None
            self.helped_on = None
        elif kind == "display.changed" and event.get("page") != self.page:
            self.page = event.get("page")
            self.last_activity = now
            self.helped_on = None
        elif kind in ("touch", "act.triggered", "command.started", "command.done"):
            self.last_activity = now
        if not live:
            return actions
        if kind == "robot" and event.get("event") == self.settings.greet_event:
            actions += self._greet(event)
        if kind == "act.triggered" and event.get("label") in self.settings.after_video:
            self.video_acts[event.get("trigger")] = event.get("label")
        if kind == "command.done" and event.get("verb") == "PROJECT":
            label = self.video_acts.pop(event.get("trigger"), None)
            if label is not None:
                following = self.settings.after_video[label]
                actions.append(Action(following, f"the video of {label} has ended"))
        if kind in ("command.failed", "command.cancelled") and event.get("verb") == "PROJECT":
            # A film that did not play to its end does not move the tour on.
            self.video_acts.pop(event.get("trigger"), None)
        return actions

    def _greet(self, event: dict) -> list:
        distance = (event.get("data") or {}).get("distance")
        if not isinstance(distance, (int, float)) or distance > self.settings.greet_within_m:
            return []
        if self.session in self.greeted_in:
            return []
        self.greeted_in.add(self.session)
        return [Action(self.settings.greet_act, f"a person came within {distance:.1f} m")]

    def deadline(self):
        """When `tick` may next act (monotonic seconds), or None when nothing is pending."""
        if self.session is None or self.last_activity is None:
            return None
        if self.page in (None, self.settings.home_page) or self.helped_on == self.page:
            return None
        return self.last_activity + self.settings.idle_seconds

    def tick(self, now: float) -> list:
        """Offers help once the visitor has been idle on a page for `idle_seconds`."""
        deadline = self.deadline()
        if deadline is None or now < deadline:
            return []
        self.helped_on = self.page
        idle = now - self.last_activity
        return [Action(self.settings.help_act, f"the visitor has been idle on {self.page} for {idle:.0f} s")]
