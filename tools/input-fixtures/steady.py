"""Held-out ISO 2631-1 test vectors with closed-form figures, made without wbv's filters.

Usage: steady.py OUTDIR. Writes OUTDIR/steady/*.csv (Python's csv module) and
OUTDIR/steady/manifest.json, read by tests/analysis_steady.rs.

- Steady sines A·cos(2πft + φ) + offset, starting at a random phase (so mid-vibration), with the
  closed forms of a steady sine through the analog weightings of ISO 2631-1 Annex A (Table A.2,
  evaluated here from the standard's formulas, not from wbv's sections):
  a_w = A|W|/√2, VDV = A|W|(3T/8)^¼, crest factor √2, MSDV = A|Wf|√(T/2),
  MTVV (linear, τ = 1 s) = A|W|·√(½ + |sin ωτ|/(2ωτ)) (the largest 1 s mean of cos²).
- Pairs of band-limited random signals (scipy.signal.butter + lfilter): the same vibration started
  at rest, once with no offset and once with a sensor offset that holds during a quiet first second
  (a step at t = 0 from the analysis' point of view). Their figures must agree.
"""

import csv
import json
import sys
from pathlib import Path

import numpy as np
import scipy.signal as ss

out = Path(sys.argv[1]) / "steady"
out.mkdir(parents=True, exist_ok=True)
rng = np.random.default_rng(20261125)
Q = 1 / np.sqrt(2)

# ISO 2631-1:1997 Table A.2 (f in Hz; None: the factor is absent).
PARAMS = {
    "Wk": dict(f1=0.4, f2=100.0, f3=12.5, f4=12.5, q4=0.63, f5=2.37, q5=0.91, f6=3.35, q6=0.91),
    "Wd": dict(f1=0.4, f2=100.0, f3=2.0, f4=2.0, q4=0.63, f5=None, q5=None, f6=None, q6=None),
    "Wf": dict(f1=0.08, f2=0.63, f3=None, f4=0.25, q4=0.86, f5=0.0625, q5=0.80, f6=0.1, q6=0.80),
}


def magnitude(name, f):
    """|H(j2πf)| of ISO 2631-1 eqs. A.1–A.4 (Hh·Hl·Ht·Hs)."""
    p = PARAMS[name]
    s = 2j * np.pi * f
    w = lambda fc: 2 * np.pi * fc
    h = 1 / (1 + w(p["f1"]) / (Q * s) + (w(p["f1"]) / s) ** 2)
    h *= 1 / (1 + s / (Q * w(p["f2"])) + (s / w(p["f2"])) ** 2)
    num = 1 + s / w(p["f3"]) if p["f3"] else 1
    h *= num / (1 + s / (p["q4"] * w(p["f4"])) + (s / w(p["f4"])) ** 2)
    if p["f5"]:
        h *= (1 + s / (p["q5"] * w(p["f5"])) + (s / w(p["f5"])) ** 2) / (
            1 + s / (p["q6"] * w(p["f6"])) + (s / w(p["f6"])) ** 2
        ) * (w(p["f5"]) / w(p["f6"])) ** 2
    return abs(h)


def write(name, fs, cols):
    path = out / name
    with open(path, "w", newline="") as fh:
        wr = csv.writer(fh)
        wr.writerow(["t_s"] + list(cols))
        n = len(next(iter(cols.values())))
        for i in range(n):
            wr.writerow([repr(i / fs)] + [repr(float(cols[c][i])) for c in cols])
    return name


sines = []
for f in [0.3, 2.0, 8.0, 17.2]:
    for k in range(3):
        fs = float(rng.choice([400.0, 500.0, 1000.0])) if f > 0.5 else 200.0
        T = float(rng.uniform(100.0, 140.0))
        n = int(T * fs)
        T = n / fs
        t = np.arange(n) / fs
        amp, phase = float(rng.uniform(0.3, 2.0)), float(rng.uniform(0, 2 * np.pi))
        offset = float(rng.uniform(-10.0, 10.0))
        z = amp * np.cos(2 * np.pi * f * t + phase) + offset
        xphase = float(rng.uniform(0, 2 * np.pi))
        x = amp * np.cos(2 * np.pi * f * t + xphase) - offset
        w, tau = 2 * np.pi * f, 1.0
        mtvv_factor = np.sqrt(0.5 + abs(np.sin(w * tau)) / (2 * w * tau))
        expect = {}
        for ch, wname in [("a_seat_z", "Wk"), ("a_seat_x", "Wd")]:
            a = amp * magnitude(wname, f)
            expect[ch] = {
                "a_w": a / np.sqrt(2),
                "vdv": a * (3 * T / 8) ** 0.25,
                "mtvv": a * mtvv_factor,
                "crest_factor": np.sqrt(2),
            }
        expect["a_seat_z"]["msdv"] = amp * magnitude("Wf", f) * np.sqrt(T / 2)
        name = write(f"sine-{f}-{k}.csv", fs, {"a_seat_z": z, "a_seat_x": x})
        sines.append({"file": name, "f_hz": f, "fs": fs, "duration_s": T, "phase": phase,
                      "offset": offset, "expect": expect})

pairs = []
for k in range(4):
    fs = float(rng.choice([256.0, 500.0, 1000.0]))
    T = float(rng.uniform(40.0, 160.0))
    n = int(T * fs)
    lo, hi = float(rng.uniform(0.5, 3.0)), float(rng.uniform(10.0, 40.0))
    b, a = ss.butter(4, [lo, hi], btype="band", fs=fs)
    x = ss.lfilter(b, a, rng.standard_normal(n + 20000))[20000:]
    x *= float(rng.uniform(0.3, 2.0)) / np.std(x)
    x[: int(fs)] = 0.0
    offset = float(rng.uniform(-12.0, 12.0))
    rest = write(f"random-{k}-rest.csv", fs, {"a_seat_z": x})
    step = write(f"random-{k}-step.csv", fs, {"a_seat_z": x + offset})
    pairs.append({"rest": rest, "step": step, "fs": fs, "offset": offset})


def magnitude_sq_periodic(name, n, fs):
    """|W(f)|² at the rfft bins of a record of n samples (the analog weighting of Annex A)."""
    f = np.fft.rfftfreq(n, 1 / fs)
    w2 = np.zeros_like(f)
    w2[1:] = magnitude(name, f[1:]) ** 2
    return w2


# Broadband records cut anywhere out of a longer vibration: circular rotations of one periodic
# record (its periodic extension is the longer vibration), whose steady-state MSDV is the same for
# every rotation: [∫ a_wf² dt]^½ over one period, from the record's spectrum through the analog Wf
# (Parseval), with no filter start at all.
rotations = []
for fs, T, kind in [(200.0, 300.0, "white"), (1000.0, 300.0, "white"), (200.0, 300.0, "band"),
                    (1000.0, 300.0, "band")]:
    n = int(T * fs)
    x = rng.standard_normal(n)
    if kind == "band":
        # Periodic band-limited noise 0.05-40 Hz with a seat-like 4 Hz bump, shaped on its spectrum.
        f = np.fft.rfftfreq(n, 1 / fs)
        shape = ((f > 0.05) & (f < 40.0)) * (1.0 + 3.0 / (1.0 + ((f - 4.0) / 1.5) ** 2))
        x = np.fft.irfft(np.fft.rfft(x) * shape, n)
    x *= float(rng.uniform(0.5, 2.0)) / np.std(x)
    X = np.fft.rfft(x)
    w2 = magnitude_sq_periodic("Wf", n, fs)
    # Σ y² over one period from the one-sided spectrum (Parseval for rfft).
    e = (2 * np.sum(np.abs(X[1:]) ** 2 * w2[1:]) - (np.abs(X[-1]) ** 2 * w2[-1] if n % 2 == 0 else 0)) / n
    msdv = float(np.sqrt(e / fs))
    for k in range(4):
        shift = int(rng.integers(0, n))
        name = write(f"rotation-{kind}-{int(fs)}-{k}.csv", fs, {"a_seat_z": np.roll(x, -shift)})
        rotations.append({"file": name, "fs": fs, "duration_s": n / fs, "kind": kind,
                          "shift": shift, "msdv": msdv})

(out / "manifest.json").write_text(
    json.dumps({"sines": sines, "pairs": pairs, "rotations": rotations}, indent=1))
print(f"steady vectors: {len(sines)} sines, {len(pairs)} random pairs, {len(rotations)} rotations "
      f"in {out}")
