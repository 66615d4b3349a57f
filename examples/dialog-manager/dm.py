#!/usr/bin/env python3
"""An example autonomous dialog manager for Docent: the starting point for a site's own.

It connects to Docent's websocket with the dialog-manager role, reads robot, touch, display
and speech events, and decides with `policy.py` when to greet a person who comes close, move
the tour on when a video ends, and offer help to a visitor idle on a page. In
mixed-initiative mode (`--mode mixed`, the default) it proposes each act to the operators,
who accept or dismiss it in the console; in autonomous mode (`--mode autonomous`) it
triggers the act itself. Run it with one command (see README.md):

    examples/dialog-manager/run.sh --url ws://127.0.0.1:8080/ws --token "$DOCENT_DM_TOKEN"

Nothing fails silently: a wrong credential or an act the bundle lacks stops it at once with
the reason; a lost connection is said and retried with back-off; every refusal Docent sends
is printed.
"""

import argparse
import asyncio
import json
import random
import sys
import time
import urllib.error
import urllib.request

import websockets

from policy import Policy, Settings


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--url", default="ws://127.0.0.1:8080/ws", help="Docent's websocket")
    p.add_argument("--token", required=True, help="the dialog-manager credential (DOCENT_DM_TOKEN)")
    p.add_argument("--mode", choices=["mixed", "autonomous"], default="mixed",
                   help="propose acts to the operator (mixed) or trigger them (autonomous)")
    p.add_argument("--name", default="example-dm", help="the name operators see")
    p.add_argument("--greet-act", default="GREETING")
    p.add_argument("--greet-event", default="person.near", help="the robot event of a person close by")
    p.add_argument("--greet-within", type=float, default=1.5, help="metres (the event's data.distance)")
    p.add_argument("--after-video", action="append", default=None, metavar="ACT=NEXT",
                   help="when ACT's PROJECT film ends, NEXT follows (repeatable)")
    p.add_argument("--help-act", default="ANY_QUESTIONS")
    p.add_argument("--idle", type=float, default=45.0, help="seconds idle on a page before help")
    p.add_argument("--home", default="index.html", help="the kiosk's home page (no help offered there)")
    p.add_argument("--once", action="store_true", help="exit when the connection ends (for tests)")
    args = p.parse_args(argv)
    after = {"VIDEO_CARD_PUNCH": "GO_TO_HOME_COMPUTER"}
    if args.after_video is not None:
        after = {}
        for pair in args.after_video:
            act, sep, following = pair.partition("=")
            if not sep or not act or not following:
                p.error(f"--after-video takes ACT=NEXT, got {pair!r}")
            after[act] = following
    settings = Settings(args.greet_act, args.greet_event, args.greet_within, after,
                        args.help_act, args.idle, args.home)
    return args, settings


def check_labels(ws_url, token, labels):
    """Asks Docent for the bundle's acts; stops with the reason if one the settings name is
    missing, rather than proposing acts that can never run."""
    http = ws_url.replace("ws://", "http://", 1).replace("wss://", "https://", 1)
    http = http.rsplit("/ws", 1)[0] + "/api/acts"
    request = urllib.request.Request(http, headers={"Authorization": f"Bearer {token}"})
    try:
        with urllib.request.urlopen(request, timeout=10) as response:
            acts = {a["label"] for a in json.load(response)["acts"]}
    except urllib.error.HTTPError as e:
        sys.exit(f"dm: Docent refused {http}: {e.code} {e.read().decode(errors='replace')}")
    except (urllib.error.URLError, OSError) as e:
        sys.exit(f"dm: cannot reach Docent at {http}: {e}")
    missing = sorted(labels - acts)
    if missing:
        sys.exit(f"dm: the bundle has no act {', '.join(missing)}; "
                 f"give existing labels with --greet-act, --after-video or --help-act")


class Session:
    """One websocket connection: hello, the history, then live events and the clock."""

    def __init__(self, ws, args, policy):
        self.ws, self.args, self.policy = ws, args, policy
        self.me = None
        self.live = False
        self.sent = 0

    async def run(self):
        await self.ws.send(json.dumps({"type": "hello", "role": "dm", "name": self.args.name,
                                       "token": self.args.token}))
        while True:
            deadline = self.policy.deadline()
            timeout = None if deadline is None else max(0.0, deadline - time.monotonic())
            try:
                text = await asyncio.wait_for(self.ws.recv(), timeout)
            except asyncio.TimeoutError:
                await self.act(self.policy.tick(time.monotonic()))
                continue
            await self.frame(json.loads(text))

    async def frame(self, frame):
        kind = frame.get("type")
        if kind == "welcome":
            self.me = frame["client"]
            print(f"dm: connected as client {self.me}, {self.args.mode} mode", flush=True)
        elif kind == "event":
            event = frame["event"]
            # History comes first; the live stream starts with our own client.connected.
            if event.get("type") == "client.connected" and event.get("client") == self.me:
                self.live = True
            await self.act(self.policy.observe(event, time.monotonic(), self.live))
        elif kind == "error":
            code, message = frame.get("code"), frame.get("message")
            if code in ("unauthorized", "too-many-attempts", "forbidden"):
                sys.exit(f"dm: Docent refused this dialog manager ({code}): {message}")
            print(f"dm: Docent answered {code}: {message}", file=sys.stderr, flush=True)

    async def act(self, actions):
        for action in actions:
            self.sent += 1
            ref = f"dm-{self.sent}"
            if self.args.mode == "autonomous":
                frame = {"type": "trigger", "label": action.label, "ref": ref}
            else:
                frame = {"type": "propose", "label": action.label, "reason": action.reason, "ref": ref}
            print(f"dm: {frame['type']} {action.label}: {action.reason}", flush=True)
            await self.ws.send(json.dumps(frame))


async def main(argv):
    args, settings = parse_args(argv)
    check_labels(args.url, args.token, settings.labels())
    policy = Policy(settings)
    backoff = 0.5
    while True:
        try:
            async with websockets.connect(args.url) as ws:
                backoff = 0.5
                await Session(ws, args, policy).run()
        except (OSError, websockets.ConnectionClosed) as e:
            if args.once:
                print(f"dm: connection ended: {e}", flush=True)
                return
            wait = backoff * (0.5 + random.random())
            print(f"dm: lost Docent at {args.url} ({e}); trying again in {wait:.1f} s",
                  file=sys.stderr, flush=True)
            await asyncio.sleep(wait)
            backoff = min(backoff * 2, 10.0)


if __name__ == "__main__":
    try:
        asyncio.run(main(sys.argv[1:]))
    except KeyboardInterrupt:
        pass
