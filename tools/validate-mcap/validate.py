"""Reads every message of a wbv MCAP run with the PyPI `mcap` reader and checks it.

Checks: indexed reader with chunk CRCs; summary, statistics, chunk indexes with message indexes;
every channel `json` + `jsonschema`; every message a JSON object without NaN/Infinity that validates
against its channel schema; log_time == publish_time, non-decreasing per channel; message counts
equal the statistics; wbv metadata records present; attachments readable; a second pass with the
non-seeking stream reader (data-section CRC) reads every record.
Protobuf channels (the default encoding): schema encoding `protobuf`, fully qualified name, every
message decoded by `mcap-protobuf-support` (DecoderFactory: builds the message classes from the
file's FileDescriptorSet with Google's `protobuf` runtime) and every double field finite; the wbv
signal topics carry the fields `proto/wbv.proto` names.
Usage: validate.py FILE.mcap  (exit status 1 on any failure)
"""

import json
import sys
from collections import Counter

import math

import jsonschema
from google.protobuf.descriptor import FieldDescriptor
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory
from mcap.stream_reader import StreamReader


def reject_constant(name):
    raise ValueError(f"non-finite number {name} in JSON")


# Fields of the per-step wbv messages (proto/wbv.proto); State/Links hold one of these per mass/link.
WBV_FIELDS = {
    "wbv.Measured": {"t", "a_base_z", "a_seat_z", "a_head_z", "f_seat_z", "a_seat_x", "a_head_x", "f_back_z"},
    "wbv.MassState": {"x", "v", "a", "x_abs", "v_abs", "a_abs"},
    "wbv.LinkState": {"deflection", "force"},
    "wbv.LinkForce": {"force"},
}
# The batched layout (`--layout batched`): the same fields as packed arrays, `t` in every topic.
WBV_FIELDS.update({f"{k}Batch": v for k, v in WBV_FIELDS.items()})
BATCHES = {"wbv.MeasuredBatch", "wbv.StateBatch", "wbv.LinksBatch"}


def array_lengths(msg, out):
    """Lengths of every repeated double field of a batched message, at any depth."""
    for field, value in msg.ListFields():
        if field.type == FieldDescriptor.TYPE_DOUBLE:
            out.add(len(value))
        elif field.type == FieldDescriptor.TYPE_MESSAGE:
            array_lengths(value, out)
    return out


def check_protobuf(msg, at, fail):
    """Every double finite; wbv messages only use their .proto fields."""
    name = msg.DESCRIPTOR.full_name
    if name in BATCHES:
        lengths = array_lengths(msg, set())
        if len(lengths) != 1 or 0 in lengths:
            fail(f"{at}: batched arrays of lengths {sorted(lengths)}, expected one non-zero length")
    for field, value in msg.ListFields():
        if name in WBV_FIELDS and field.name not in WBV_FIELDS[name]:
            fail(f"{at}: {name} has an unexpected field {field.name}")
        repeated = (
            field.is_repeated
            if hasattr(field, "is_repeated")
            else field.label == FieldDescriptor.LABEL_REPEATED
        )
        values = value if repeated else [value]
        for v in values:
            if field.type == FieldDescriptor.TYPE_DOUBLE and not math.isfinite(v):
                fail(f"{at}.{field.name}: not finite")
            elif field.type == FieldDescriptor.TYPE_MESSAGE:
                check_protobuf(v, f"{at}.{field.name}", fail)


def main(path):
    errors = []

    def fail(msg):
        if len(errors) < 20:
            print(f"python-mcap: {path}: {msg}", file=sys.stderr)
        errors.append(msg)

    with open(path, "rb") as f:
        reader = make_reader(f, validate_crcs=True)
        factory = DecoderFactory()
        decoders = {}
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
            if ch.message_encoding == "protobuf":
                if schema is None or schema.encoding != "protobuf":
                    fail(f"{ch.topic}: protobuf channel without a protobuf schema")
                elif "." not in schema.name:
                    fail(f"{ch.topic}: schema name {schema.name!r} is not fully qualified")
                continue
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
        decoded = 0
        for schema, channel, message in reader.iter_messages(log_time_order=False):
            counts[channel.id] += 1
            if message.log_time != message.publish_time:
                fail(f"{channel.topic} #{message.sequence}: log_time != publish_time")
            if message.log_time < last.get(channel.id, 0):
                fail(f"{channel.topic} #{message.sequence}: log_time goes backwards")
            last[channel.id] = message.log_time
            if channel.message_encoding == "protobuf":
                if channel.id not in decoders:
                    decoders[channel.id] = factory.decoder_for("protobuf", schema)
                proto = decoders[channel.id](message.data)
                if proto.DESCRIPTOR.full_name != schema.name:
                    fail(f"{channel.topic}: decoded as {proto.DESCRIPTOR.full_name}")
                check_protobuf(proto, f"{channel.topic} #{message.sequence}", fail)
                decoded += 1
                continue
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
        f"python-mcap {path}: ok — {total} messages on {len(counts)} channels, all schema-valid "
        f"({decoded} protobuf-decoded); "
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
