#!/usr/bin/env python3
"""Independent check of a gc2d-rs MCAP recording, read with the reference `mcap` Python package.

Usage: check_mcap.py RECORDING EXPECT.json

EXPECT.json says what the run produced (the Rust test writes it from the World it ran):
  frames_per_second   cadence of the recording
  time_step           the run's time step, s
  particle_counts     living particles at each recorded frame (may be a prefix for a killed run)
  walls_messages      number of /walls messages (complete recordings only)
  attachment          {"name": ..., "size": ...} of the scene attachment, or null
  truncated           true for the file of a run killed mid-way: no summary or footer is expected, and
                      at least `min_frames` whole frames must be readable
  min_frames          (truncated only) frames the writer had reported flushed before the kill

Every record is read in file order with mcap's StreamReader (CRCs validated); protobuf messages are decoded with the
FileDescriptorSet stored in the file (mcap-protobuf-support), JSON messages with the json module. Exits 1 listing the
failed checks, 0 when all pass.
"""

import json
import sys

from mcap.exceptions import McapError
from mcap.reader import make_reader
from mcap.records import Attachment, Channel, Footer, Message, Metadata, Schema
from mcap.stream_reader import StreamReader
from mcap_protobuf.decoder import DecoderFactory

MAGIC = b"\x89MCAP0\r\n"
SCENE_TOPICS = ("/particles", "/walls", "/contacts")
EXPECTED_TOPICS = {
    "/particles": ("foxglove.SceneUpdate", "protobuf", "protobuf"),
    "/walls": ("foxglove.SceneUpdate", "protobuf", "protobuf"),
    "/contacts": ("foxglove.SceneUpdate", "protobuf", "protobuf"),
    "/stats": ("gc2d.FrameStats", "jsonschema", "json"),
}
STATS_FIELDS = ("time", "particles", "kinetic", "potential", "elastic", "dissipated", "contacts", "mean_coordination")
DELETE_ALL = 1  # foxglove.SceneEntityDeletion.Type.ALL


class Checks:
    def __init__(self):
        self.failures = []
        self.passed = 0

    def expect(self, condition, message):
        if condition:
            self.passed += 1
        else:
            self.failures.append(message)
        return condition


def read_records(path, checks):
    """All records that can be read in file order, and the error that ended reading early (None if none)."""
    records = []
    error = None
    with open(path, "rb") as f:
        try:
            for record in StreamReader(f, validate_crcs=True).records:
                records.append(record)
        except (McapError, EOFError, ValueError, OSError, Exception) as e:  # truncated data ends in any of these
            error = e
    return records, error


def decode_frames(records, checks):
    """Decodes every message; returns {topic: [(log_time, decoded)]} in file order."""
    schemas = {r.id: r for r in records if isinstance(r, Schema)}
    channels = {r.id: r for r in records if isinstance(r, Channel)}
    factory = DecoderFactory()
    decoders = {}
    by_topic = {topic: [] for topic in EXPECTED_TOPICS}
    for r in records:
        if not isinstance(r, Message):
            continue
        channel = channels.get(r.channel_id)
        if not checks.expect(channel is not None, f"message on unknown channel {r.channel_id}"):
            continue
        if channel.message_encoding == "json":
            decoded = json.loads(r.data)
        else:
            decoder = decoders.get(channel.id)
            if decoder is None:
                decoder = factory.decoder_for(channel.message_encoding, schemas.get(channel.schema_id))
                decoders[channel.id] = decoder
            if not checks.expect(decoder is not None, f"no decoder for {channel.topic}"):
                continue
            decoded = decoder(r.data)
        by_topic.setdefault(channel.topic, []).append((r.log_time, decoded))
    return schemas, channels, by_topic


def check_topics(schemas, channels, checks):
    topics = {c.topic: c for c in channels.values()}
    checks.expect(set(topics) == set(EXPECTED_TOPICS), f"topics {sorted(topics)} != {sorted(EXPECTED_TOPICS)}")
    for topic, (schema_name, schema_encoding, message_encoding) in EXPECTED_TOPICS.items():
        channel = topics.get(topic)
        if channel is None:
            continue
        schema = schemas.get(channel.schema_id)
        checks.expect(
            schema is not None and schema.name == schema_name and schema.encoding == schema_encoding,
            f"{topic}: schema {schema and (schema.name, schema.encoding)} != {(schema_name, schema_encoding)}",
        )
        checks.expect(channel.message_encoding == message_encoding, f"{topic}: encoding {channel.message_encoding}")
    stats_schema = next((s for s in schemas.values() if s.name == "gc2d.FrameStats"), None)
    if stats_schema is not None:
        properties = json.loads(stats_schema.data).get("properties", {})
        checks.expect(all(f in properties for f in STATS_FIELDS), f"/stats schema lacks one of {STATS_FIELDS}")


def check_log_times(records, channels, checks):
    """Log times never decrease in file order and strictly increase on each topic."""
    last_any = -1
    last_by_topic = {}
    for r in records:
        if not isinstance(r, Message):
            continue
        topic = channels[r.channel_id].topic
        checks.expect(r.log_time >= last_any, f"{topic}: log time {r.log_time} after {last_any}")
        checks.expect(r.log_time > last_by_topic.get(topic, -1), f"{topic}: log time {r.log_time} not increasing")
        last_any = r.log_time
        last_by_topic[topic] = r.log_time


def check_particles(frames, stats, expect, checks, truncated):
    fps = expect["frames_per_second"]
    dt = expect["time_step"]
    counts = expect["particle_counts"]
    if truncated:
        checks.expect(len(frames) >= expect["min_frames"], f"{len(frames)} frames readable, {expect['min_frames']} flushed")
        # The kill may fall between a frame's flush and its report: one unreported frame is fine.
        checks.expect(len(frames) <= len(counts) + 1, f"{len(frames)} frames but only {len(counts)} reported")
    else:
        checks.expect(len(frames) == len(counts), f"{len(frames)} /particles frames, expected {len(counts)}")
    stats_by_time = dict(stats)
    for k, (log_time, update) in enumerate(frames):
        tick = k / fps
        t = log_time * 1e-9
        checks.expect(abs(t - tick) <= 0.5 * dt + 1e-9, f"frame {k} at t = {t:.9f} s, tick {tick:.9f} s")
        entities = list(update.entities)
        if k < len(counts):
            checks.expect(len(entities) == counts[k], f"frame {k}: {len(entities)} particles, expected {counts[k]}")
        checks.expect(
            len(update.deletions) == 1 and update.deletions[0].type == DELETE_ALL,
            f"frame {k}: /particles does not start by clearing the topic",
        )
        for e in entities:
            ok = (
                e.frame_id == "world"
                and len(e.triangles) == 1
                and len(e.lines) == 1
                and len(e.triangles[0].indices) == 3 * (len(e.triangles[0].points) - 2)
                and len(e.lines[0].points) == len(e.triangles[0].points) >= 3
                and all(p.z == e.triangles[0].points[0].z for p in e.triangles[0].points)
            )
            if not checks.expect(ok, f"frame {k}: entity {e.id} is not a fan-triangulated, outlined polygon"):
                break
        s = stats_by_time.get(log_time)
        if checks.expect(s is not None, f"frame {k}: no /stats message at its log time"):
            checks.expect(s["particles"] == len(entities), f"frame {k}: /stats particles {s['particles']}")
            checks.expect(abs(s["time"] - t) <= 1e-9, f"frame {k}: /stats time {s['time']} != {t}")
            checks.expect(all(f in s for f in STATS_FIELDS), f"frame {k}: /stats lacks one of {STATS_FIELDS}")


def check_contacts(frames, contacts, stats, checks):
    checks.expect(len(contacts) == len(frames), f"{len(contacts)} /contacts messages for {len(frames)} frames")
    stats_by_time = dict(stats)
    for log_time, update in contacts:
        lines = [line for e in update.entities for line in e.lines]
        s = stats_by_time.get(log_time)
        if s is not None:
            checks.expect(len(lines) <= s["contacts"], f"/contacts at {log_time}: {len(lines)} > {s['contacts']}")
        checks.expect(all(line.thickness > 0 and len(line.points) % 2 == 0 for line in lines), "bad force line")


def check_complete_file(path, expect, records, checks):
    with open(path, "rb") as f:
        data = f.read()
    checks.expect(data.endswith(MAGIC), "complete recording does not end with the MCAP magic")
    checks.expect(any(isinstance(r, Footer) for r in records), "complete recording has no footer")
    with open(path, "rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        if checks.expect(summary is not None and summary.statistics is not None, "no summary statistics"):
            counts = {summary.channels[c].topic: n for c, n in summary.statistics.channel_message_counts.items()}
            checks.expect(counts.get("/particles") == len(expect["particle_counts"]), f"summary counts {counts}")
        attachments = list(reader.iter_attachments())
        metadata = list(reader.iter_metadata())
    expected_attachment = expect.get("attachment")
    if expected_attachment is not None:
        checks.expect(
            any(a.name == expected_attachment["name"] and len(a.data) == expected_attachment["size"] for a in attachments),
            f"attachment {expected_attachment} not found in {[a.name for a in attachments]}",
        )
    run = next((m for m in metadata if m.name == "gc2d-rs"), None)
    if checks.expect(run is not None, "no gc2d-rs metadata record"):
        for key in ("program_version", "seed", "command_line", "frames_per_second"):
            checks.expect(key in run.metadata, f"gc2d-rs metadata lacks {key}")
        checks.expect(isinstance(json.loads(run.metadata.get("command_line", "null")), list), "command line not a list")


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    path, expect_path = argv[1], argv[2]
    with open(expect_path) as f:
        expect = json.load(f)
    truncated = bool(expect.get("truncated", False))
    checks = Checks()

    records, error = read_records(path, checks)
    if truncated:
        with open(path, "rb") as f:
            checks.expect(not f.read().endswith(MAGIC), "the killed run's file is complete: the kill came too late")
    else:
        checks.expect(error is None, f"reading stopped early: {error!r}")

    schemas, channels, by_topic = decode_frames(records, checks)
    check_topics(schemas, channels, checks)
    check_log_times(records, channels, checks)
    frames = by_topic.get("/particles", [])
    stats = by_topic.get("/stats", [])
    check_particles(frames, stats, expect, checks, truncated)
    check_contacts(frames, by_topic.get("/contacts", []), stats, checks)
    checks.expect(any(isinstance(r, Metadata) and r.name == "gc2d-rs" for r in records), "no gc2d-rs metadata")
    if expect.get("attachment") is not None:
        checks.expect(any(isinstance(r, Attachment) for r in records), "no attachment record")
    if not truncated:
        walls = by_topic.get("/walls", [])
        checks.expect(len(walls) == expect["walls_messages"], f"{len(walls)} /walls messages, expected {expect['walls_messages']}")
        check_complete_file(path, expect, records, checks)

    print(f"{path}: {len(frames)} frames, {len(records)} records, {checks.passed} checks passed"
          + (f", reading ended with {type(error).__name__}" if error is not None else ""))
    for failure in checks.failures[:50]:
        print(f"FAILED: {failure}")
    if len(checks.failures) > 50:
        print(f"... and {len(checks.failures) - 50} more")
    return 1 if checks.failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
