"""The package against the `wbv` command on the same inputs: every function returns what the
command prints (`--json`) or writes (`--csv`), because both call the same library function."""

import math
import subprocess
import sys
import tomllib

import numpy as np
import pytest

import wbv
from conftest import assert_same, cli, cli_json, read_csv, write_csv


def seat_record(fs, seconds, seed):
    """A measured-looking seat run made with numpy alone: a band-limited random base and a seat
    that resonates near 4 Hz (a damped sinusoid's impulse response), in m/s²."""
    rng = np.random.default_rng(seed)
    n = int(seconds * fs)
    base = np.convolve(rng.normal(0.0, 1.0, n), np.hanning(9) / np.hanning(9).sum(), "same")
    t = np.arange(int(2 * fs)) / fs
    h = np.exp(-2 * math.pi * 4.0 * 0.3 * t) * np.sin(2 * math.pi * 4.0 * t)
    seat = np.convolve(base, h / h.sum(), "full")[:n] + 0.2 * base
    return {"a_base_z": 0.6 * base, "a_seat_z": 0.6 * seat}


def normalised_warnings(doc, source):
    """The document's warnings with the source named alike and a file's rate notes (the time
    column's, or `--fs` for a file without one: arrays are given their rate) left out."""
    return [
        w.replace(source, "SOURCE") if source else w
        for w in doc["warnings"]
        if "fitted to the time column" not in w and "from --fs (the file has no time column)" not in w
    ]


@pytest.mark.parametrize(
    "fs, units, cli_units",
    [(500.0, None, []), (1000.0, "g", ["--units", "g"]), (250.0, {"a_seat_z": "mg"}, ["--units", "a_seat_z=mg"])],
)
def test_analyze_equals_the_command(tmp_path, wbv_bin, fs, units, cli_units):
    channels = seat_record(fs, 60.0, seed=11)
    if units is not None:
        # The same samples in the declared unit: small numbers, as a logger in g writes them.
        channels = {k: v / (9.80665 if units == "g" else 1.0) for k, v in channels.items()}
    path = tmp_path / "logger.csv"
    write_csv(path, fs, channels)
    expected = cli_json(wbv_bin, "analyze", path, "--exposure-hours", "8", *cli_units)
    got = wbv.analyze(channels, fs, units=units)
    assert got["command"] == "analyze"
    assert_same(expected, got, rel=1e-9, skip={"source", "warnings"})
    assert normalised_warnings(expected, str(path)) == normalised_warnings(got, "arrays")
    # The health block is there by default (8 h) and is the only difference without it.
    no_health = wbv.analyze(channels, fs, units=units, exposure_hours=None)
    assert no_health["health"] is None and got["health"] is not None


def test_analyze_takes_pandas_columns_and_other_dtypes(wbv_bin):
    pd = pytest.importorskip("pandas")
    channels = seat_record(400.0, 30.0, seed=5)
    frame = pd.DataFrame(channels).astype("float32")
    as_f32 = wbv.analyze({c: frame[c] for c in frame}, 400.0)
    direct = wbv.analyze({c: frame[c].to_numpy().astype(float) for c in frame}, 400.0)
    assert as_f32 == direct


@pytest.mark.parametrize(
    "model, excitation, options, cli_options",
    [
        ("reference", "bell-214", {}, []),
        (
            "planar-occupant",
            "random",
            {"rms": 0.8, "band": (1.0, 40.0), "integrator": "rk4", "dt": 0.0005},
            ["--rms", "0.8", "--band", "1,40", "--integrator", "rk4", "--dt", "0.0005"],
        ),
    ],
)
def test_simulate_equals_the_commands_csv(tmp_path, wbv_bin, model, excitation, options, cli_options):
    csv_path = tmp_path / "run.csv"
    doc = cli_json(
        wbv_bin, "simulate", "--model", model, "--excitation", excitation, "--duration", 12,
        "--seed", 3, *cli_options, "--no-record", "--csv", csv_path,
    )
    run = wbv.simulate(model, excitation, 12, 3, **options)
    columns = read_csv(csv_path)
    assert list(run.channels) == [c for c in columns if c != "t_s"]
    for name, values in columns.items():
        got = run.time if name == "t_s" else run.channels[name]
        assert got.shape == (len(values),)
        np.testing.assert_allclose(got, values, rtol=1e-12, atol=1e-12, err_msg=name)
    assert run.fs == pytest.approx(1.0 / options.get("dt", 0.001), rel=1e-15)
    assert_same(doc["analysis"], run.figures, rel=1e-12)
    assert run.document["command"] == "simulate" and run.path is None
    assert_same(doc, run.document, rel=1e-12, skip={"elapsed_s", "peak_memory_bytes", "written"})


def test_a_recorded_run_is_the_commands_recording(tmp_path, wbv_bin):
    cli(wbv_bin, "simulate", "--model", "reference", "--excitation", "bell-214", "--duration", 5,
        "--seed", 2, "--out", tmp_path / "cli")
    run = wbv.simulate("reference", "bell-214", 5, 2, record=tmp_path / "py")
    assert run.path == tmp_path / "py" / "run.mcap"
    written = sorted(w["path"] for w in run.document["written"])
    assert written == sorted(str(p) for p in (tmp_path / "py").iterdir())
    # The same signals and figures in both recordings: `wbv replay` reads them back.
    a = cli_json(wbv_bin, "replay", tmp_path / "cli")["analysis"]
    b = cli_json(wbv_bin, "replay", tmp_path / "py")["analysis"]
    assert_same(a, b, rel=0, abs_=0, skip={"source"})
    with pytest.raises(wbv.WbvError, match="refusing to overwrite"):
        wbv.simulate("reference", "bell-214", 5, 2, record=tmp_path / "py")
    wbv.simulate("reference", "bell-214", 5, 2, record=tmp_path / "py", force=True)


def test_catalogues_and_modes_equal_the_command(wbv_bin):
    assert wbv.models() == cli_json(wbv_bin, "models")["models"]
    assert wbv.excitations() == cli_json(wbv_bin, "excitations")["excitations"]
    for model in ["reference", "planar-occupant"]:
        assert wbv.modes(model) == cli_json(wbv_bin, "modes", "--model", model)
    version = cli(wbv_bin, "--version").split()[-1]
    assert wbv.__version__ == version


def test_frf_equals_the_commands_csv(tmp_path, wbv_bin):
    out = tmp_path / "frf.csv"
    cli(wbv_bin, "frf", "--model", "seed001-full", "--from", "0.5", "--to", "20", "--points", "60",
        "--log", "--out", out)
    columns = read_csv(out)
    f = wbv.frf("seed001-full", columns["freq_hz"])
    np.testing.assert_array_equal(f.freq_hz, columns["freq_hz"])
    assert sorted(f.responses) == sorted(c[: -len("_mag")] for c in columns if c.endswith("_mag"))
    for name, h in f.responses.items():
        assert h.dtype == np.complex128
        np.testing.assert_allclose(np.abs(h), columns[f"{name}_mag"], rtol=1e-12)
        np.testing.assert_allclose(np.degrees(np.angle(h)), columns[f"{name}_phase_deg"],
                                   rtol=1e-12, atol=1e-9)
    assert f.units["apms"] == "kg"


@pytest.mark.parametrize(
    "kwargs, cli_args",
    [
        ({}, []),
        ({"excitation": "bell-214"}, ["--excitation", "bell-214"]),
        (
            {"excitation": "random", "rms": 1.0, "duration": 20.0, "time_domain": True},
            ["--excitation", "random", "--rms", "1", "--duration", "20", "--time-domain"],
        ),
    ],
)
def test_sweep_equals_the_commands_table(wbv_bin, kwargs, cli_args):
    pd = pytest.importorskip("pandas")
    doc = cli_json(wbv_bin, "sweep", "--model", "reference", "--param", "link.cushion.k",
                   "--values", "18500:22500:3", "--response", "seat", *cli_args)
    table = wbv.sweep("reference", {"link.cushion.k": np.linspace(18500, 22500, 3)},
                      response="seat", **kwargs)
    assert isinstance(table, pd.DataFrame)
    assert len(table) == len(doc["points"])
    for row, p in zip(table.to_dict("records"), doc["points"]):
        expected = {"point": p["point"], **p["values"], "peak_freq_hz": p["peak_freq_hz"],
                    "peak_mag": p["peak_mag"], **p["figures"]}
        assert_same(expected, row, rel=1e-12)
    # The wall times of two runs differ; everything else is the same document.
    timing = {"points", "elapsed_s", "seconds_per_point"}
    assert_same({k: v for k, v in doc.items() if k not in timing},
                {k: v for k, v in table.attrs.items() if k not in timing}, rel=0)


def test_sweep_without_pandas_returns_arrays(wbv_bin):
    code = (
        "import sys; sys.modules['pandas'] = None\n"
        "import wbv, numpy as np\n"
        "t = wbv.sweep('reference', {'link.cushion.k': '18500:22500:3'}, excitation='bell-214')\n"
        "assert isinstance(t, dict), type(t)\n"
        "assert all(isinstance(v, np.ndarray) for v in t.values())\n"
        "assert t['point'].dtype == np.int64 and t['a_w_seat_m_s2'].dtype == np.float64\n"
        "print(list(t), list(t['comfort']))\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "link.cushion.k" in done.stdout and "not_uncomfortable" in done.stdout


def test_gap_on_arrays_equals_the_command_on_files(tmp_path, wbv_bin):
    runs = {}
    for name, rms, seed in [("low", 0.5, 21), ("high", 1.5, 22), ("mid", 1.0, 23)]:
        run = wbv.simulate("seed001-full", "random", 60, seed, rms=rms)
        runs[name] = {c: run.channels[c] for c in ("a_base_z", "a_seat_z", "a_head_z")}
        write_csv(tmp_path / f"{name}.csv", run.fs, runs[name])
    doc = cli_json(wbv_bin, "gap", "--model", "reference", "--run", tmp_path / "low.csv",
                   "--run", tmp_path / "high.csv", "--check", tmp_path / "mid.csv")
    # Arrays, and a file standing for a run as on the command line.
    got = wbv.gap([tmp_path / "low.csv", runs["high"]], runs["mid"], "reference", fs=1000.0)
    assert got["verdict"] == doc["verdict"] and got["named"] == doc["named"]
    # Runs given as arrays are named by their place in the call, files by their path.
    assert [r["source"] for r in got["runs"]] == [str(tmp_path / "low.csv"), "runs[1]", "check"]
    assert_same(doc, got, rel=1e-9, skip={"source", "model"})
    # The corrected model (docs/gap.md §10): the command's file but for the runs' names, and a
    # model text every call takes (`--write-model` writes the same bytes as the JSON's `model`).
    assert "[provenance]" in got["model"]
    assert_same(tomllib.loads(doc["model"]), tomllib.loads(got["model"]), rel=1e-9,
                skip={"source", "training_runs", "check_run"})
    written = cli_json(wbv_bin, "gap", "--model", "reference", "--run", tmp_path / "low.csv",
                       "--run", tmp_path / "high.csv", "--check", tmp_path / "mid.csv",
                       "--write-model", tmp_path / "corrected.toml")
    assert (tmp_path / "corrected.toml").read_text() == written["model"]
    by_text = wbv.simulate(got["model"], "random", 5, 3, rms=1.0)
    by_file = wbv.simulate(str(tmp_path / "corrected.toml"), "random", 5, 3, rms=1.0)
    assert np.array_equal(by_text.channels["a_seat_z"], by_file.channels["a_seat_z"])


def test_seat_test_simulated_equals_the_command(wbv_bin):
    # One test person, short runs: the same library call as the command's, seeds 1, 2, 3, ….
    args = dict(occupant="light", duration=20.0, seat_limit=0.9)
    doc = cli_json(wbv_bin, "seat-test", "--model", "scissor-seat", "--class", "iso7096-em3",
                   "--occupant", "light", "--duration", 20, "--seat-limit", 0.9)
    got = wbv.seat_test("scissor-seat", "iso7096-em3", **args)
    assert got["command"] == "seat-test" and got["damping"] is not None
    assert_same(doc, got, rel=1e-12)


def test_seat_test_on_measured_arrays_equals_the_command_on_files(tmp_path, wbv_bin):
    # Three lab runs made with numpy alone, as files for the command and as arrays (one as its
    # file) for the package; the runs' names differ (paths vs runs[i]), every figure is equal.
    files, runs = [], []
    for i in range(3):
        run = seat_record(500.0, 40.0, 30 + i)
        files.append(tmp_path / f"run{i}.csv")
        write_csv(files[-1], 500.0, run)
        runs.append(run)
    doc = cli_json(wbv_bin, "seat-test", "--class", "iso7096-em3",
                   *[a for f in files for a in ("--run", f)])
    got = wbv.seat_test(None, "iso7096-em3", runs=[files[0], runs[1], runs[2]], fs=500.0)
    assert [r["id"] for r in got["classes"][0]["runs"]] == [str(files[0]), "runs[1]", "runs[2]"]
    assert got["source"] == "measured" and got["verdict"] is None
    assert_same(doc, got, rel=1e-9, skip={"id"})


def test_exposure_on_arrays_equals_the_command_on_files(tmp_path, wbv_bin):
    # A day of two operations; the arrays named as the command names the files.
    ops = [(seat_record(500.0, 30.0, 40), 3.0), (seat_record(500.0, 30.0, 41), 2.5)]
    cli_ops = []
    for i, (channels, hours) in enumerate(ops):
        path = tmp_path / f"op{i}.csv"
        write_csv(path, 500.0, {k: 2.0 * v for k, v in channels.items()})
        cli_ops += ["--operation", f"{path}:{hours}"]
    doc = cli_json(wbv_bin, "exposure", *cli_ops, "--iso2631-5")
    got = wbv.exposure(
        [(str(tmp_path / f"op{i}.csv"), {k: 2.0 * v for k, v in c.items()}, h)
         for i, (c, h) in enumerate(ops)],
        fs=500.0, iso2631_5=True,
    )
    assert got["command"] == "exposure" and got["zone"] == doc["zone"]
    assert normalised_warnings(got, "") == normalised_warnings(doc, "")
    assert_same(doc, got, rel=1e-9, skip={"warnings"})
    # A file as the command reads it, named by its path.
    assert wbv.exposure([(tmp_path / "op0.csv", 3.0)])["operations"][0]["name"] == str(
        tmp_path / "op0.csv")


def test_exposure_takes_a_rate_per_operation_and_equals_the_command(tmp_path, wbv_bin):
    # Two loggers: 500 Hz and 2048 Hz. Each array carries its own rate; the command reads each
    # file's rate from its time column. The same day, figure for figure.
    a, b = seat_record(500.0, 40.0, 50), seat_record(2048.0, 40.0, 51)
    write_csv(tmp_path / "a.csv", 500.0, a)
    write_csv(tmp_path / "b.csv", 2048.0, b)
    doc = cli_json(wbv_bin, "exposure", "--operation", f"{tmp_path / 'a.csv'}:3",
                   "--operation", f"{tmp_path / 'b.csv'}:2.5")
    as_tuples = wbv.exposure([(str(tmp_path / "a.csv"), a, 500.0, 3.0),
                              (str(tmp_path / "b.csv"), b, 2048.0, 2.5)])
    as_records = wbv.exposure([wbv.Operation(a, 500.0, 3.0, name=str(tmp_path / "a.csv")),
                               wbv.Operation(b, 2048.0, 2.5, name=str(tmp_path / "b.csv"))])
    for got in (as_tuples, as_records):
        assert_same(doc, got, rel=1e-9, skip={"warnings"})
        assert normalised_warnings(got, "") == normalised_warnings(doc, "")
    # One rate for both (the old call) reads the 2048 Hz record as 164 s: another A(8).
    wrong = wbv.exposure([(a, 3.0), (b, 2.5)], fs=500.0)
    assert not math.isclose(wrong["a8"], doc["a8"], rel_tol=1e-3)
    # A record longer than its operation's hours is a warning naming it.
    short_day = wbv.exposure([(b, 500.0, 0.03)])
    assert any("operations[0]: 0.05 h of samples" in w and "1.1×" in w
               for w in short_day["warnings"]), short_day["warnings"]
