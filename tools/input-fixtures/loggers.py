"""Writes logger recordings with numpy and scipy only, for tests/logger_faults.rs: coarse
converters on quiet and loud runs, written as a logger's CSV export.

Usage: loggers.py OUTDIR. Writes OUTDIR/loggers/*.csv and OUTDIR/loggers/manifest.json, which says
for each file what a reader must find: clipping (and at which value) or none.
"""

import json
import sys
from pathlib import Path

import numpy as np
from scipy import signal

out = Path(sys.argv[1]) / "loggers"
out.mkdir(parents=True, exist_ok=True)
rng = np.random.default_rng(52)
manifest = []


def vibration(n, fs, band):
    """Seat-like random vibration: white noise through a 4th-order Butterworth band-pass."""
    sos = signal.butter(4, band, btype="bandpass", fs=fs, output="sos")
    x = signal.sosfilt(sos, rng.standard_normal(n + int(2 * fs)))[int(2 * fs):]
    return x / np.std(x)


def write(name, fs, cols, clipped_at=None):
    t = np.arange(len(cols["a_seat_z"])) / fs
    data = np.column_stack([t] + list(cols.values()))
    np.savetxt(out / name, data, fmt=["%.6f"] + ["%.9g"] * len(cols), delimiter=",",
               header=",".join(["t_s"] + list(cols)), comments="")
    manifest.append({"file": name, "fs": fs, "clipped": clipped_at})


# An 8-bit logger (±2 g range, step 4 g/256) on quiet runs: the seat channel uses about ten codes,
# revisits every one of them, and never reaches the range.
for i, (fs, band, level) in enumerate([(500, (0.5, 20), 0.019), (1024, (0.5, 8), 0.015), (2000, (1, 20), 0.024), (512, (0.5, 4), 0.02)]):
    n = int(fs * 120)
    step = 4.0 * 9.80665 / 256
    seat = level * 9.80665 * vibration(n, fs, band)
    base = 1.2 * seat + 0.05 * rng.standard_normal(n)
    write("quiet-8bit-%d.csv" % i, fs, {
        "a_seat_z": np.round(seat / step) * step,
        "a_base_z": base,
    })

# The same logger on a loud run past its range: the converter holds its end codes.
fs, n = 500, 500 * 120
step = 4.0 * 9.80665 / 256
seat = 0.9 * 9.80665 * vibration(n, fs, (0.5, 20))
codes = np.clip(np.round(seat / step), -128, 127)
write("loud-8bit-clipped.csv", fs, {"a_seat_z": codes * step, "a_base_z": 0.8 * seat}, clipped_at=[-128 * step, 127 * step])

with open(out / "manifest.json", "w") as fh:
    json.dump(manifest, fh, indent=1)
