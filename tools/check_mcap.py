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
  fluid_arrows        (optional) the arrows of the fluid drawn in every frame of a World with a fluid: the file must
                      then carry the /fluid topic, one message per frame at the frame's log time, each one entity
                      'fluid' whose line list draws a shaft and two barbs per arrow; absent or null: no /fluid topic

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
FLUID_TOPIC = ("/fluid", ("foxglove.SceneUpdate", "protobuf", "protobuf"))
STATS_FIELDS = ("time", "particles", "kinetic", "potential", "elastic", "dissipated", "contacts", "mean_coordination")
DELETE_ALL = 1  # foxglove.SceneEntityDeletion.Type.ALL
LINE_LIST = 2  # foxglove.LinePrimitive.Type.LINE_LIST
FORCE_WIDTH_CLASSES = 16  # /contacts: one line list per width class


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
    by_topic = {}
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


def expected_topics(expect):
    """The topics a recording carries: the fixed four, and /fluid where the World has a fluid."""
    topics = dict(EXPECTED_TOPICS)
    if expect.get("fluid_arrows") is not None:
        topics[FLUID_TOPIC[0]] = FLUID_TOPIC[1]
    return topics


def check_topics(schemas, channels, expected, checks):
    topics = {c.topic: c for c in channels.values()}
    checks.expect(set(topics) == set(expected), f"topics {sorted(topics)} != {sorted(expected)}")
    for topic, (schema_name, schema_encoding, message_encoding) in expected.items():
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


def count_packed_particles(entity, k, checks):
    """Counts the particles of a packed /particles entity (a block of body slots): one triangle list of all fills (per-vertex colours) and
    one line list of all outlines on the same points. Each particle is a closed outline loop (a connected component
    of the line list in which every point has two neighbours), filled by a fan of n - 2 triangles within its own
    points, in one colour, in the plane z = const. Returns the number of loops (0 when the checks fail)."""
    if len(entity.triangles) == 0 and len(entity.lines) == 0:
        return 0
    if not checks.expect(len(entity.triangles) == 1 and len(entity.lines) == 1,
                         f"frame {k}: particles are not one triangle list and one line list"):
        return 0
    fills, outlines = entity.triangles[0], entity.lines[0]
    points = [(p.x, p.y, p.z) for p in fills.points]
    n = len(points)
    ok = checks.expect([(p.x, p.y, p.z) for p in outlines.points] == points, f"frame {k}: outline points != fill points")
    ok &= checks.expect(len(fills.colors) == n, f"frame {k}: {len(fills.colors)} fill colours for {n} points")
    ok &= checks.expect(outlines.type == LINE_LIST and len(outlines.indices) % 2 == 0, f"frame {k}: outlines not a line list")
    ok &= checks.expect(len(fills.indices) % 3 == 0 and all(i < n for i in fills.indices), f"frame {k}: bad fill indices")
    ok &= checks.expect(all(i < n for i in outlines.indices), f"frame {k}: bad outline indices")
    ok &= checks.expect(all(p[2] == points[0][2] for p in points), f"frame {k}: fills not in one plane")
    if not ok:
        return 0
    # Connected components of the outline graph (union-find), and every point's degree.
    parent = list(range(n))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    degree = [0] * n
    edges = list(zip(outlines.indices[0::2], outlines.indices[1::2]))
    for a, b in edges:
        degree[a] += 1
        degree[b] += 1
        parent[root(a)] = root(b)
    size = {}
    for i in range(n):
        size[root(i)] = size.get(root(i), 0) + 1
    ok &= checks.expect(all(d == 2 for d in degree), f"frame {k}: an outline point does not close a loop")
    ok &= checks.expect(len(edges) == n and all(m >= 3 for m in size.values()), f"frame {k}: outlines are not loops")
    triangles = {}
    for t in range(0, len(fills.indices), 3):
        a, b, c = fills.indices[t:t + 3]
        same = root(a) == root(b) == root(c)
        ok &= checks.expect(same, f"frame {k}: a fill triangle spans two particles")
        if not same:
            break
        triangles[root(a)] = triangles.get(root(a), 0) + 1
    ok &= checks.expect(all(triangles.get(r, 0) == m - 2 for r, m in size.items()), f"frame {k}: a fill is no fan of n - 2 triangles")
    colour = {}
    for i, c in enumerate(fills.colors):
        rgba = (c.r, c.g, c.b, c.a)
        ok &= colour.setdefault(root(i), rgba) == rgba
    checks.expect(ok, f"frame {k}: packed particles are not filled, outlined loops of one colour each")
    return len(size) if ok else 0


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
        ids = [e.id for e in entities]
        checks.expect(
            len(set(ids)) == len(ids)
            and all(i.startswith("particles/") and i[len("particles/"):].isdigit() for i in ids)
            and all(e.frame_id == "world" for e in entities),
            f"frame {k}: /particles entities {ids[:5]} are not distinct blocks 'particles/<k>' in frame 'world'",
        )
        particles = sum(count_packed_particles(e, k, checks) for e in entities)
        if k < len(counts):
            checks.expect(particles == counts[k], f"frame {k}: {particles} particles, expected {counts[k]}")
        s = stats_by_time.get(log_time)
        if checks.expect(s is not None, f"frame {k}: no /stats message at its log time"):
            checks.expect(s["particles"] == particles, f"frame {k}: /stats particles {s['particles']}")
            checks.expect(abs(s["time"] - t) <= 1e-9, f"frame {k}: /stats time {s['time']} != {t}")
            checks.expect(all(f in s for f in STATS_FIELDS), f"frame {k}: /stats lacks one of {STATS_FIELDS}")


def check_contacts(frames, contacts, stats, checks):
    checks.expect(len(contacts) == len(frames), f"{len(contacts)} /contacts messages for {len(frames)} frames")
    stats_by_time = dict(stats)
    for log_time, update in contacts:
        lines = [line for e in update.entities for line in e.lines]
        segments = sum(len(line.points) // 2 for line in lines)
        s = stats_by_time.get(log_time)
        checks.expect(len(lines) <= FORCE_WIDTH_CLASSES, f"/contacts at {log_time}: {len(lines)} line lists")
        if s is not None:
            # A contact draws a segment from each of its particles (two at most) to its force point.
            checks.expect(segments <= 2 * s["contacts"], f"/contacts at {log_time}: {segments} segments > 2 x {s['contacts']}")
        checks.expect(
            all(line.thickness > 0 and len(line.points) % 2 == 0 and len(line.colors) == len(line.points) for line in lines),
            "bad force line",
        )
        checks.expect(len({line.thickness for line in lines}) == len(lines), f"/contacts at {log_time}: two lists of one width")


def check_fluid(frames, fluid, arrows, checks):
    """One /fluid message per frame at its log time: one entity 'fluid', whose line list holds a shaft and two barbs
    (three segments, six points) per arrow, with a colour per point."""
    checks.expect([t for t, _ in fluid] == [t for t, _ in frames], f"{len(fluid)} /fluid messages for {len(frames)} frames")
    for log_time, update in fluid:
        entities = list(update.entities)
        if not checks.expect(len(entities) == 1 and entities[0].id == "fluid", f"/fluid at {log_time}: entities"):
            continue
        lines = list(entities[0].lines)
        if not checks.expect(len(lines) == 1 and lines[0].type == LINE_LIST, f"/fluid at {log_time}: not one line list"):
            continue
        points = len(lines[0].points)
        checks.expect(points == 6 * arrows, f"/fluid at {log_time}: {points} points for {arrows} arrows")
        checks.expect(len(lines[0].colors) == points, f"/fluid at {log_time}: {len(lines[0].colors)} colours")


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
    check_topics(schemas, channels, expected_topics(expect), checks)
    check_log_times(records, channels, checks)
    frames = by_topic.get("/particles", [])
    stats = by_topic.get("/stats", [])
    check_particles(frames, stats, expect, checks, truncated)
    check_contacts(frames, by_topic.get("/contacts", []), stats, checks)
    if expect.get("fluid_arrows") is not None:
        check_fluid(frames, by_topic.get("/fluid", []), expect["fluid_arrows"], checks)
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
