"""Writes the Rerun blueprint of a wbv run (`tools/viewer/wbv.rbl`) with the PyPI `rerun-sdk`, or
checks one.

Rerun's MCAP importer decodes each protobuf message of `/wbv/measured` into one `wbv.Measured:message`
struct per row; a time-series view plots a field of it through a component mapping (selector
`.a_seat_z` onto `Scalars:scalars`). The blueprint has two such views: the base, seat and head
accelerations (m/s²) and the seat force (N). It is generated here, not by wbv, because `.rbl` is
Rerun's own Arrow-based store format that only its SDKs write; wbv copies the committed file beside
every run it records. Rerun applies a blueprint to recordings of the same application id, so the
blueprint's is `wbv` and a run is opened with that id (README, "Viewing a run").

Usage: python rerun_blueprint.py write OUT.rbl   |   python rerun_blueprint.py check FILE.rbl
"""

import sys

import rerun as rr
import rerun.blueprint as rrb
from rerun.blueprint.encodings import ComponentSourceKind, VisualizerComponentMapping

APPLICATION_ID = "wbv"
MEASURED = "/wbv/measured"
SOURCE = "wbv.Measured:message"
# (view name, [(field of /wbv/measured, legend, colour RGBA)])
VIEWS = [
    (
        "Absolute acceleration z (m/s²)",
        [
            ("a_base_z", "base", 0x4E79A7FF),
            ("a_seat_z", "seat", 0x59A14FFF),
            ("a_head_z", "head", 0xE15759FF),
        ],
    ),
    ("Seat force z (N)", [("f_seat_z", "seat force", 0xB07AA1FF)]),
]
SIGNALS = [field for _, fields in VIEWS for field, _, _ in fields]


def series(field, legend, colour):
    """A line series of one double field of the decoded `wbv.Measured` messages."""
    return rr.SeriesLines(names=legend, colors=colour).visualizer(
        mappings=[
            VisualizerComponentMapping(
                target="Scalars:scalars",
                source_kind=ComponentSourceKind.SourceComponent,
                source_component=SOURCE,
                selector=f".{field}",
            )
        ]
    )


def blueprint():
    return rrb.Blueprint(
        rrb.Vertical(
            *(
                rrb.TimeSeriesView(
                    name=name,
                    origin=MEASURED,
                    overrides={MEASURED: [series(*f) for f in fields]},
                )
                for name, fields in VIEWS
            )
        ),
        collapse_panels=True,
    )


def check(path):
    """Reads `path` back with rerun-sdk's RRD reader: one blueprint of application id `wbv` whose
    visualizers map the four signals of `wbv.Measured` onto scalars."""
    reader = rr.chunk.RrdReader(path)
    stores = reader.blueprints()
    if len(stores) != 1 or reader.recordings():
        raise SystemExit(f"{path}: expected exactly one blueprint and no recording")
    if stores[0].application_id != APPLICATION_ID:
        raise SystemExit(f"{path}: application id {stores[0].application_id!r}, expected {APPLICATION_ID!r}")
    mapped, views = set(), []
    for chunk in reader.store(store=stores[0]).stream():
        batch = chunk.to_record_batch()
        for name in batch.schema.names:
            if not name.endswith(("VisualizerInstruction:component_map", "ViewBlueprint:display_name")):
                continue
            for row in batch.column(name).to_pylist():
                if name.endswith("VisualizerInstruction:component_map"):
                    mapped.update(
                        m["selector"][1:]
                        for m in row or []
                        if m["target"] == "Scalars:scalars" and m["source_component"] == SOURCE
                    )
                else:
                    views.extend(row or [])
    missing = sorted(set(SIGNALS) - mapped)
    if missing:
        raise SystemExit(f"{path}: the blueprint does not plot {missing} of {SOURCE}")
    print(
        f"rerun blueprint {path}: ok — application id {APPLICATION_ID}, views {views}, "
        f"plotting {', '.join(s for s in SIGNALS)} of {SOURCE}"
    )


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("write", "check"):
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    if sys.argv[1] == "write":
        blueprint().save(APPLICATION_ID, sys.argv[2])
    check(sys.argv[2])
