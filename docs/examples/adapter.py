#!/usr/bin/env python3
"""An external Docent adapter: a process that serves verbs over Docent's websocket.

It connects to ws://HOST:PORT/ws, says hello with role "adapter" and the verbs it serves,
then carries out every `command` frame Docent sends and answers `started`, then `done` or
`failed`. A `cancel` frame drops queued commands and cuts the running one short. When the
connection drops, it connects again.

On the robot itself (Docent on the same machine) the adapter needs no credential. Connecting
to Docent on another machine, it must show the dialog-manager credential: set the
environment variable DOCENT_DM_TOKEN and it is sent as `token` in hello. A refused
credential ends the adapter instead of retrying (after five wrong or missing credentials in a
row, Docent lets this machine try only once every 10 seconds).

Commands run in lanes. A lane is a queue that runs its commands one at a time, in the order
they arrived. Verbs that must stay in order with each other share a lane (a drive's
SET_WAYPOINT, DRIVE_START and DRIVE_STOP); verbs of separate devices get separate lanes, so a
long SAY does not hold up the lights.

    pip install websockets
    python3 adapter.py --url ws://127.0.0.1:8080/ws --lane SAY --lane LIGHTS
    python3 adapter.py --lane SET_WAYPOINT,DRIVE_START,DRIVE_STOP
    DOCENT_DM_TOKEN=... python3 adapter.py --url ws://robot.local:8080/ws --lane SAY

Replace the functions in HANDLERS with code for your devices. See docs/ADAPTERS.md.
"""

import argparse
import asyncio
import json
import logging
import os
import sys

import websockets

log = logging.getLogger("adapter")


# --- What each verb does. Replace these with calls to your hardware. ---------------------------
# A handler gets the command's argument (a string, or None) and returns when the command is
# done. Raising an exception reports `failed` with the exception's message as the reason.
# Cancellation arrives as asyncio.CancelledError: stop the device, then let it propagate.


async def say(arg):
    words = len((arg or "").split())
    log.info("SAY %r", arg)
    await asyncio.sleep(words * 60 / 160 + 0.1)  # pretend to speak at 160 words per minute


async def lights(arg):
    if arg not in ("on", "off", "dim"):
        raise ValueError(f"LIGHTS takes on, off or dim, not {arg!r}")
    log.info("LIGHTS %s", arg)
    await asyncio.sleep(0.2)


async def drive_start(arg):
    log.info("DRIVE_START")
    try:
        await asyncio.sleep(3)  # pretend to drive to the waypoint
    except asyncio.CancelledError:
        log.info("motors stopped")  # a real drive must stop the motors here
        raise


async def anything(verb, arg):
    log.info("%s %s", verb, arg or "")


HANDLERS = {"SAY": say, "LIGHTS": lights, "DRIVE_START": drive_start}


async def run_command(verb, arg):
    handler = HANDLERS.get(verb)
    if handler is None:
        await anything(verb, arg)
    else:
        await handler(arg)


# --- The protocol side: usually left as it is. ---------------------------------------------------


class Refused(Exception):
    """Docent refused the credential (or its absence): connecting again would not help."""


class Lane:
    """Runs the commands of some verbs one at a time, in arrival order."""

    def __init__(self, verbs, send):
        self.verbs = set(verbs)
        self.send = send
        self.queue = asyncio.Queue()
        self.current = None  # (command id, task) while a command runs
        self.closing = False
        self.worker = asyncio.create_task(self.work())

    async def work(self):
        while True:
            frame = await self.queue.get()
            cid = frame["id"]
            # `started` stops this connection's answer clock (adapters.timeout): the command
            # may then take as long as it needs.
            await self.send({"type": "started", "id": cid})
            task = asyncio.create_task(run_command(frame["verb"], frame.get("arg")))
            self.current = (cid, task)
            try:
                await task
            except asyncio.CancelledError:
                if self.closing or not task.cancelled():
                    raise  # the lane itself is being closed
                # Cancelled by a `cancel` frame: Docent already logged it; send nothing.
                continue
            except Exception as e:  # the device failed
                await self.send({"type": "failed", "id": cid, "reason": str(e) or repr(e)})
            else:
                await self.send({"type": "done", "id": cid})
            finally:
                self.current = None

    def cancel(self, verbs, reason):
        """Drops queued commands of `verbs` (None: all) and cuts the running one short."""
        kept = []
        while not self.queue.empty():
            frame = self.queue.get_nowait()
            if verbs is None or frame["verb"] in verbs:
                log.info("dropped command %s (%s): %s", frame["id"], frame["verb"], reason)
            else:
                kept.append(frame)
        for frame in kept:
            self.queue.put_nowait(frame)
        if self.current is not None:
            cid, task = self.current
            log.info("cancelling command %s: %s", cid, reason)
            task.cancel()

    def close(self):
        self.closing = True
        self.worker.cancel()  # also cancels the running command


async def serve(url, name, lane_specs, token):
    verbs = [verb for spec in lane_specs for verb in spec]
    async with websockets.connect(url) as ws:
        lock = asyncio.Lock()

        async def send(frame):
            async with lock:
                try:
                    await ws.send(json.dumps(frame))
                except websockets.ConnectionClosed:
                    pass  # the loop below notices too, and main() connects again

        hello = {"type": "hello", "role": "adapter", "name": name, "verbs": verbs}
        if token:
            hello["token"] = token  # the dialog-manager credential; never logged
        await send(hello)
        welcome = json.loads(await ws.recv())
        if welcome.get("type") == "error" and welcome["code"] in ("unauthorized",
                                                                  "too-many-attempts"):
            # Docent closes the connection after this frame.
            raise Refused(f'{welcome["code"]}: {welcome["message"]}')
        if welcome.get("type") != "welcome":
            raise RuntimeError(f"Docent refused the hello: {welcome}")
        log.info("connected as client %s (protocol %s), serving %s",
                 welcome["client"], welcome["protocol"], ", ".join(verbs))
        lanes = [Lane(spec, send) for spec in lane_specs]
        lane_of = {verb: lane for lane in lanes for verb in lane.verbs}
        try:
            async for text in ws:
                frame = json.loads(text)
                kind = frame.get("type")
                if kind == "command":
                    lane_of[frame["verb"]].queue.put_nowait(frame)
                elif kind == "cancel":
                    wanted = frame["verbs"]  # null means every verb
                    for lane in lanes:
                        if wanted is None or lane.verbs & set(wanted):
                            lane.cancel(None if wanted is None else set(wanted), frame["reason"])
                elif kind == "error":
                    # `unknown-command`: an answer with an id Docent does not know (answers to
                    # commands it settled lately, e.g. cancelled or timed out, are ignored
                    # without an error). `verb-not-routed` (once, right after the welcome):
                    # docent.yaml sends some of our verbs elsewhere; check the set-up.
                    log.warning("Docent says %s: %s", frame["code"], frame["message"])
        finally:
            for lane in lanes:
                lane.close()


async def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--url", default="ws://127.0.0.1:8080/ws")
    parser.add_argument("--name", default="python-adapter")
    parser.add_argument("--lane", action="append", required=True, metavar="VERB[,VERB...]",
                        help="verbs that run one after another; give --lane once per lane")
    args = parser.parse_args()
    lane_specs = [[v.strip() for v in lane.split(",") if v.strip()] for lane in args.lane]
    # Needed only when Docent runs on another machine; from the environment, so it stays out
    # of the command line (which other users of the machine can see).
    token = os.environ.get("DOCENT_DM_TOKEN") or None
    delay = 1
    while True:
        try:
            await serve(args.url, args.name, lane_specs, token)
            delay = 1
            log.warning("Docent closed the connection; connecting again in %s s", delay)
        except Refused as e:
            hint = "check DOCENT_DM_TOKEN" if token else "set DOCENT_DM_TOKEN"
            log.error("Docent refused this adapter (%s); %s and start again", e, hint)
            return 1
        except (OSError, websockets.ConnectionClosed) as e:
            log.warning("connection lost (%s); connecting again in %s s", e, delay)
        await asyncio.sleep(delay)
        delay = min(delay * 2, 30)


if __name__ == "__main__":
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(name)s %(message)s")
    try:
        sys.exit(asyncio.run(main()))
    except KeyboardInterrupt:
        pass
