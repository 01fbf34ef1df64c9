"""Reading and analysis speed of `wbv analyze` beside pandas (docs/speed.md#reading-and-analysing-a-file):
one hour at 1 kHz, 4 acceleration channels, written as CSV by numpy (time to 1 ms, accelerations
to 1e-6 m/s², as a logger exports them: 165 MB), then, in the same run and alternating, `pandas.read_csv` of the file
(reading only) and `wbv analyze FILE --json` (reading and the whole ISO 2631-1 analysis), each the
best and the median of `--repeat` runs. The CPU seconds of reading and of the analysis alone come from
`--timing` (the process's CPU time, every thread, around each step).

Usage: python bench.py WBV_BIN [--repeat N] [--hours H] [--keep DIR]
"""

import argparse
import json
import os
import re
import resource
import statistics
import subprocess
import tempfile
import time

import numpy as np
import pandas as pd


def hour_csv(path, hours, fs=1000.0, seed=1):
    """Writes `hours` h at `fs` Hz of four band-limited random channels (base z, seat x/y/z) with a
    time column; returns the number of rows."""
    n = int(round(hours * 3600 * fs))
    rng = np.random.default_rng(seed)
    k = np.hanning(9) / np.hanning(9).sum()
    t = np.arange(2000) / fs
    h = np.exp(-2 * np.pi * 4.0 * 0.3 * t) * np.sin(2 * np.pi * 4.0 * t)
    base = np.convolve(rng.normal(0.0, 0.6, n), k, "same")
    seat_z = np.convolve(base, h / h.sum(), "full")[:n] + 0.2 * base
    seat_x = np.convolve(rng.normal(0.0, 0.3, n), k, "same")
    seat_y = np.convolve(rng.normal(0.0, 0.25, n), k, "same")
    data = np.column_stack([np.arange(n) / fs, base, seat_x, seat_y, seat_z])
    with open(path, "w", newline="") as f:
        f.write("t_s,a_base_z,a_seat_x,a_seat_y,a_seat_z\n")
        # A logger's export: time in ms, accelerations to 1e-6 m/s² (about 46 bytes a row, 165 MB
        # an hour).
        np.savetxt(f, data, delimiter=",", fmt=["%.3f"] + ["%.6f"] * 4)
    return n


def run_wbv(wbv, path):
    """Wall time, the process's CPU time, wbv's own load and analysis times, and the document."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([wbv, "analyze", path, "--json", "--timing"], capture_output=True,
                          text=True, check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    m = re.search(r"timing: load ([0-9.]+) s \(([0-9.]+) CPU-s\), analysis ([0-9.]+) s "
                  r"\(([0-9.]+) CPU-s\)", done.stderr)
    load, load_cpu, analysis, analysis_cpu = map(float, m.groups())
    return wall, cpu, load, load_cpu, analysis, analysis_cpu, json.loads(done.stdout)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("wbv_bin")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--hours", type=float, default=1.0)
    ap.add_argument("--keep", help="directory for the CSV (kept); default a temporary one")
    a = ap.parse_args()
    load = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(a.keep or tmp, "hour-4ch.csv")
        if not os.path.exists(path):
            hour_csv(path, a.hours)
        size = os.path.getsize(path)
        # Warm the page cache: both readers then read from memory.
        with open(path, "rb") as f:
            while f.read(1 << 24):
                pass
        pandas_walls, pandas_cpus, wbv_runs = [], [], []
        for _ in range(a.repeat):
            before = resource.getrusage(resource.RUSAGE_SELF)
            start = time.perf_counter()
            df = pd.read_csv(path)
            pandas_walls.append(time.perf_counter() - start)
            after = resource.getrusage(resource.RUSAGE_SELF)
            pandas_cpus.append((after.ru_utime - before.ru_utime)
                               + (after.ru_stime - before.ru_stime))
            wbv_runs.append(run_wbv(a.wbv_bin, path))
        walls, cpus, loads, load_cpus, analyses, analysis_cpus, docs = zip(*wbv_runs)
        doc = docs[-1]
        # The same samples: the mean of a channel as pandas reads it and as wbv reports it.
        for c in doc["channels"]:
            assert abs(c["mean"] - df[c["name"]].mean()) < 1e-9, c["name"]
        channels = len(doc["channels"])
        hours = doc["duration_s"] / 3600.0
    print(f"file {size / 1e6:.0f} MB ({hours:g} h at 1 kHz, {channels} channels + time), "
          f"load average at start {load:.1f} (1 min), {os.cpu_count()} cores, pandas "
          f"{pd.__version__}, {a.repeat} runs each, alternating\n")
    print("| what | best [s] | median [s] |\n|---|---|---|")
    rows = [
        ("pandas `read_csv` (reading only), wall", pandas_walls),
        ("pandas `read_csv` (reading only), CPU (user + sys)", pandas_cpus),
        ("`wbv analyze --json` (reading + analysis), wall", walls),
        ("&nbsp;&nbsp;its CPU (user + sys)", cpus),
        ("&nbsp;&nbsp;of which reading, wall", loads),
        ("&nbsp;&nbsp;of which reading, CPU", load_cpus),
        ("&nbsp;&nbsp;of which the analysis, wall", analyses),
        ("&nbsp;&nbsp;of which the analysis, CPU", analysis_cpus),
        ("the analysis, CPU-s per channel-hour", [c / (channels * hours) for c in analysis_cpus]),
    ]
    for what, xs in rows:
        print(f"| {what} | {min(xs):.3f} | {statistics.median(xs):.3f} |")
    ratio = statistics.median(walls) / statistics.median(pandas_walls)
    cpu_ratio = statistics.median(cpus) / statistics.median(pandas_cpus)
    print(f"\nwbv read + analysis / pandas read, medians: wall {ratio:.2f}, CPU {cpu_ratio:.2f}")


if __name__ == "__main__":
    main()
