"""Speed of the Python package beside the `wbv` command on the same data (docs/speed.md#python):
the ISO 2631-1 figures of one hour at 1 kHz from a numpy array, and a 60 s simulation returned as
arrays. Prints a Markdown table; every row is the best and the median of `--repeat` runs, the
command's rows (the baseline) measured in the same run.

Usage: python bench.py WBV_BIN [--repeat N]
"""

import argparse
import csv
import json
import os
import re
import statistics
import subprocess
import tempfile
import time

import numpy as np

import wbv


def timed(f, repeat):
    """Best and median wall time of `f()` in s, and its last result."""
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = f()
        times.append(time.perf_counter() - start)
    return min(times), statistics.median(times), result


def command(*args):
    done = subprocess.run([str(a) for a in args], capture_output=True, text=True, check=True)
    return done.stdout, done.stderr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("wbv_bin")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    rows = []
    load = os.getloadavg()[0]

    # One hour at 1 kHz: a band-limited random base and a seat resonating at 4 Hz (numpy only).
    fs, n = 1000.0, 3_600_000
    rng = np.random.default_rng(1)
    base = np.convolve(rng.normal(0.0, 0.6, n), np.hanning(9) / np.hanning(9).sum(), "same")
    t = np.arange(2000) / fs
    h = np.exp(-2 * np.pi * 4.0 * 0.3 * t) * np.sin(2 * np.pi * 4.0 * t)
    seat = np.convolve(base, h / h.sum(), "full")[:n] + 0.2 * base
    channels = {"a_base_z": base, "a_seat_z": seat}
    best, med, doc = timed(lambda: wbv.analyze(channels, fs), a.repeat)
    rows.append(("1 h at 1 kHz, 2 channels: `wbv.analyze` from numpy arrays", best, med))
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "hour.csv")
        with open(path, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["t_s", "a_base_z", "a_seat_z"])
            w.writerows(zip((repr(i / fs) for i in range(n)), map(repr, base.tolist()), map(repr, seat.tolist())))
        runs = []
        for _ in range(a.repeat):
            start = time.perf_counter()
            out, err = command(a.wbv_bin, "analyze", path, "--json", "--exposure-hours", "8",
                               "--timing")
            wall = time.perf_counter() - start
            m = re.search(r"timing: load ([0-9.]+) s[^,]*, analysis ([0-9.]+) s", err)
            runs.append((wall, float(m.group(1)), float(m.group(2))))
        walls, loads, analyses = zip(*runs)
        rows.append(("the same as CSV: `wbv analyze --json`, whole command", min(walls),
                     statistics.median(walls)))
        rows.append(("  of which reading the CSV", min(loads), statistics.median(loads)))
        rows.append(("  of which the analysis (the library call both make)", min(analyses),
                     statistics.median(analyses)))
        assert abs(doc["total_value"] / json.loads(out)["total_value"] - 1) < 1e-9

        best, med, run = timed(lambda: wbv.simulate("reference", "bell-214", 60, 1), a.repeat)
        rows.append(("60 s of `reference` under `bell-214`: `wbv.simulate` → arrays and figures",
                     best, med))
        sim = ["simulate", "--model", "reference", "--excitation", "bell-214", "--duration", "60",
               "--seed", "1", "--no-record"]
        for label, extra in [("`wbv simulate --no-record`", []),
                             ("`wbv simulate --no-record --csv` (the arrays as a file)",
                              ["--csv", os.path.join(tmp, "run.csv"), "--force"])]:
            best, med, _ = timed(lambda: command(a.wbv_bin, *sim, *extra), a.repeat)
            rows.append((f"the same, {label}, whole command", best, med))
    print(f"load average at start {load:.1f} (1 min), {os.cpu_count()} cores, wbv {wbv.__version__}, "
          f"{a.repeat} runs each\n")
    print("| what | best [s] | median [s] |\n|---|---|---|")
    for what, best, med in rows:
        print(f"| {what} | {best:.3f} | {med:.3f} |")


if __name__ == "__main__":
    main()
