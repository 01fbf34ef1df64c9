"""Reads every message of a wbv MCAP run with the PyPI `mcap` reader and checks it.

Checks: indexed reader with chunk CRCs; summary, statistics, chunk indexes with message indexes;
every channel `json` + `jsonschema`; every message a JSON object without NaN/Infinity that validates
against its channel schema; log_time == publish_time, non-decreasing per channel; message counts
equal the statistics; wbv metadata records present; attachments readable; a second pass with the
non-seeking stream reader (data-section CRC) reads every record.
Usage: validate.py FILE.mcap  (exit status 1 on any failure)
"""

import json
import sys
from collections import Counter

import jsonschema
from mcap.reader import make_reader
from mcap.stream_reader import StreamReader


def reject_constant(name):
    raise ValueError(f"non-finite number {name} in JSON")


def main(path):
    errors = []

    def fail(msg):
        if len(errors) < 20:
            print(f"python-mcap: {path}: {msg}", file=sys.stderr)
        errors.append(msg)

    with open(path, "rb") as f:
        reader = make_reader(f, validate_crcs=True)
        header = reader.get_header()
        summary = reader.get_summary()
        if summary is None or summary.statistics is None:
            fail("no summary/statistics")
            return 1
        if not summary.chunk_indexes:
            fail("no chunk indexes")
        for ci in summary.chunk_indexes:
            if not ci.message_index_offsets:
                fail(f"chunk at {ci.chunk_start_offset} has no message indexes")
        validators = {}
        for cid, ch in summary.channels.items():
            schema = summary.schemas.get(ch.schema_id)
            if ch.message_encoding != "json":
                fail(f"{ch.topic}: message encoding {ch.message_encoding!r}, expected json")
            if schema is None or schema.encoding != "jsonschema":
                fail(f"{ch.topic}: no jsonschema schema")
                continue
            doc = json.loads(schema.data)
            jsonschema.Draft202012Validator.check_schema(doc)
            validators[cid] = jsonschema.Draft202012Validator(doc)
        counts = Counter()
        last = {}
        for schema, channel, message in reader.iter_messages(log_time_order=False):
            counts[channel.id] += 1
            if message.log_time != message.publish_time:
                fail(f"{channel.topic} #{message.sequence}: log_time != publish_time")
            if message.log_time < last.get(channel.id, 0):
                fail(f"{channel.topic} #{message.sequence}: log_time goes backwards")
            last[channel.id] = message.log_time
            try:
                obj = json.loads(message.data, parse_constant=reject_constant)
            except ValueError as e:
                fail(f"{channel.topic} #{message.sequence}: invalid JSON: {e}")
                continue
            if not isinstance(obj, dict):
                fail(f"{channel.topic} #{message.sequence}: not a JSON object")
                continue
            v = validators.get(channel.id)
            if v is not None and not v.is_valid(obj):
                err = jsonschema.exceptions.best_match(v.iter_errors(obj))
                fail(f"{channel.topic} #{message.sequence}: schema: {err.message}")
        expected = summary.statistics.channel_message_counts
        for cid, n in expected.items():
            if counts[cid] != n:
                fail(f"channel {cid}: read {counts[cid]} messages, statistics say {n}")
        metadata = {m.name: m.metadata for m in reader.iter_metadata()}
        for name in ("wbv.run", "wbv.model", "wbv.excitation"):
            if name not in metadata:
                fail(f"metadata record {name} missing")
        attachments = [(a.name, len(a.data)) for a in reader.iter_attachments()]

    with open(path, "rb") as f:
        records = sum(1 for _ in StreamReader(f, validate_crcs=True).records)

    total = sum(counts.values())
    if errors:
        print(f"python-mcap: {path}: FAILED ({len(errors)} problems)", file=sys.stderr)
        return 1
    print(
        f"python-mcap {path}: ok — {total} messages on {len(counts)} channels, all schema-valid; "
        f"{len(metadata)} metadata, {len(attachments)} attachments, {records} records streamed "
        f"({header.library})"
    )
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    try:
        sys.exit(main(sys.argv[1]))
    except Exception as e:  # any reader error is a validation failure, on one line
        print(f"python-mcap: {sys.argv[1]}: FAILED: {type(e).__name__}: {e}", file=sys.stderr)
        sys.exit(1)
