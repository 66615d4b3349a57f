#!/usr/bin/env python3
"""Reads a session's MCAP export back with the `mcap` Python reader (the one Foxglove
publishes), checks every message against its channel's JSON Schema with `jsonschema`, and
prints what was read, with every problem found, as one JSON object (tests/corpus_export.rs
compares it with the session's log, channel by channel, time by time, text by text).

    check_mcap.py FILE.mcap

Read twice: record by record (StreamReader, every CRC checked, chunks kept whole) for the
file's layout, and through the summary (SeekingReader) for the messages, as a player does.
Checked here, beyond what the reader itself refuses:

- layout: the header; chunks, all lz4, each followed by its message indexes; a summary with
  schemas, channels, chunk indexes, statistics, metadata indexes and summary offsets, the
  footer pointing at it; the statistics' counts equal to what was read; a seek into the middle
  gives exactly the later messages;
- every schema `jsonschema`-encoded and a valid JSON Schema, every channel `json`-encoded,
  every message valid against its schema;
- per channel, log times in order in the file, `publish_time` equal to `log_time`, every log
  time within the session (from `docent.session`'s `session_clock_zero_ns` to its end);
- what the schemas let pass: a `foxglove.Log` has all its fields, a level Foxglove names other
  than UNKNOWN, its timestamp equal to its log time and its name the type of the line it
  carries; a pose's quaternion is of unit length and turns about z only, its timestamp is its
  log time; an interval does not end before it starts, and its log time is its start.
"""

import io
import json
import math
import sys
from collections import defaultdict

import jsonschema
from mcap.reader import SeekingReader
from mcap.records import Chunk, Footer
from mcap.stream_reader import StreamReader

PROBLEMS = []
LOG_LEVELS = {1: "DEBUG", 2: "INFO", 3: "WARNING", 4: "ERROR", 5: "FATAL"}
LOG_FIELDS = {"timestamp", "level", "message", "name", "file", "line"}


def problem(message):
    if len(PROBLEMS) < 50:
        PROBLEMS.append(message)


def ns(time):
    return time["sec"] * 1_000_000_000 + time["nsec"]


def layout(data):
    """The file's records in order: the layout checks, and the chunks' compressions."""
    kinds = []
    compressions = set()
    footer = None
    for record in StreamReader(io.BytesIO(data), emit_chunks=True, validate_crcs=True).records:
        kinds.append(type(record).__name__)
        if isinstance(record, Chunk):
            compressions.add(record.compression)
        if isinstance(record, Footer):
            footer = record
    if not kinds or kinds[0] != "Header":
        problem(f"the file does not begin with a header: {kinds[:1]}")
    if "DataEnd" not in kinds:
        problem("no DataEnd record")
        return sorted(compressions)
    data_end = kinds.index("DataEnd")
    data_section, summary = kinds[:data_end], kinds[data_end + 1:]
    if "Message" in data_section:
        problem("messages outside chunks")
    if "Chunk" not in data_section:
        problem("no chunk")
    for n, kind in enumerate(data_section):
        if kind == "Chunk" and (n + 1 >= len(data_section) or data_section[n + 1] != "MessageIndex"):
            problem(f"the chunk at record {n} is not followed by its message indexes")
    for kind in ["Schema", "Channel", "ChunkIndex", "Statistics", "MetadataIndex",
                 "SummaryOffset"]:
        if kind not in summary:
            problem(f"the summary has no {kind} record")
    if footer is None or footer.summary_start == 0 or footer.summary_offset_start == 0:
        problem(f"the footer does not point at the summary: {footer}")
    return sorted(compressions)


def main():
    path = sys.argv[1]
    with open(path, "rb") as f:
        data = f.read()
    compressions = layout(data)
    reader = SeekingReader(io.BytesIO(data), validate_crcs=True)
    header = reader.get_header()
    summary = reader.get_summary()
    if summary is None:
        print(json.dumps({"problems": ["no summary: a player cannot seek"]}))
        return
    if not summary.chunk_indexes:
        problem("no chunk index in the summary")

    validators = {}
    for schema_id, schema in summary.schemas.items():
        if schema.encoding != "jsonschema":
            problem(f"schema {schema.name}: encoding {schema.encoding!r}, not jsonschema")
        document = json.loads(schema.data)
        try:
            jsonschema.Draft202012Validator.check_schema(document)
        except jsonschema.SchemaError as e:
            problem(f"schema {schema.name} is not a valid JSON Schema: {e.message}")
        if document.get("title") != schema.name:
            problem(f"schema {schema.name} has the title {document.get('title')!r}")
        validators[schema_id] = jsonschema.Draft202012Validator(document)

    metadata = defaultdict(list)
    for record in reader.iter_metadata():
        metadata[record.name].append(dict(record.metadata))
    session = (metadata.get("docent.session") or [{}])[0]
    zero = int(session.get("session_clock_zero_ns", "0"))
    if "ended.mono_us" in session:
        length_us = int(session["ended.mono_us"]) - int(session["started.mono_us"])
    else:
        length_us = None

    channels = {}
    counts = defaultdict(int)
    last_time = {}
    for schema, channel, message in reader.iter_messages(log_time_order=False):
        counts[channel.id] += 1
        topic = channel.topic
        if topic not in channels:
            if channel.message_encoding != "json":
                problem(f"{topic}: message encoding {channel.message_encoding!r}, not json")
            channels[topic] = {"schema": schema.name if schema else None, "messages": []}
        where = f"{topic} message {counts[channel.id]}"
        t = message.log_time
        if t < last_time.get(topic, 0):
            problem(f"{where}: log time {t} before the previous message's")
        last_time[topic] = t
        if message.publish_time != t:
            problem(f"{where}: publish time {message.publish_time} is not its log time {t}")
        if t < zero or (length_us is not None and t > zero + length_us * 1000):
            problem(f"{where}: log time {t} outside the session")
        body = json.loads(message.data)
        if schema is None:
            problem(f"{where}: no schema")
        else:
            for error in validators[schema.id].iter_errors(body):
                problem(f"{where}: not a valid {schema.name}: {error.message}")
        check(schema.name if schema else None, body, t, zero, where)
        channels[topic]["messages"].append([t, body])

    statistics = summary.statistics
    read_count = sum(counts.values())
    if statistics is None:
        problem("the summary has no statistics")
    else:
        if statistics.message_count != read_count:
            problem(f"statistics count {statistics.message_count} messages, {read_count} read")
        if dict(statistics.channel_message_counts) != dict(counts):
            problem(f"statistics count per channel {statistics.channel_message_counts}, read {dict(counts)}")
        if statistics.metadata_count != sum(len(v) for v in metadata.values()):
            problem("statistics count another number of metadata records")
    if len(summary.metadata_indexes) != sum(len(v) for v in metadata.values()):
        problem("not every metadata record is indexed")
    seek(reader, channels)

    print(json.dumps({
        "problems": PROBLEMS,
        "profile": header.profile,
        "library": header.library,
        "compressions": compressions,
        "channels": channels,
        "metadata": metadata,
        "attachments": [a.name for a in reader.iter_attachments()],
    }))


def seek(reader, channels):
    """A seek to the middle of the session, as a player's, gives exactly the later messages."""
    times = sorted(t for c in channels.values() for t, _ in c["messages"])
    if not times:
        return
    middle = times[len(times) // 2]
    want = sum(1 for t in times if t >= middle)
    got = sum(1 for _ in reader.iter_messages(starting_at=middle))
    if got != want:
        problem(f"a seek to {middle} gave {got} messages, not {want}")


def check(schema, body, t, zero, where):
    """What the schemas let pass."""
    if schema == "foxglove.Log":
        if set(body) != LOG_FIELDS:
            problem(f"{where}: a Log with the fields {sorted(body)}")
            return
        if body["level"] not in LOG_LEVELS:
            problem(f"{where}: level {body['level']} is no level Foxglove names (or UNKNOWN)")
        if ns(body["timestamp"]) != t:
            problem(f"{where}: timestamp {body['timestamp']} is not its log time {t}")
        try:
            line = json.loads(body["message"])
            if line.get("type") != body["name"] or line.get("session_us") * 1000 + zero != t:
                problem(f"{where}: name or time differ from the line it carries")
        except (ValueError, TypeError, AttributeError):
            problem(f"{where}: the message is not a log line: {body['message'][:80]!r}")
    elif schema == "foxglove.PoseInFrame":
        try:
            q = body["pose"]["orientation"]
            norm = math.sqrt(sum(q[k] ** 2 for k in "xyzw"))
            if abs(norm - 1) > 1e-9 or q["x"] != 0 or q["y"] != 0:
                problem(f"{where}: orientation {q} is not a unit turn about z")
            if ns(body["timestamp"]) != t or not body["frame_id"]:
                problem(f"{where}: timestamp or frame wrong: {body}")
            if set(body["pose"]["position"]) != {"x", "y", "z"}:
                problem(f"{where}: position {body['pose']['position']}")
        except KeyError as e:
            problem(f"{where}: a pose without {e}")
    elif schema is not None:
        start = body.get("start_us", body.get("at_us"))
        if "end_us" in body and body["end_us"] < start:
            problem(f"{where}: ends at {body['end_us']}, before its start {start}")
        if zero + start * 1000 != t:
            problem(f"{where}: log time {t} is not its start {start} µs")


if __name__ == "__main__":
    main()
