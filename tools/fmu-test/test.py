"""The FMUs of `wbv fmu` checked by FMPy, which shares no code with wbv (docs/fmu.md).

1. Every built-in model: `wbv fmu`, `fmpy.validation.validate_fmu` (no problems), a simulation
   with an input CSV of a floor acceleration (finite outputs).
2. Equality: communication step = dt, the FMU's a_seat_z and a_head_z against `wbv simulate
   --excitation recorded --input FILE --csv` on the input delayed by one step (the FMU's input
   convention), ≤ 1e-9 relative r.m.s.: a linear model, the scissor seat with its end stops
   engaged, the planar model.
3. Communication points that are not multiples of dt.
4. State: get, step 1000 times, set, step again: the same outputs bit for bit; the serialised
   state in a second instance too.
5. Faults through FMPy's low-level API: NaN and infinite input, zero and negative step, a step
   backwards, a parameter out of range or set after initialisation: fmi2Error, a logged message,
   the process goes on.
6. Two instances in one process are independent.
7. Closed loop: a vehicle body in numpy, the seat FMU, f_floor_z fed back, against `wbv simulate`
   of the monolithic model file at 1, 2 and 5 ms communication steps.

Usage: test.py WBV_BIN WORKDIR
"""

import json
import math
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import fmpy
from fmpy import read_model_description, extract
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import (
    FMU2Slave,
    fmi2CallbackFunctions,
    fmi2CallbackLoggerTYPE,
    fmi2CallbackAllocateMemoryTYPE,
    fmi2CallbackFreeMemoryTYPE,
)
from fmpy import calloc, free
from fmpy.validation import validate_fmu

WBV = sys.argv[1]
WORK = Path(sys.argv[2])
WORK.mkdir(parents=True, exist_ok=True)
DT = 1e-3
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def wbv(*args):
    out = subprocess.run([WBV, *args], capture_output=True, text=True)
    if out.returncode != 0:
        raise SystemExit(f"wbv {' '.join(args)} failed: {out.stderr}")
    return out.stdout


def make_fmu(model, name=None, extra=()):
    path = WORK / f"{name or model.replace('/', '_')}.fmu"
    wbv("fmu", "--model", model, "--out", str(path), "--force", *extra)
    return path


def floor_signal(n, seed, rms, band=(0.5, 20.0), offset=0.0):
    """Band-limited Gaussian noise sampled every DT (numpy FFT), scaled to `rms`."""
    rng = np.random.default_rng(seed)
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, DT)
    spec[(f < band[0]) | (f > band[1])] = 0.0
    x = np.fft.irfft(spec, n)
    return offset + x * rms / np.sqrt(np.mean(x**2))


def write_csv(path, a):
    with open(path, "w") as fh:
        fh.write("t_s,a_base_z\n")
        for k, v in enumerate(a):
            fh.write(f"{k * DT!r},{float(v)!r}\n")


def simulate_wbv(model, a, tag, extra=()):
    """`wbv simulate` on floor acceleration `a` (one sample per DT): its CSV as columns."""
    inp, out = WORK / f"{tag}-in.csv", WORK / f"{tag}-out.csv"
    write_csv(inp, a)
    wbv("simulate", "--model", str(model), "--excitation", "recorded", "--input", str(inp),
        "--dt", repr(DT), "--csv", str(out), "--no-record", "--force", *extra)
    data = np.genfromtxt(out, delimiter=",", names=True)
    return data


def simulate_fmu(fmu, a, outputs, step=DT, stop=None):
    t = np.arange(len(a)) * DT
    signals = np.array(list(zip(t, a)), dtype=[("time", float), ("a_floor_z", float)])
    return fmpy.simulate_fmu(
        str(fmu), input=signals, output=outputs, step_size=step, output_interval=step,
        stop_time=stop if stop is not None else t[-1], fmi_type="CoSimulation")


def rel_rms(x, ref):
    return float(np.sqrt(np.mean((x - ref) ** 2)) / np.sqrt(np.mean(ref**2)))


class Logged:
    """FMPy's callbacks with a logger that keeps the messages."""

    def __init__(self):
        self.messages = []
        cb = fmi2CallbackFunctions()
        cb.logger = fmi2CallbackLoggerTYPE(self.log)
        cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self.callbacks = cb

    def log(self, env, name, status, category, message):
        self.messages.append((status, message.decode()))


EXTRACTED = {}


def slave(fmu, logged=None, params=()):
    """An initialised instance; every instance of one FMU loads the same extracted library."""
    md = read_model_description(str(fmu))
    if str(fmu) not in EXTRACTED:
        EXTRACTED[str(fmu)] = extract(str(fmu), unzipdir=str(WORK / f"x{len(EXTRACTED)}"))
    unzipped = EXTRACTED[str(fmu)]
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                  modelIdentifier=md.coSimulation.modelIdentifier, instanceName="seat")
    s.instantiate(callbacks=logged.callbacks if logged else None)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    for name, value in params:
        s.setReal([vr[name]], [value])
    s.exitInitializationMode()
    return s, vr


# 1. Every built-in model.
t0 = time.time()
models = [m["name"] for m in json.loads(wbv("models", "--json"))["models"]]
a_short = floor_signal(2000, 1, 0.5)
for m in models:
    fmu = make_fmu(m)
    problems = validate_fmu(str(fmu))
    check(problems == [], f"{m}: validate_fmu: {problems or 'no problems'}")
    r = simulate_fmu(fmu, a_short, ["f_floor_z", "a_seat_z", "a_w_seat_z", "vdv_seat_z"])
    finite = all(np.all(np.isfinite(r[c])) for c in r.dtype.names)
    check(finite and len(r) == len(a_short), f"{m}: FMPy simulates 2 s, outputs finite")
print(f"(catalogue: {len(models)} models in {time.time() - t0:.1f} s)")

# A stack with a model file among its parts, and a model file alone.
repo = Path(__file__).resolve().parents[2]
(WORK / "my-seat.toml").write_text((repo / "models/scissor-seat.toml").read_text())
(WORK / "my-cushion.toml").write_text((repo / "models/cushion-zener.toml").read_text())
for tag, spec in (("model file", str(WORK / "my-seat.toml")),
                  ("stack with a file", f"wan-schimmels-4dof+{WORK / 'my-cushion.toml'}")):
    fmu = make_fmu(spec, tag.replace(" ", "-"))
    problems = validate_fmu(str(fmu))
    r = simulate_fmu(fmu, a_short, ["f_floor_z", "a_seat_z"])
    check(problems == [] and np.all(np.isfinite(r["a_seat_z"])),
          f"FMU of a {tag}: validate_fmu {problems or 'no problems'}, simulates")

# 2. Equality with wbv simulate on the input delayed by one step.
n = 12000
cases = [
    ("reference", floor_signal(n, 2, 1.0, offset=0.2), ()),
    ("scissor-seat", floor_signal(n, 3, 4.0, band=(0.5, 4.0)), ()),
    ("planar-occupant", floor_signal(n, 4, 1.0), ()),
    ("reference", floor_signal(n, 5, 1.0), ("--integrator", "rk4")),
]
for model, a, extra in cases:
    tag = model + "".join(extra)
    fmu = make_fmu(model, tag, extra)
    delayed = np.concatenate([[a[0]], a[:-1]])
    ref = simulate_wbv(model, delayed, tag, extra)
    names = [c for c in ("a_seat_z", "a_head_z", "f_seat_z") if c in ref.dtype.names]
    r = simulate_fmu(fmu, a, names)
    k = len(r)
    for c in names:
        e = rel_rms(r[c], ref[c][:k])
        bound = 1e-9 if "rk4" not in extra else 1e-2
        check(e <= bound, f"{tag}: {c} FMU vs wbv simulate, rel. r.m.s. {e:.2e} (≤ {bound:g})")
    if model == "scissor-seat":
        # The end stops engage: the suspension's stroke passes its free travel.
        plain = simulate_fmu(fmu, a * 1e-3, ["a_seat_z"])
        nonlin = rel_rms(r["a_seat_z"] * 1e-3, plain["a_seat_z"])
        check(nonlin > 1e-3, f"scissor-seat: response not proportional to the input (end stops engaged): {nonlin:.2e}")

# 3. Communication points that are not multiples of dt.
fmu = make_fmu("reference")
a = floor_signal(n, 6, 1.0)
base = simulate_fmu(fmu, a, ["a_head_z"])
odd = simulate_fmu(fmu, a, ["a_head_z"], step=0.0015)
ref_at = np.interp(odd["time"], base["time"], base["a_head_z"])
e = rel_rms(odd["a_head_z"], ref_at)
check(np.all(np.isfinite(odd["a_head_z"])) and e < 0.1,
      f"reference: communication step 1.5 ms (dt 1 ms) runs, a_head_z within {e:.3f} of the 1 ms run")

# 4. State get/set, bit for bit; serialised into another instance.
s, vr = slave(fmu)
outs = [vr[c] for c in ("f_floor_z", "a_seat_z", "a_head_z", "a_w_seat_z", "vdv_seat_z")]
t = 0.0
for k in range(200):
    s.setReal([vr["a_floor_z"]], [a[k]])
    s.doStep(t, DT)
    t += DT
state = s.getFMUstate()
blob = s.serializeFMUstate(state)


def run_from(sl, t_start, k0, steps=1000):
    rows, tt = [], t_start
    for k in range(k0, k0 + steps):
        sl.setReal([vr["a_floor_z"]], [a[k]])
        sl.doStep(tt, DT)
        tt += DT
        rows.append(sl.getReal(outs))
    return np.array(rows)


first = run_from(s, t, 200)
s.setFMUstate(state)
again = run_from(s, t, 200)
check(np.array_equal(first, again), "state: get, 1000 steps, set, 1000 steps: bit for bit")
other, _ = slave(fmu)
restored = other.deSerializeFMUstate(blob)
other.setFMUstate(restored)
third = run_from(other, t, 200)
check(np.array_equal(first, third), f"state: serialised ({len(blob)} bytes) into a second instance: bit for bit")
s.freeFMUstate(state)
other.freeFMUstate(restored)
other.terminate()
other.freeInstance()
s.terminate()
s.reset()
s.setupExperiment(startTime=0.0)
s.enterInitializationMode()
s.exitInitializationMode()
run_from(s, 0.0, 0, 200)
check(np.array_equal(first, run_from(s, t, 200)), "reset: terminate, reset, initialise, the same run again bit for bit")
s.terminate()
s.freeInstance()

# 5. Faults through the low-level API.


def fault(what, call, logged):
    before = len(logged.messages)
    try:
        call()
        check(False, f"fault {what}: no error returned")
        return
    except FMICallException as e:
        status = e.status
    new = logged.messages[before:]
    check(status == 3 and new and new[-1][0] == 3,
          f"fault {what}: fmi2Error, logged: {new[-1][1] if new else '(nothing)'}")


logged = Logged()
s, vr = slave(fmu, logged)
s.setReal([vr["a_floor_z"]], [0.1])
s.doStep(0.0, DT)
fault("NaN input", lambda: s.setReal([vr["a_floor_z"]], [float("nan")]), logged)
fault("infinite input", lambda: s.setReal([vr["a_floor_z"]], [float("inf")]), logged)
fault("zero step", lambda: s.doStep(DT, 0.0), logged)
fault("negative step", lambda: s.doStep(DT, -DT), logged)
fault("step backwards", lambda: s.doStep(0.0, DT), logged)
fault("parameter after initialisation", lambda: s.setReal([vr["mass.head.m"]], [5.0]), logged)
fault("directional derivative (not provided)",
      lambda: s.getDirectionalDerivative([vr["a_head_z"]], [vr["a_floor_z"]], [1.0]), logged)
s.doStep(DT, DT)  # the instance goes on after refused calls
check(np.isfinite(s.getReal([vr["a_head_z"]])[0]), "faults: the instance steps on after the refused calls")
s.terminate()
s.freeInstance()
logged2 = Logged()
md = read_model_description(str(fmu))
s2 = FMU2Slave(guid=md.guid, unzipDirectory=EXTRACTED[str(fmu)],
               modelIdentifier=md.coSimulation.modelIdentifier, instanceName="bad-param")
s2.instantiate(callbacks=logged2.callbacks)
s2.setupExperiment(startTime=0.0)
s2.enterInitializationMode()
fault("negative mass", lambda: s2.setReal([vr["mass.head.m"]], [-1.0]), logged2)
fault("NaN stiffness", lambda: s2.setReal([vr["link.cushion.k"]], [float("nan")]), logged2)
s2.exitInitializationMode()
s2.terminate()
s2.freeInstance()
check(True, "faults: the importing process survived every refused call")

# 6. Two instances in one process are independent (one extracted library, loaded once).
b_sig = floor_signal(n, 7, 2.0)
s_a, _ = slave(fmu)
s_b, _ = slave(fmu, params=[("mass.head.m", 7.0)])
ra, rb, tt = [], [], 0.0
for k in range(3000):
    s_a.setReal([vr["a_floor_z"]], [a[k]])
    s_b.setReal([vr["a_floor_z"]], [b_sig[k]])
    s_a.doStep(tt, DT)
    s_b.doStep(tt, DT)
    tt += DT
    ra.append(s_a.getReal([vr["a_head_z"]])[0])
    rb.append(s_b.getReal([vr["a_head_z"]])[0])
for sl in (s_a, s_b):
    sl.terminate()
    sl.freeInstance()
s_alone, _ = slave(fmu)
alone_a, tt = [], 0.0
for k in range(3000):
    s_alone.setReal([vr["a_floor_z"]], [a[k]])
    s_alone.doStep(tt, DT)
    tt += DT
    alone_a.append(s_alone.getReal([vr["a_head_z"]])[0])
s_alone.terminate()
s_alone.freeInstance()
alone_a = np.array(alone_a)
check(np.array_equal(np.array(ra), alone_a), "two instances: instance A equals A run alone, bit for bit")
check(not np.allclose(np.array(rb), alone_a), "two instances: instance B (other input, other head mass) differs")

# 7. Closed loop: vehicle body in numpy, seat FMU, f_floor_z fed back.
M_B, K_S, C_S = 400.0, 4.0e4, 2.0e3  # kg, N/m, N·s/m: body on its suspension (≈1.6 Hz)
vehicle = WORK / "vehicle.toml"
vehicle.write_text(f'''name = "vehicle"
description = "vehicle body on its suspension (closed-loop test)"
source = "tools/fmu-test"
kind = "seat"
top = "body"

[[mass]]
name = "body"
role = "frame"
m = {M_B!r}

[[link]]
name = "suspension"
between = ["body", "base"]
role = "frame"
type = "kelvin-voigt"
k = {K_S!r}
c = {C_S!r}
''')
road = floor_signal(n, 8, 1.0, band=(0.5, 15.0))
mono = simulate_wbv(f"boileau-rakheja-4dof+cushion-reference+{vehicle}", road, "mono")


def cosim(H):
    """Gauss–Seidel co-simulation at communication step H (s): the seat FMU first, then the body
    by the trapezoidal rule with the floor force linear over the step."""
    s, vr = slave(fmu)
    m = int(round(H / DT))
    steps = (n - 1) // m
    y = yd = 0.0  # body displacement and velocity relative to the road
    f_prev = 0.0
    a_b = 0.0
    head = []
    for k in range(steps):
        t = k * H
        s.setReal([vr["a_floor_z"]], [a_b])
        s.doStep(t, H)
        f_next, h = s.getReal([vr["f_floor_z"], vr["a_head_z"]])
        head.append(h)
        # Body over [t, t + H] in substeps of DT, road acceleration at the samples.
        for j in range(m):
            i = k * m + j
            f0 = f_prev + (f_next - f_prev) * j / m
            f1 = f_prev + (f_next - f_prev) * (j + 1) / m
            acc0 = (-K_S * y - C_S * yd + f0) / M_B - road[i]
            # implicit trapezoid (Newmark average acceleration) on the body alone
            kk = K_S / M_B * DT * DT / 4 + C_S / M_B * DT / 2 + 1.0
            rhs = (-K_S * (y + DT * yd + DT * DT / 4 * acc0) - C_S * (yd + DT / 2 * acc0) + f1) / M_B - road[i + 1]
            acc1 = rhs / kk
            y += DT * yd + DT * DT / 4 * (acc0 + acc1)
            yd += DT / 2 * (acc0 + acc1)
        f_prev = f_next
        a_b = (-K_S * y - C_S * yd + f_next) / M_B
    s.terminate()
    s.freeInstance()
    times = (np.arange(steps) + 1) * H
    return times, np.array(head)


errors = {}
for H in (5e-3, 2e-3, 1e-3):
    times, head = cosim(H)
    ref = np.interp(times, mono["t_s"], mono["a_head_z"])
    errors[H] = rel_rms(head, ref)
    print(f"closed loop: communication step {H * 1e3:.0f} ms: a_head_z rel. r.m.s. error {errors[H]:.3e}")
check(errors[1e-3] < errors[2e-3] < errors[5e-3],
      "closed loop: the error falls as the communication step shrinks (5 → 2 → 1 ms)")
check(errors[1e-3] < 0.05, f"closed loop: at 1 ms within 5 % of the monolithic model ({errors[1e-3]:.2%})")

print(f"fmu-test: {len(failures)} failed")
sys.exit(1 if failures else 0)
