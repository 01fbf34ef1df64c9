"""Opens a wbv MCAP run with Rerun (PyPI `rerun-sdk`, headless) and checks that the signal topics
arrive as data.

Rerun's MCAP loader (`rerun mcap convert`, the importer the viewer uses for a dropped .mcap) is run
on the file; the resulting .rrd is listed with `rerun rrd print`. For a protobuf run, each signal
topic (`/wbv/measured`, `/wbv/state`, `/wbv/links`) must arrive as a decoded `<schema>:message`
column whose Arrow type holds the run's double fields as `Float64` (per-sample: one value per row;
batched: a `List(Float64)` per row), with one row per MCAP message (the counts from the file's
statistics, read with the PyPI `mcap` reader). A JSON run's signal topics arrive only as raw bytes
(`McapMessage:data`): that is reported, not failed (Rerun does not decode JSON channels).
Then the .rrd is read back with rerun-sdk's own RRD reader (`rr.chunk.RrdReader`): on a per-sample
run every row of `/wbv/measured` must hold exactly one message whose `a_seat_z` is a `Float64` —
one value per row, a time series Rerun plots (a batched run holds a list of samples per row).
Usage: python rerun_check.py RERUN_BINARY FILE.mcap   (exit status 1 on any failure)
"""

import re
import subprocess
import sys
import tempfile
from pathlib import Path

import pyarrow as pa
import pyarrow.compute as pc
import rerun as rr
from mcap.reader import make_reader

SIGNALS = ("/wbv/measured", "/wbv/state", "/wbv/links")
# The double fields each signal topic must show, whatever the model (proto/wbv.proto).
LEAVES = {
    "/wbv/measured": {"t", "a_base_z", "a_seat_z", "a_head_z", "f_seat_z"},
    "/wbv/state": {"x", "v", "a", "x_abs", "v_abs", "a_abs"},
    "/wbv/links": {"force"},
}
CHUNK = re.compile(r"with (\d+) rows .* - (/\S+) - data columns: \[(.*)\]")
DOUBLE = re.compile(r'"(\w+)": (?:List\()?(?:non-null )?Float64')


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed: {p.stderr.strip()[-500:]}")
    return p.stdout


def main(rerun, path):
    errors = []

    def fail(msg):
        print(f"rerun: {path}: {msg}", file=sys.stderr)
        errors.append(msg)

    with open(path, "rb") as f:
        summary = make_reader(f).get_summary()
    counts = summary.statistics.channel_message_counts
    expected = {}
    for cid, ch in summary.channels.items():
        if ch.topic in SIGNALS:
            schema = summary.schemas[ch.schema_id].name
            expected[ch.topic] = (ch.message_encoding, schema, counts.get(cid, 0))
    if "/wbv/measured" not in expected:
        fail("no /wbv/measured channel in the file")

    with tempfile.TemporaryDirectory() as tmp:
        rrd = Path(tmp) / "run.rrd"
        try:
            run([rerun, "mcap", "convert", path, "-o", rrd])
            listing = run([rerun, "rrd", "print", rrd])
            verbose = run([rerun, "rrd", "print", "-vv", rrd])
        except RuntimeError as e:
            fail(str(e))
            return 1

        # Rerun's own reader: /wbv/measured `a_seat_z`, one Float64 per row (per-sample runs).
        measured = expected.get("/wbv/measured")
        if measured and measured[0] == "protobuf":
            column = f"{measured[1]}:message"
            reader = rr.chunk.RrdReader(rrd)
            lengths, a_seat_z, sdk_rows = set(), set(), 0
            for chunk in reader.store(store=reader.recordings()[0]).stream():
                if chunk.entity_path != "/wbv/measured":
                    continue
                batch = chunk.to_record_batch()
                if column not in batch.schema.names:
                    continue
                col = batch.column(column)
                sdk_rows += len(col)
                lengths.update(pc.list_value_length(col).unique().to_pylist())
                a_seat_z.add(str(pc.struct_field(pc.list_flatten(col), "a_seat_z").type))
            batched = measured[1].endswith("Batch")
            want = "list<item: double not null>" if batched else "double"
            if a_seat_z != {want}:
                fail(f"/wbv/measured a_seat_z arrives as {sorted(a_seat_z)}, expected {want}")
            elif lengths != {1}:
                fail(f"/wbv/measured: {sorted(lengths)} messages per row, expected one per row")
            sdk = f"rerun-sdk reads /wbv/measured a_seat_z as {want}, {sdk_rows} rows" + (
                " (one list of samples per batch)" if batched else ", one Float64 per row"
            )
        else:
            sdk = "no protobuf /wbv/measured"

    rows = {}
    for m in CHUNK.finditer(listing):
        n, entity, columns = int(m.group(1)), m.group(2), m.group(3).split()
        for c in columns:
            rows[(entity, c)] = rows.get((entity, c), 0) + n
    # Arrow types of each entity's data chunks (the type line follows its `entity_path` line).
    doubles = {}
    entity = None
    for line in verbose.splitlines():
        m = re.search(r"entity_path: (\S+)", line)
        if m:
            entity = m.group(1)
        elif entity and "type: List(Struct(" in line:
            doubles.setdefault(entity, set()).update(DOUBLE.findall(line))

    decoded = []
    for topic, (encoding, schema, n) in sorted(expected.items()):
        if encoding != "protobuf":
            raw = rows.get((topic, "McapMessage:data"), 0)
            print(
                f"rerun {path}: note — {topic} ({encoding}) arrives as {raw} rows of raw bytes "
                "only (Rerun decodes protobuf channels, not JSON)"
            )
            continue
        column = f"{schema}:message"
        got = rows.get((topic, column), 0)
        if got != n:
            fail(f"{topic}: {got} rows of {column}, the file has {n} messages")
        missing = LEAVES[topic] - doubles.get(topic, set())
        if missing:
            fail(f"{topic}: fields {sorted(missing)} do not arrive as Float64 data")
        decoded.append(f"{topic} {got} rows")
    if errors:
        print(f"rerun: {path}: FAILED ({len(errors)} problems)", file=sys.stderr)
        return 1
    version = " ".join(run([rerun, "--version"]).split()[:2])
    print(
        f"rerun {path}: ok — {', '.join(decoded) or 'no protobuf signal topics'} decoded as Float64 "
        f"data; {sdk} ({version})"
    )
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
