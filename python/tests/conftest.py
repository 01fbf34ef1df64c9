"""Shared helpers of the Python package's tests: the `wbv` command they compare with, a CSV
writer independent of wbv (Python's csv module), and a comparison of JSON documents."""

import csv
import json
import math
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def wbv_bin():
    """The `wbv` command built from the same sources (tools/test builds it first)."""
    path = pathlib.Path(os.environ.get("WBV_BIN", ROOT / "target" / "release" / "wbv"))
    if not path.is_file():
        pytest.fail(f"no wbv command at {path}: build it (cargo build --release) or set WBV_BIN")
    return path


def cli(wbv_bin, *args, cwd=None):
    """Runs `wbv ARGS…` and returns its stdout; fails the test with its stderr on an error."""
    done = subprocess.run(
        [str(wbv_bin), *map(str, args)], capture_output=True, text=True, cwd=cwd
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


def cli_json(wbv_bin, *args, cwd=None):
    return json.loads(cli(wbv_bin, *args, "--json", cwd=cwd))


def write_csv(path, fs, channels):
    """A logger-style CSV (`t_s` then one column per channel) written with Python's csv module;
    every value as Python's shortest round-trip repr, so the file holds the arrays exactly."""
    names = list(channels)
    n = len(channels[names[0]])
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t_s", *names])
        for i in range(n):
            w.writerow([repr(i / fs), *(repr(float(channels[c][i])) for c in names)])


def read_csv(path):
    """A CSV's columns as lists of floats (Python's csv module)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {h: [float(r[i]) for r in body] for i, h in enumerate(header)}


def assert_same(a, b, rel=1e-9, abs_=1e-12, skip=(), where="$"):
    """Two JSON documents equal: the same keys and strings, numbers within `rel` (relative) or
    `abs_`; keys in `skip` are left out at every depth."""
    if isinstance(a, dict):
        assert isinstance(b, dict), where
        ka = {k for k in a if k not in skip}
        kb = {k for k in b if k not in skip}
        assert ka == kb, f"{where}: keys differ: {sorted(ka ^ kb)}"
        for k in ka:
            assert_same(a[k], b[k], rel, abs_, skip, f"{where}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), f"{where}: lengths differ"
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, rel, abs_, skip, f"{where}[{i}]")
    elif isinstance(a, (int, float)) and not isinstance(a, bool):
        assert isinstance(b, (int, float)) and not isinstance(b, bool), f"{where}: {a!r} vs {b!r}"
        if math.isnan(a) and math.isnan(b):  # an unidentifiable parameter's σ in both
            return
        assert math.isclose(a, b, rel_tol=rel, abs_tol=abs_), f"{where}: {a!r} vs {b!r}"
    else:
        assert a == b, f"{where}: {a!r} vs {b!r}"
