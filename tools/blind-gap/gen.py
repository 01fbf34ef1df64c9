#!/usr/bin/env python3
"""Blind lab-condition cases for `wbv gap`, simulated without any wbv code.

Usage: gen.py OUTDIR --seed S --cases N        (writes OUTDIR/case-XXX/{run-*.csv, truth.json, cmd.json})
       gen.py --check-frf                      (plant check against `wbv frf --model reference`)

The plant is the structure of the `reference` setup (shared/specs/measured-runs.md): the
Boileau–Rakheja 4-DOF body (head, upper torso, lower torso, pelvis) on a Kelvin–Voigt cushion top
mass, base-excited. Its parameters are *data* copied from that spec; the assembly, integration,
sensors and DAQ below are written here, independently of wbv.

Integration. Coordinates are displacements relative to the base, z (m, up), so the base acceleration
a_b (m/s^2) is the only input: M z'' + C z' + K z = -M 1 a_b + (Maxwell arm forces) + (nonlinear
residual forces). The linear part is solved exactly per mode (diagonalised state space, first-order
hold on the input between fine samples, scipy.signal.lfilter per mode). A nonlinear law is split into
its tangent (in the linear part) and a residual force r(e) that is fed back by a fixed-step loop with the
exact zero-order-hold propagator (superposition). The fine rate is >= 4 kHz and >= 2x the output rate;
all channels then go through the same causal 6-pole Butterworth anti-alias filter at 0.4 fs and are
decimated, as a DAQ does.
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np
from scipy import integrate, linalg, optimize, signal

G = 9.80665  # m/s^2, standard gravity

# Reference setup (shared/specs/measured-runs.md), SI units.
REF_MASSES = {"head": 5.31, "upper_torso": 28.49, "lower_torso": 8.62, "pelvis": 12.78, "cushion": 1.0}
REF_LINKS = {  # name: (node i, node j or None for the base, k N/m, c N s/m)
    "k1": ("head", "upper_torso", 310000.0, 400.0),
    "k2": ("upper_torso", "lower_torso", 183000.0, 4750.0),
    "k3": ("lower_torso", "pelvis", 162800.0, 4585.0),
    "k4": ("pelvis", "cushion", 90000.0, 2064.0),
    "cushion": ("cushion", None, 80000.0, 500.0),
}
BODY = ["head", "upper_torso", "lower_torso", "pelvis"]
# Paper 001 (shared/seeds/001), configuration 4 (its Fig. 10, 6 DOF): the Table 1 body (a plain chain;
# the k5/c5 of eqs. (3), (5) are not in Table 1, ERRATA), the Table 3 Kelvin–Voigt cushion (0.7 kg,
# 20 kN/m, 200 N s/m) on the Table 2 suspension (suspended seat mass m_s 45 kg, 250 kN/m, 150 N s/m)
# on the base. Data copied from the paper's tables; the chain order is the paper's Fig. 10.
S1_MASSES = {"head": 6.5, "upper_torso": 30.5, "lower_torso": 9.5, "pelvis": 13.5, "cushion": 0.7,
             "seat_frame": 45.0}
S1_LINKS = {
    "k1": ("head", "upper_torso", 310000.0, 400.0),
    "k2": ("upper_torso", "lower_torso", 183000.0, 4750.0),
    "k3": ("lower_torso", "pelvis", 162000.0, 4600.0),
    "k4": ("pelvis", "cushion", 90000.0, 2100.0),
    "cushion": ("cushion", "seat_frame", 20000.0, 200.0),
    "suspension": ("seat_frame", None, 250000.0, 150.0),
}
MODELS = {"reference": (REF_MASSES, REF_LINKS), "seed001-full": (S1_MASSES, S1_LINKS)}


# ----------------------------------------------------------------------------------------------
# Plant assembly
# ----------------------------------------------------------------------------------------------
class Plant:
    """Masses, Kelvin–Voigt links, Maxwell arms (state = arm force) and at most one nonlinear link."""

    def __init__(self, masses, links, arms=(), nonlinear=None):
        self.names = list(masses)
        self.m = np.array([masses[n] for n in self.names])
        self.links = dict(links)
        self.arms = list(arms)  # (i, j, k_m, tau_s)
        self.nonlinear = nonlinear  # (i, j, residual function r(e) -> force on i, e = z_i - z_j)

    def idx(self, n):
        return None if n is None else self.names.index(n)

    def matrices(self):
        """State x = [z, z', arm forces]; A, B (input a_b), and the output map of absolute accelerations."""
        nm = len(self.names)
        na = len(self.arms)
        K = np.zeros((nm, nm))
        C = np.zeros((nm, nm))
        for (i, j, k, c) in self.links.values():
            for (mat, val) in ((K, k), (C, c)):
                a, b = self.idx(i), self.idx(j)
                mat[a, a] += val
                if b is not None:
                    mat[b, b] += val
                    mat[a, b] -= val
                    mat[b, a] -= val
        n = 2 * nm + na
        A = np.zeros((n, n))
        A[:nm, nm:2 * nm] = np.eye(nm)
        Minv = np.diag(1.0 / self.m)
        A[nm:2 * nm, :nm] = -Minv @ K
        A[nm:2 * nm, nm:2 * nm] = -Minv @ C
        for q, (i, j, km, tau) in enumerate(self.arms):
            a, b = self.idx(i), self.idx(j)
            s = 2 * nm + q
            # arm force F (tension positive): F' = k_m e' - F / tau, e = z_i - z_j; force on i is -F.
            A[s, nm + a] += km
            if b is not None:
                A[s, nm + b] -= km
            A[s, s] = -1.0 / tau
            A[nm + a, s] -= 1.0 / self.m[a]
            if b is not None:
                A[nm + b, s] += 1.0 / self.m[b]
        B = np.zeros(n)
        B[nm:2 * nm] = -1.0
        Bf = np.zeros(n)  # residual force on i (and its reaction on j)
        if self.nonlinear is not None:
            i, j, _ = self.nonlinear
            Bf[nm + self.idx(i)] = 1.0 / self.m[self.idx(i)]
            if self.idx(j) is not None:
                Bf[nm + self.idx(j)] = -1.0 / self.m[self.idx(j)]
        return A, B, Bf

    def deflection_row(self, i, j):
        n = 2 * len(self.names) + len(self.arms)
        row = np.zeros(n)
        row[self.idx(i)] = 1.0
        if self.idx(j) is not None:
            row[self.idx(j)] -= 1.0
        return row

    def rate_row(self, i, j):
        row = np.roll(self.deflection_row(i, j), len(self.names))
        return row

    def static_weight(self):
        return G * float(self.m.sum())


def simulate(plant, u, h, outputs):
    """Simulate base acceleration u (fine grid, step h s). outputs: dict name -> ('acc', node) or
    ('force', list of (row_x, coef), coef_r) linear functionals. Returns dict of arrays."""
    A, B, Bf = plant.matrices()
    lam, V = linalg.eig(A)
    Vinv = linalg.inv(V)
    E = np.exp(lam * h)
    I0 = np.where(np.abs(lam) > 1e-12, (E - 1.0) / np.where(lam == 0, 1, lam), h)
    I1 = np.where(np.abs(lam) > 1e-12, (E - 1.0 - lam * h) / (np.where(lam == 0, 1, lam) ** 2 * h), h / 2)
    bq = Vinv @ B
    n = len(u)
    # Output rows on the state: absolute acceleration of a mass = its z'' + a_b = A-row x (B cancels).
    nm = len(plant.names)
    rows = {}
    rrow = {}
    for name, spec in outputs.items():
        if spec[0] == "acc":
            a = plant.idx(spec[1])
            rows[name] = A[nm + a].copy()
            rrow[name] = Bf[nm + a]
        else:
            rows[name] = spec[1]
            rrow[name] = spec[2]
    out_modal = {name: rows[name] @ V for name in rows}
    # Linear response per mode (FOH): q[n] = E q[n-1] + b (I1 u[n] + (I0 - I1) u[n-1]).
    res = {name: np.zeros(n) for name in rows}
    need_state = plant.nonlinear is not None
    if need_state:
        i, j, rfun = plant.nonlinear
        drow = plant.deflection_row(i, j)
        e_lin = np.zeros(n)
        stateful = hasattr(rfun, "step")  # a law with memory/velocity (suspension, see SuspLaw)
        vrow = plant.rate_row(i, j)
        v_lin = np.zeros(n)
    for q in range(len(lam)):
        if abs(bq[q]) < 1e-300:
            continue
        if lam[q].imag < -1e-9:  # conjugate partner handled with its pair (2 x real part)
            continue
        fac = 1.0 if abs(lam[q].imag) <= 1e-9 else 2.0
        qq = signal.lfilter([bq[q] * I1[q], bq[q] * (I0[q] - I1[q])], [1.0, -E[q]], u.astype(complex))
        for name in rows:
            res[name] += fac * np.real(out_modal[name][q] * qq)
        if need_state:
            e_lin += fac * np.real((drow @ V[:, q]) * qq)
            v_lin += fac * np.real((vrow @ V[:, q]) * qq)
    if need_state:
        # Residual feedback with the exact ZOH propagator: x_nl[n+1] = Ad x_nl[n] + Gd r[n].
        Ad = np.real(V @ np.diag(E) @ Vinv)
        Gd = np.real(V @ (I0 * (Vinv @ Bf)))
        x = np.zeros(len(lam))
        r = np.zeros(n)
        X = np.empty((n, len(lam)))
        if stateful:
            ge, gv = float(drow @ Gd), float(vrow @ Gd)
            rows4 = np.vstack([drow, vrow, drow @ Ad, vrow @ Ad])
            lin4 = np.column_stack([e_lin, v_lin, np.append(e_lin[1:], e_lin[-1]), np.append(v_lin[1:], v_lin[-1])])
        for k in range(n):
            X[k] = x
            if stateful:  # the law sees e, v now and their values at k+1 without its force
                w = lin4[k] + rows4 @ x
                rk = rfun.step(w[0], w[1], w[2], w[3], ge, gv)
            else:
                rk = rfun(e_lin[k] + drow @ x)
            r[k] = rk
            x = Ad @ x + Gd * rk
        for name in rows:
            res[name] += X @ rows[name] + rrow[name] * r
    return res


def frf_check(model="reference"):
    """Plant vs `wbv frf --model reference`: (1) the assembled state space's H(j2πf) against wbv's
    curves (data-entry/assembly check); (2) the time-domain integrator on sine dwells (steady-state
    complex amplitude by a single-bin DFT over the last 20 s) against that H (integration check)."""
    p = Plant(*MODELS[model])
    out = subprocess.run([os.environ.get("WBV", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "target", "release", "wbv")), "frf", "--model", model, "--from", "0.5", "--to", "40",
                          "--points", "400"], capture_output=True, text=True, check=True).stdout
    ref = np.genfromtxt(out.splitlines(), delimiter=",", names=True)
    A, B, _ = p.matrices()
    nm = len(p.names)
    seat, head = nm + p.idx("cushion"), nm + p.idx("head")

    def hexact(fr):
        x = linalg.solve(2j * np.pi * fr * np.eye(len(A)) - A, B)
        return A[seat] @ x, (A[head] @ x) / (A[seat] @ x)

    ex = np.array([hexact(fr) for fr in ref["freq_hz"]])
    print("assembly: max |H_seat - wbv seat_mag| / wbv = %.1e, max |STHT - wbv stht_mag| / wbv = %.1e"
          % (np.max(np.abs(np.abs(ex[:, 0]) - ref["seat_mag"]) / ref["seat_mag"]),
             np.max(np.abs(np.abs(ex[:, 1]) - ref["stht_mag"]) / ref["stht_mag"])))
    if "seat_frame" in p.names:  # suspended seat mass (seed001-full): complex, magnitude and phase
        fr_i = nm + p.idx("seat_frame")
        hf = np.array([A[fr_i] @ linalg.solve(2j * np.pi * fr * np.eye(len(A)) - A, B) for fr in ref["freq_hz"]])
        cplx = lambda name: ref[name + "_mag"] * np.exp(1j * np.deg2rad(ref[name + "_phase_deg"]))
        print("assembly (complex): max |H - wbv| / |wbv|: seat %.1e, STHT %.1e, seat frame %.1e"
              % tuple(np.max(np.abs(h_ - cplx(nme)) / np.abs(cplx(nme)))
                      for h_, nme in ((ex[:, 0], "seat"), (ex[:, 1], "stht"), (hf, "t_seat_frame"))))
    h = 1 / 4096.0
    t = np.arange(int(40 / h)) * h
    last = t >= 20
    worst = [0.0, 0.0]
    for fr in (0.5, 1, 2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 25, 30, 40):
        u = np.sin(2 * np.pi * fr * t)
        y = simulate(p, u, h, {"seat": ("acc", "cushion"), "head": ("acc", "head")})
        ph = np.exp(-2j * np.pi * fr * t[last])
        au, asb, ahd = (np.mean(v[last] * ph) for v in (u, y["seat"], y["head"]))
        hs, hh = hexact(fr)
        worst[0] = max(worst[0], abs(asb / au / hs - 1))
        worst[1] = max(worst[1], abs(ahd / asb / hh - 1))
    print("integration (sine dwells 0.5-40 Hz at 4096 Hz): max complex error seat %.4f %%, STHT %.4f %%"
          % (100 * worst[0], 100 * worst[1]))


# ----------------------------------------------------------------------------------------------
# The subject, the hidden effect
# ----------------------------------------------------------------------------------------------
def draw_subject(rng, model="reference"):
    """Every mass +-10 %, stiffness +-15 %, damping +-25 % (uniform): the occupant is not the model's
    (on seed001-full the seat's cushion and suspension too: a seat is not its data sheet)."""
    ref_masses, ref_links = MODELS[model]
    masses = {n: m * rng.uniform(0.9, 1.1) for n, m in ref_masses.items()}
    links = {n: (i, j, k * rng.uniform(0.85, 1.15), c * rng.uniform(0.75, 1.25))
             for n, (i, j, k, c) in ref_links.items()}
    return masses, links


FAMILIES = {
    "viscoelastic": ["sls", "maxwell2", "fractional"],
    "stiffening": ["cubic", "exponential", "bottoming"],
    "softening": ["tanh", "bilinear", "magnitude-saturating"],
    "support-path": ["backrest", "thigh-path", "hands-wheel"],
    "missing-dof": ["seat-frame", "viscera"],
    "sensor": ["delay", "mount", "lowpass", "gain"],
}
# Forms reached only by a study set (--form): the random rotation above stays as it was, so the
# cases of earlier seeds are drawn the same.
STUDY_FORMS = {"viscoelastic": ["kww"], "missing-dof": ["rocking-frame", "floor-panel"], "sensor": ["highpass-multi", "lowpass-multi"],
               "body-stiffening": ["magnitude-stiffening"], "support-path": ["harness", "lap-belt", "feet-lift-off", "head-restraint"]}


def prony_fractional(kf, alpha, f0, rng_lo=0.2, rng_hi=100.0, n=8):
    """Maxwell arms (k_n, tau_n) whose sum approximates k_f (j w / w0)^alpha over rng_lo..rng_hi Hz
    (non-negative least squares on real and imaginary parts, log-spaced relaxation times)."""
    taus = 1.0 / (2 * np.pi * np.geomspace(rng_lo / 2, rng_hi * 2, n))
    f = np.geomspace(rng_lo, rng_hi, 200)
    w = 2 * np.pi * f
    target = kf * (1j * w / (2 * np.pi * f0)) ** alpha
    basis = (1j * w[:, None] * taus[None, :]) / (1 + 1j * w[:, None] * taus[None, :])
    scale = np.abs(target)[:, None]
    Aml = np.vstack([(basis.real / scale), (basis.imag / scale)])
    bml = np.concatenate([target.real / np.abs(target), target.imag / np.abs(target)])
    kn, _ = optimize.nnls(Aml, bml)
    fit = basis @ kn
    err = float(np.max(np.abs(fit - target) / np.abs(target)))
    return [(float(k), float(t)) for k, t in zip(kn, taus) if k > 0], err


def kww_modulus(w, tau, beta):
    """The normalised complex modulus of a stretched-exponential (Kohlrausch-Williams-
    Watts) relaxation phi(t) = exp(-(t/tau)^beta), M*(w) = i w int_0^inf phi(t) e^{-i w t} dt, by
    scipy's Fourier-weighted quadrature (QAWF) on each frequency; 0 at rest, 1 at high frequency."""
    out = []
    for wi in np.atleast_1d(w):
        phi = lambda t: np.exp(-(t / tau) ** beta)
        c, _ = integrate.quad(phi, 0, np.inf, weight="cos", wvar=wi, limlst=200)
        s_, _ = integrate.quad(phi, 0, np.inf, weight="sin", wvar=wi, limlst=200)
        out.append(1j * wi * (c - 1j * s_))
    return np.array(out)


def prony_kww(dk, tau, beta, rng_lo=0.2, rng_hi=100.0, n=12):
    """Maxwell arms (k_n, tau_n) whose sum approximates dk * M_kww(w) over rng_lo..rng_hi Hz
    (non-negative least squares, relative error, log-spaced relaxation times two decades beyond)."""
    taus = 1.0 / (2 * np.pi * np.geomspace(rng_lo / 10, rng_hi * 10, n))
    f = np.geomspace(rng_lo, rng_hi, 120)
    w = 2 * np.pi * f
    target = dk * kww_modulus(w, tau, beta)
    basis = (1j * w[:, None] * taus[None, :]) / (1 + 1j * w[:, None] * taus[None, :])
    scale = np.abs(target)[:, None]
    A = np.vstack([basis.real / scale, basis.imag / scale])
    b = np.concatenate([target.real / np.abs(target), target.imag / np.abs(target)])
    kn, _ = optimize.nnls(A, b)
    err = float(np.max(np.abs(basis @ kn - target) / np.abs(target)))
    return [(float(k), float(t)) for k, t in zip(kn, taus) if k > 0], err


def draw_effect(rng, family, form, strength):
    """Parameters of one hidden effect; `strength` >= 1 scales its departure from the linear model."""
    p = {}
    if family == "suspension":
        return draw_suspension(rng, form, strength)
    if family == "viscoelastic":
        if form == "sls":
            p = {"k_arm_over_k": min(2.0, rng.uniform(0.3, 0.9) * strength), "tau_s": rng.uniform(0.003, 0.03),
                 "c_parallel_over_c": rng.uniform(0.2, 0.8)}
        elif form == "maxwell2":
            p = {"k1_over_k": min(1.5, rng.uniform(0.2, 0.6) * strength), "tau1_s": rng.uniform(0.002, 0.01),
                 "k2_over_k": min(1.5, rng.uniform(0.2, 0.6) * strength), "tau2_s": rng.uniform(0.03, 0.2),
                 "c_parallel_over_c": rng.uniform(0.1, 0.6)}
        elif form == "kww":
            # a cold foam: stretched-exponential relaxation, its loss peak broad and skewed to high
            # frequency (beta 0.3-0.6), near the body modes
            p = {"dk_over_k": min(2.0, rng.uniform(0.3, 0.9) * strength), "tau_s": float(np.exp(rng.uniform(np.log(0.003), np.log(0.05)))),
                 "beta": rng.uniform(0.3, 0.6), "c_parallel_over_c": rng.uniform(0.2, 0.8)}
        else:
            p = {"kf_over_k": min(1.0, rng.uniform(0.2, 0.5) * strength), "alpha": rng.uniform(0.2, 0.6),
                 "f0_hz": 5.0, "c_parallel_over_c": rng.uniform(0.1, 0.5)}
    elif family == "stiffening":
        if form == "cubic":
            # F = k1 d + k3 d^3 (total compression d), tangent at the gravity sag = subject's k_c.
            p = {"sag_over_W_per_k": min(2.9, 1.2 + rng.uniform(0.6, 1.4) * strength)}
        elif form == "exponential":
            # F = F0 (exp(d / d_e) - 1), tangent at the sag = k_c; d_e >= W / k_c.
            p = {"de_over_W_per_k": max(1.02, rng.uniform(1.05, 1.5) / strength)}
        else:
            # a second, stiffer layer touches beyond a gap delta past the sag (bottoming/progressive)
            p = {"gap_over_sigma": max(0.2, rng.uniform(0.6, 1.6) / strength),
                 "k_stop_over_k": rng.uniform(0.5, 2.0)}
    elif family == "body-stiffening":
        # the opposite of a softening: k(A) = k (1 + s (1 - exp(-A / A_s))), the body's resonance
        # rising with magnitude (a tensing subject); damping follows with half of s
        p = {"s": {lk: -min(0.8, rng.uniform(0.2, 0.5) * strength) for lk in ("k2", "k3", "k4")},
             "A_s": rng.uniform(0.4, 1.2)}
    elif family == "softening":
        if form == "tanh":
            p = {"link": "k4", "ds_over_sigma": max(0.4, rng.uniform(1.0, 2.5) / strength)}
        elif form == "bilinear":
            p = {"link": "k4", "eb_over_sigma": max(0.2, rng.uniform(0.4, 1.2) / strength),
                 "slope_ratio": max(0.1, 1 - rng.uniform(0.3, 0.6) * strength)}
        else:
            # k(A) = k (1 - s (1 - exp(-A / A_s))), per link unequal; damping follows with half of s.
            p = {"s": {lk: min(0.8, rng.uniform(0.2, 0.5) * strength) for lk in ("k2", "k3", "k4")},
                 "A_s": rng.uniform(0.4, 1.2)}
    elif family == "support-path":
        if form == "backrest":
            p = {"k_N_per_m": rng.uniform(10e3, 40e3) * strength, "c_Ns_per_m": rng.uniform(200, 1000) * strength}
        elif form == "hands-wheel":
            # hands on a steering wheel: the arms (about a tenth of body mass for two) leave the upper
            # torso, hang on the shoulders and grip a wheel rim that sits on a steel steering column
            p = {"m_arms_kg": rng.uniform(4.0, 8.0),
                 "k_shoulder_N_per_m": rng.uniform(3e3, 12e3) * strength,
                 "c_shoulder_Ns_per_m": rng.uniform(80, 300) * strength,
                 "k_grip_N_per_m": rng.uniform(60e3, 200e3), "c_grip_Ns_per_m": rng.uniform(150, 500),
                 "m_wheel_kg": rng.uniform(2.0, 5.0), "f_column_hz": rng.uniform(25, 45),
                 "zeta_column": rng.uniform(0.03, 0.1)}
        elif form == "harness":
            # a pilot's shoulder harness from the seat back over the shoulders: webbing that pulls
            # the upper torso down only in tension, once the torso has risen past the strap's
            # slack (a one-sided path, unlike the candidates' two-sided spring-dampers)
            p = {"k_N_per_m": rng.uniform(15e3, 60e3) * strength,
                 "slack_over_sigma": max(0.0, rng.uniform(0.0, 1.0) / strength)}
        elif form == "lap-belt":
            # a lap belt from the seat frame across the pelvis: webbing anchored beside the seat pan
            # that pulls the pelvis down only in tension, once it has risen past the belt's slack;
            # the belt's force does not pass through the seat pan's force plate
            p = {"k_N_per_m": rng.uniform(20e3, 80e3) * strength,
                 "slack_over_sigma": max(0.0, rng.uniform(0.0, 1.0) / strength)}
        elif form == "feet-lift-off":
            # the feet on the floor carrying part of the pelvis past the seat pan, preloaded by the
            # legs' weight: the contact unloads and the feet leave the floor once the pelvis has
            # risen past the pad's static compression (a path that carries less the larger the
            # motion; its damper stays, so the law is not the candidates' clean lift-off)
            p = {"k_N_per_m": rng.uniform(20e3, 60e3) * strength, "c_Ns_per_m": rng.uniform(300, 1500) * strength,
                 "travel_over_sigma": rng.uniform(0.4, 1.2)}
        elif form == "head-restraint":
            # a reclined seat's head restraint the head rests on: a preloaded foam pad from the seat
            # back to the head (its damper always on) carrying part of the head's weight, that the
            # head leaves once it has risen past the pad's static compression
            p = {"k_N_per_m": rng.uniform(15e3, 60e3) * strength, "c_Ns_per_m": rng.uniform(60, 300) * strength,
                 "travel_over_sigma": rng.uniform(0.5, 1.5)}
        else:
            p = {"k_N_per_m": rng.uniform(20e3, 60e3) * strength, "c_Ns_per_m": rng.uniform(300, 1500) * strength}
    elif family == "missing-dof":
        if form == "seat-frame":
            p = {"m_kg": rng.uniform(3, 10), "f_loaded_hz": rng.uniform(20, 45), "zeta": rng.uniform(0.03, 0.15) / strength}
        elif form == "rocking-frame":
            p = {"m_kg": rng.uniform(4, 12), "front_mass_share": rng.uniform(0.3, 0.5),
                 "front_load_share": rng.uniform(0.15, 0.4), "rear_leg_share": rng.uniform(0.55, 0.8),
                 "f_loaded_hz": rng.uniform(15, 28), "zeta": rng.uniform(0.03, 0.1) / strength}
        elif form == "floor-panel":
            p = {"m_frame_kg": rng.uniform(3, 8), "f_frame_hz": rng.uniform(28, 45),
                 "m_panel_kg": rng.uniform(8, 20), "f_panel_hz": rng.uniform(12, 22),
                 "m_side_kg": rng.uniform(2, 6), "f_side_hz": rng.uniform(30, 55),
                 "zeta": rng.uniform(0.03, 0.1) / strength}
        else:
            p = {"host": str(rng.choice(["upper_torso", "lower_torso"])), "m_kg": min(8.0, rng.uniform(2, 5) * strength),
                 "f_hz": rng.uniform(4, 10), "zeta": rng.uniform(0.15, 0.4)}
    elif family == "sensor":
        ch = str(rng.choice(["a_seat_z", "a_head_z", "a_base_z"], p=[0.45, 0.4, 0.15]))
        p = {"channel": ch}
        if form == "delay":
            p["delay_s"] = min(0.02, rng.uniform(0.002, 0.02) * strength)
        elif form == "mount":
            p["f_hz"] = rng.uniform(15, 60) / strength
            p["zeta"] = rng.uniform(0.05, 0.2)
        elif form == "lowpass":
            p["f_hz"] = max(8.0, rng.uniform(15, 50) / strength)
            p["zeta"] = rng.uniform(0.5, 0.71)
        elif form == "highpass-multi":
            # a conditioner's high-pass: a charge amplifier's 2-pole, a 3- or 4-pole filter, in
            # designs other than Butterworth (cascaded RC stages, Bessel) or Butterworth itself
            p["order"] = int(rng.choice([2, 3, 4]))
            p["design"] = str(rng.choice(["rc", "bessel", "butter"]))
            p["f_hz"] = min(3.0, rng.uniform(0.3, 1.2) * strength)
        elif form == "lowpass-multi":
            p["channel"] = str(rng.choice(["a_seat_z", "a_head_z"]))
            p["order"] = int(rng.choice([1, 2, 3]))
            p["design"] = str(rng.choice(["rc", "bessel"]))
            p["f_hz"] = max(8.0, rng.uniform(12, 40) / strength)
        else:
            p["gain"] = 1 + float(rng.choice([-1, 1])) * min(0.3, rng.uniform(0.05, 0.15) * strength)
    return p


def frame_mode(masses, links, kf):
    """Undamped mode of the plant with frame spring kf whose strain energy is most in the frame spring:
    (frequency Hz, that share, modal mass seen by the frame spring kg)."""
    pl = Plant(masses, dict(links, frame=("frame", None, kf, 0.0)))
    nm = len(pl.names)
    A, _, _ = pl.matrices()
    K = -np.diag(pl.m) @ A[nm:2 * nm, :nm]
    w2, phi = linalg.eigh(K, np.diag(pl.m))
    fr = pl.idx("frame")
    share = [kf * phi[fr, q] ** 2 / (phi[:, q] @ K @ phi[:, q]) for q in range(nm)]
    q = int(np.argmax(share))
    return math.sqrt(max(w2[q], 0.0)) / (2 * np.pi), float(share[q]), kf / max(w2[q], 1e-9)


def frame_stiffness(masses, links, f_target):
    """Frame spring whose frame-dominated mode (most strain energy in the frame spring, with the
    occupant on the seat) is nearest f_target Hz, scanned over 1e4..1e9 N/m. The occupant above the
    cushion is partly decoupled at these frequencies, so the loaded mass comes from the eigenproblem;
    below ~15 Hz the frame mode mixes with the body's and the nearest reachable one is taken.
    Returns (k_f N/m, modal mass kg, actual frequency Hz, strain-energy share)."""
    best = None
    for kf in np.geomspace(1e4, 1e9, 500):
        f, share, me = frame_mode(masses, links, kf)
        if share < 0.4:
            continue
        err = abs(math.log(f / f_target))
        if best is None or err < best[0]:
            best = (err, float(kf), me, f, share)
    return best[1:]


def leg_modes(masses, links, kf, rho):
    """Undamped modes of the plant with a rear leg rho·kf and a front leg (1 - rho)·kf under the
    frame: (frequency Hz, share of strain energy in the legs) per mode."""
    pl = Plant(masses, dict(links, leg_rear=("frame_rear", None, rho * kf, 0.0),
                            leg_front=("frame_front", None, (1 - rho) * kf, 0.0)))
    nm = len(pl.names)
    A, _, _ = pl.matrices()
    K = -np.diag(pl.m) @ A[nm:2 * nm, :nm]
    w2, phi = linalg.eigh(K, np.diag(pl.m))
    r, f = pl.idx("frame_rear"), pl.idx("frame_front")
    out = []
    for q in range(nm):
        legs = rho * kf * phi[r, q] ** 2 + (1 - rho) * kf * phi[f, q] ** 2
        out.append((math.sqrt(max(w2[q], 0.0)) / (2 * np.pi), float(legs / (phi[:, q] @ K @ phi[:, q]))))
    return out


def build_plant(subject, family, form, p, A_rms, sigma):
    """The plant of one run. sigma: dict of linear-twin r.m.s. deflections (m) used to place
    amplitude thresholds ('cushion', 'k4'). Returns (Plant, contact-force functional builder)."""
    if family == "suspension":
        return build_suspension(subject, form, p, sigma)
    masses, links = dict(subject[0]), dict(subject[1])
    arms = []
    nonlinear = None
    if family == "viscoelastic":
        i, j, k, c = links["cushion"]
        if form == "sls":
            km = p["k_arm_over_k"] * k
            links["cushion"] = (i, j, k * (1 - 0.3 * p["k_arm_over_k"]), c * p["c_parallel_over_c"])
            arms.append((i, j, km, p["tau_s"]))
        elif form == "maxwell2":
            links["cushion"] = (i, j, k * (1 - 0.2 * (p["k1_over_k"] + p["k2_over_k"])), c * p["c_parallel_over_c"])
            arms.append((i, j, p["k1_over_k"] * k, p["tau1_s"]))
            arms.append((i, j, p["k2_over_k"] * k, p["tau2_s"]))
        elif form == "kww":
            series, _ = prony_kww(p["dk_over_k"] * k, p["tau_s"], p["beta"])
            links["cushion"] = (i, j, k, c * p["c_parallel_over_c"])
            for (kn, tn) in series:
                arms.append((i, j, kn, tn))
        else:
            series, _ = prony_fractional(p["kf_over_k"] * k, p["alpha"], p["f0_hz"])
            links["cushion"] = (i, j, k * (1 - 0.5 * p["kf_over_k"]), c * p["c_parallel_over_c"])
            for (kn, tn) in series:
                arms.append((i, j, kn, tn))
    elif family == "stiffening":
        i, j, kc, c = links["cushion"]
        W = G * sum(v for n, v in masses.items() if n != "seat_frame")  # the body and the cushion top
        if form == "cubic":
            d0 = p["sag_over_W_per_k"] * W / kc
            k3 = (kc * d0 - W) / (2 * d0 ** 3)
            k1 = kc - 3 * k3 * d0 ** 2
            F = lambda d: k1 * d + k3 * d ** 3
        elif form == "exponential":
            de = p["de_over_W_per_k"] * W / kc
            F0 = kc * de - W
            d0 = de * math.log(1 + W / F0)
            F = lambda d: F0 * (math.exp(d / de) - 1)
        else:
            d0 = W / kc
            gap = p["gap_over_sigma"] * sigma["cushion"]
            ks = p["k_stop_over_k"] * kc
            F = lambda d: kc * d + ks * max(0.0, d - d0 - gap)
        Fd0 = F(d0)

        # force on the top = +(F(d0 - e) - F(d0)); the linear part already applies -k_c e.
        nonlinear = ("cushion", j, lambda e, F=F, d0=d0, Fd0=Fd0, kc=kc: (F(d0 - e) - Fd0) + kc * e)
        p = dict(p, sag_m=d0)
    elif family == "softening" and form in ("tanh", "bilinear"):
        i, j, k, c = links["k4"]
        s4 = sigma["k4"]
        if form == "tanh":
            ds = p["ds_over_sigma"] * s4
            nonlinear = (i, j, lambda e, k=k, ds=ds: -k * ds * math.tanh(e / ds) + k * e)
        else:
            eb = p["eb_over_sigma"] * s4
            rr = p["slope_ratio"]

            def rb(e, k=k, eb=eb, rr=rr):
                a = abs(e)
                if a <= eb:
                    return 0.0
                spring = k * eb + rr * k * (a - eb)
                return -math.copysign(spring, e) + k * e
            nonlinear = (i, j, rb)
    elif family in ("softening", "body-stiffening"):
        for lk, s in p["s"].items():
            i, j, k, c = links[lk]
            fk = 1 - s * (1 - math.exp(-A_rms / p["A_s"]))
            fc = 1 - 0.5 * s * (1 - math.exp(-A_rms / p["A_s"]))
            links[lk] = (i, j, k * fk, c * fc)
    elif family == "support-path" and form == "hands-wheel":
        masses["upper_torso"] = masses["upper_torso"] - p["m_arms_kg"]
        masses["arms"], masses["wheel"] = p["m_arms_kg"], p["m_wheel_kg"]
        kc = p["m_wheel_kg"] * (2 * np.pi * p["f_column_hz"]) ** 2
        links["shoulder"] = ("upper_torso", "arms", p["k_shoulder_N_per_m"], p["c_shoulder_Ns_per_m"])
        links["grip"] = ("arms", "wheel", p["k_grip_N_per_m"], p["c_grip_Ns_per_m"])
        links["column"] = ("wheel", None, kc, 2 * p["zeta_column"] * math.sqrt(kc * p["m_wheel_kg"]))
    elif family == "support-path" and form == "harness":
        # tension only: force on the torso -k (e - slack) for a rise e past the slack, else none;
        # no tangent at rest, so the whole force is the residual fed back
        slack = p["slack_over_sigma"] * sigma["torso"]
        kh = p["k_N_per_m"]
        nonlinear = ("upper_torso", None, lambda e, kh=kh, slack=slack: -kh * max(0.0, e - slack))
        p = dict(p, slack_m=slack)
    elif family == "support-path" and form == "lap-belt":
        # the same tension-only law on the pelvis, anchored to the base (not through the cushion)
        slack = p["slack_over_sigma"] * sigma["pelvis"]
        kb = p["k_N_per_m"]
        nonlinear = ("pelvis", None, lambda e, kb=kb, slack=slack: -kb * max(0.0, e - slack))
        p = dict(p, slack_m=slack)
    elif family == "support-path" and form in ("feet-lift-off", "head-restraint"):
        # the linear pad from the floor to the pelvis (the feet) or from the seat back to the head
        # (a head restraint), and once that mass has risen past the pad's static compression the
        # spring's pull given back (the contact carries no tension)
        node = "pelvis" if form == "feet-lift-off" else "head"
        travel = p["travel_over_sigma"] * sigma[node]
        kp = p["k_N_per_m"]
        links["extra"] = (node, None, kp, p["c_Ns_per_m"])
        nonlinear = (node, None, lambda e, kp=kp, travel=travel: kp * max(0.0, e - travel))
        p = dict(p, travel_m=travel)
    elif family == "support-path":
        node = "upper_torso" if form == "backrest" else "pelvis"
        links["extra"] = (node, None, p["k_N_per_m"], p["c_Ns_per_m"])
    elif family == "missing-dof":
        if form == "seat-frame":
            masses["frame"] = p["m_kg"]
            i, _, k, c = links["cushion"]
            links["cushion"] = (i, "frame", k, c)
            kf, m_eff, f_act, share = frame_stiffness(masses, links, p["f_loaded_hz"])
            links["frame"] = ("frame", None, kf, 2 * p["zeta"] * math.sqrt(kf * m_eff))
            p["frame_mode_actual_hz"], p["frame_strain_share"], p["k_frame_N_per_m"] = f_act, share, kf
        elif form == "rocking-frame":
            # A frame on a rear and a front leg, its mass lumped at the two (its bounce and pitch are
            # the two ends' vertical motions), under a cushion carried at both: with the occupant's
            # load off the frame's middle and unequal legs, bounce and pitch couple and both modes
            # reach the seat pad, which reads only vertical motion.
            m, sm, w, rho = p["m_kg"], p["front_mass_share"], p["front_load_share"], p["rear_leg_share"]
            masses["frame_front"], masses["frame_rear"] = m * sm, m * (1 - sm)
            i, _, k, c = links["cushion"]
            links["cushion"] = (i, "frame_rear", k * (1 - w), c * (1 - w))
            links["cushion_front"] = (i, "frame_front", k * w, c * w)
            best = None
            for kf in np.geomspace(1e4, 1e9, 300):
                frame = sorted(f for f, share in leg_modes(masses, links, kf, rho) if share >= 0.4)
                if frame:
                    err = abs(math.log(frame[0] / p["f_loaded_hz"]))
                    if best is None or err < best[0]:
                        best = (err, float(kf), frame)
            _, kf, frame = best
            for name, node, kl in (("leg_rear", "frame_rear", rho * kf), ("leg_front", "frame_front", (1 - rho) * kf)):
                links[name] = (node, None, kl, 2 * p["zeta"] * kl / (2 * np.pi * frame[0]))
            p["frame_modes_hz"], p["k_legs_N_per_m"] = [float(f) for f in frame], kf
        elif form == "floor-panel":
            # A seat frame on a cab floor panel, between the base accelerometer (on the cab's
            # structure) and the seat: the panel's first plate mode a mass on its own spring to the
            # base carrying the frame, its second a modal mass hung off the panel beside the load
            # path (it moves the frame's footing, not the frame's load). Three lightly damped modes
            # reach the seat pad; the springs are tuned on their own masses, the modes with the
            # occupant seated come from the eigenproblem.
            masses["panel"], masses["panel_side"], masses["frame"] = p["m_panel_kg"], p["m_side_kg"], p["m_frame_kg"]
            i, _, k, c = links["cushion"]
            links["cushion"] = (i, "frame", k, c)
            z = p["zeta"]
            for name, node, to, m, f in (("frame", "frame", "panel", p["m_frame_kg"], p["f_frame_hz"]),
                                         ("panel", "panel", None, p["m_panel_kg"] + p["m_frame_kg"], p["f_panel_hz"]),
                                         ("panel_side", "panel_side", "panel", p["m_side_kg"], p["f_side_hz"])):
                kl = m * (2 * np.pi * f) ** 2
                links[name] = (node, to, kl, 2 * z * math.sqrt(kl * m))
            pl = Plant(masses, {n: (a, b, kk, 0.0) for n, (a, b, kk, _) in links.items()})
            nm = len(pl.names)
            A, _, _ = pl.matrices()
            K = -np.diag(pl.m) @ A[nm:2 * nm, :nm]
            w2, phi = linalg.eigh(K, np.diag(pl.m))
            parts = [pl.idx(n) for n in ("panel", "panel_side", "frame")]
            p["structure_modes_hz"] = [float(math.sqrt(max(w2[q], 0.0)) / (2 * np.pi)) for q in range(nm)
                                       if sum(pl.m[a] * phi[a, q] ** 2 for a in parts) / (phi[:, q] @ np.diag(pl.m) @ phi[:, q]) >= 0.5]
        else:
            host = p["host"]
            masses[host] = masses[host] - p["m_kg"]
            masses["viscera"] = p["m_kg"]
            kv = p["m_kg"] * (2 * np.pi * p["f_hz"]) ** 2
            links["viscera"] = ("viscera", host, kv, 2 * p["zeta"] * math.sqrt(kv * p["m_kg"]))
    return Plant(masses, links, arms, nonlinear)


# ----------------------------------------------------------------------------------------------
# Base excitation (fine grid), sensors, DAQ
# ----------------------------------------------------------------------------------------------
def shaped_noise(rng, n, fs, psd):
    """Gaussian noise with one-sided PSD shape psd(f) (FFT shaping, random phases)."""
    f = np.fft.rfftfreq(n, 1 / fs)
    amp = np.sqrt(np.maximum(psd(f), 0.0))
    spec = amp * (rng.standard_normal(len(f)) + 1j * rng.standard_normal(len(f)))
    spec[0] = 0
    x = np.fft.irfft(spec, n)
    return x / np.std(x)


def draw_spectrum(rng, fs):
    kind = str(rng.choice(["shaker-0.5-20", "shaker-1-40", "road", "helicopter"]))
    sp = {"kind": kind}
    if kind.startswith("shaker"):
        lo, hi = (0.5, 20.0) if kind == "shaker-0.5-20" else (1.0, 40.0)
        sp.update(lo=lo, hi=hi, ripple_db=rng.uniform(0.5, 2.0), ripple_hz=rng.uniform(3, 9),
                  ripple_phase=rng.uniform(0, 2 * np.pi))
    elif kind == "road":
        sp.update(f_body=rng.uniform(1.0, 1.8), z_body=rng.uniform(0.25, 0.4), f_wheel=rng.uniform(9, 13),
                  z_wheel=rng.uniform(0.2, 0.35))
    else:
        f1 = rng.uniform(12, 24)
        sp.update(n_rev_hz=f1, blades=int(rng.choice([2, 4])), line_share=rng.uniform(0.5, 0.8),
                  harmonics=[h for h in (1, 2, 3) if h * f1 < 0.35 * fs], wander=rng.uniform(0.002, 0.01))
    return sp


def _spectrum_of(kind, rng, fs):
    """A spectrum of the given kind (controlled experiments only)."""
    for _ in range(200):
        sp = draw_spectrum(rng, fs)
        if sp["kind"] == kind:
            return sp
    raise SystemExit("no spectrum of kind %s" % kind)


def base_signal(rng, sp, n, fs):
    if sp["kind"] == "em":
        return em_signal(rng, sp, n, fs)
    if sp["kind"].startswith("shaker"):
        lo, hi = sp["lo"], sp["hi"]

        def psd(f):
            band = 1 / (1 + (lo / np.maximum(f, 1e-9)) ** 8) / (1 + (f / hi) ** 8)
            ripple = 10 ** (sp["ripple_db"] * np.sin(2 * np.pi * f / sp["ripple_hz"] + sp["ripple_phase"]) / 10)
            return band * ripple
        return shaped_noise(rng, n, fs, psd)
    if sp["kind"] == "road":
        ws, wu = 2 * np.pi * sp["f_body"], 2 * np.pi * sp["f_wheel"]
        ms, mu = 1.0, 0.12
        ks, cs = ms * ws ** 2, 2 * sp["z_body"] * ms * ws
        kt = mu * wu ** 2 - ks
        cu = 2 * sp["z_wheel"] * mu * wu

        def psd(f):
            w = 2 * np.pi * np.maximum(f, 1e-6)
            s = 1j * w
            # quarter car: sprung floor acceleration per unit road displacement
            M = np.array([[ms * s ** 2 + cs * s + ks, -(cs * s + ks)],
                          [-(cs * s + ks), mu * s ** 2 + (cs + cu) * s + ks + kt]])
            det = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
            xs = (cs * s + ks) * (kt + cu * s) / det
            road = 1 / np.maximum(f, 0.3) ** 2  # ISO 8608 displacement PSD ~ n^-2 at constant speed
            hp = 1 / (1 + (0.3 / np.maximum(f, 1e-9)) ** 4)
            return np.abs(s ** 2 * xs) ** 2 * road * hp
        return shaped_noise(rng, n, fs, psd)
    # helicopter: rotor lines (N/rev and harmonics, with slow speed wander) on broadband
    t = np.arange(n) / fs
    broad = shaped_noise(rng, n, fs, lambda f: 1 / (1 + (0.7 / np.maximum(f, 1e-9)) ** 4) / (1 + (f / 80) ** 4))
    wander = 1 + sp["wander"] * shaped_noise(rng, n, fs, lambda f: 1 / (1 + (f / 0.05) ** 2))
    phase = 2 * np.pi * np.cumsum(sp["n_rev_hz"] * wander) / fs
    lines = np.zeros(n)
    for h in sp["harmonics"]:
        lines += (1.0 / h) * np.sin(h * phase + rng.uniform(0, 2 * np.pi))
    lines += 0.3 * np.sin(phase / sp["blades"] + rng.uniform(0, 2 * np.pi))  # 1/rev
    lines /= np.std(lines)
    return np.sqrt(sp["line_share"]) * lines + np.sqrt(1 - sp["line_share"]) * broad


def sensor_filter(x, fs, p):
    """One channel's sensor effect on the fine grid."""
    if "delay_s" in p:
        n = len(x)
        f = np.fft.rfftfreq(n, 1 / fs)
        return np.fft.irfft(np.fft.rfft(x) * np.exp(-2j * np.pi * f * p["delay_s"]), n)
    if "gain" in p:
        return x * p["gain"]
    if "design" in p:
        # analog prototype (scipy.signal) to second-order sections by the bilinear transform, as a
        # DAQ's IIR filter runs (sections: a 0.3 Hz corner at kHz rates is ill-conditioned as one
        # polynomial)
        hp = p["form"] == "highpass-multi"
        wc, n = 2 * np.pi * p["f_hz"], p["order"]
        if p["design"] == "rc":
            # n identical first-order RC stages, each at f_hz
            z, pl, k = ([0.0] * n, [-wc] * n, 1.0) if hp else ([], [-wc] * n, wc ** n)
        elif p["design"] == "bessel":
            z, pl, k = signal.bessel(n, wc, "highpass" if hp else "lowpass", analog=True,
                                     norm="mag", output="zpk")
        else:
            z, pl, k = signal.butter(n, wc, "highpass" if hp else "lowpass", analog=True, output="zpk")
        zd, pd, kd = signal.bilinear_zpk(np.asarray(z, float), np.asarray(pl, complex), k, fs)
        return signal.sosfilt(signal.zpk2sos(zd, pd, kd), x)
    wn = 2 * np.pi * p["f_hz"]
    z = p["zeta"]
    if "mount" == p.get("form"):
        b, a = [2 * z * wn, wn ** 2], [1, 2 * z * wn, wn ** 2]  # base-excited mount: (2 z wn s + wn^2) / (...)
    else:
        b, a = [wn ** 2], [1, 2 * z * wn, wn ** 2]  # 2-pole low-pass
    bd, ad = signal.bilinear(b, a, fs)
    return signal.lfilter(bd, ad, x)


def pink(rng, n, fs):
    return shaped_noise(rng, n, fs, lambda f: 1 / np.maximum(f, 0.05))


def daq(channels, m, fs):
    """Same causal 6-pole Butterworth anti-alias filter (0.4 fs) on every channel, then every m-th sample."""
    sos = signal.butter(6, 0.4 * fs, fs=fs * m, output="sos")
    return {k: signal.sosfilt(sos, v)[::m] for k, v in channels.items()}


def peak(f, H, lo=0.8, hi=30.0):
    sel = (f >= lo) & (f <= hi)
    i = np.argmax(np.abs(H[sel]))
    return float(np.abs(H[sel][i])), float(f[sel][i])
# ----------------------------------------------------------------------------------------------
# The suspension seat (--model seed001-full): suspension friction and end-stops in forms that are
# not wbv's candidates (wbv: F_c·tanh(v/0.01 m/s) statistically linearised; a linear stop of free
# stiffness, 0.1–30·k_s, beyond ±gap), plus the other families on that seat.
# ----------------------------------------------------------------------------------------------
S1_FAMILIES = {
    "suspension": ["stick-slip", "dahl", "bump-cubic", "bump-exp"],
    "viscoelastic": ["sls", "maxwell2", "fractional"],
    "stiffening": ["cubic", "exponential"],
    "softening": ["tanh", "bilinear", "magnitude-saturating"],
    "support-path": ["backrest", "thigh-path", "hands-wheel"],
    "missing-dof": ["viscera"],  # wbv's seat-frame candidate needs a cushion on the base
    "sensor": ["delay", "mount", "lowpass", "gain"],
}


def draw_family_s1(rng):
    """Half of the cases a suspension effect, ~20 % none, the rest the other families."""
    u = rng.uniform()
    if u < 0.2:
        return "none", "none"
    if u < 0.7:
        return "suspension", str(rng.choice(S1_FAMILIES["suspension"]))
    family = str(rng.choice([f for f in S1_FAMILIES if f != "suspension"]))
    return family, str(rng.choice(S1_FAMILIES[family]))


def draw_suspension(rng, form, strength):
    """Suspension effect parameters. Friction: a seat suspension's 20-150 N (scissor and guide
    friction), with a viscous part added to the damper. Stops: the paper's suspension is 250 kN/m with
    a 12 Hz, ζ≈0.02 frame mode, so its stroke at 1-2 m/s² is ~1 mm r.m.s., not the ±30-60 mm of a soft
    1.5 Hz ISO 7096 suspension; the free travel is placed at 1.3-2.3 stroke r.m.s. of the highest run
    (linear twin), so the stops are hit in the high run, seldom in the check run, never in the low run."""
    if form in ("stick-slip", "dahl"):
        p = {"f_c_n": min(300.0, rng.uniform(20, 150) * strength), "c_viscous_ns_m": rng.uniform(0, 300)}
        if form == "stick-slip":
            p["f_s_over_f_c"] = rng.uniform(1.1, 1.5)  # breakaway (static) over kinetic friction
        else:
            p["presliding_m"] = rng.uniform(2e-5, 1e-4)  # Dahl: F_c / sigma_0, the bristle's elastic range
        return p
    return {"gap_over_sigma_high": max(0.6, rng.uniform(1.3, 2.3) / strength),
            "k_b_over_k_s": rng.uniform(1.0, 4.0),
            "p0_over_gap": rng.uniform(0.3, 1.0),  # progression length of the rubber
            "restitution": rng.uniform(0.4, 0.8),
            "sides": str(rng.choice(["both", "bottom"]))}


class StickSlip:
    """Coulomb friction with stiction on the suspension, exact switching at the sample instants
    (implicit time stepping, Moreau/Stewart): with the force r held over the step, v(k+1) = v_free +
    g_v·r. Stuck: the force that makes v(k+1) = 0 if it is within ±F_s (±F_c when sliding), else the
    bound; so the seat locks exactly while the spring and inertia forces stay below breakaway."""

    def __init__(self, f_c, f_s):
        self.f_c, self.f_s, self.stuck = f_c, f_s, True

    def step(self, e, v, e_next, v_next, ge, gv):
        lim = self.f_s if self.stuck else self.f_c
        r = -v_next / gv
        self.stuck = abs(r) <= lim
        return float(np.clip(r, -lim, lim))


class Dahl:
    """Dahl bristle friction: dF/de = σ0 (1 − F/F_c·sgn ė), integrated exactly over each step's
    deflection increment, F(k+1) = s F_c + (F(k) − s F_c)·exp(−σ0|Δe|/F_c); presliding is elastic
    (σ0), so the seat is not locked but stiffened at low magnitude, and slides as F → ±F_c."""

    def __init__(self, f_c, sigma0):
        self.f_c, self.s0, self.F = f_c, sigma0, 0.0

    def step(self, e, v, e_next, v_next, ge, gv):
        r = -self.F
        de = e_next + ge * r - e
        if de != 0.0:
            sg = math.copysign(1.0, de)
            self.F = sg * self.f_c + (self.F - sg * self.f_c) * math.exp(-self.s0 * abs(de) / self.f_c)
        return r


class BumpStop:
    """Progressive rubber bump stop beyond the free travel ±gap (or the bottom one only), with
    Hunt–Crossley contact damping: F = F_el(p)·(1 + α ṗ) ≥ 0, p the penetration; cubic
    F_el = k_b p (1 + (p/p0)²) or exponential F_el = k_b p0 (e^(p/p0) − 1). α = 3(1 − e)/(2 v_c)
    from a restitution e at the contact speed v_c."""

    def __init__(self, gap, k_b, p0, alpha, sides, law):
        self.gap, self.k_b, self.p0, self.alpha, self.sides, self.law = gap, k_b, p0, alpha, sides, law
        self.max_tangent = 0.0

    def force(self, p, pd):
        if self.law == "cubic":
            fe, kt = self.k_b * p * (1 + (p / self.p0) ** 2), self.k_b * (1 + 3 * (p / self.p0) ** 2)
        else:
            x = min(p / self.p0, 30.0)
            fe, kt = self.k_b * self.p0 * math.expm1(x), self.k_b * math.exp(x)
        self.max_tangent = max(self.max_tangent, kt)
        return max(0.0, fe * (1 + self.alpha * pd))

    def at(self, e, v):
        if e < -self.gap:  # bottom (compression of the suspension): pushes the seat up
            return self.force(-e - self.gap, -v)
        if e > self.gap and self.sides == "both":
            return -self.force(e - self.gap, v)
        return 0.0

    def step(self, e, v, e_next, v_next, ge, gv):
        # the force held over the step is taken at the step's midpoint (predicted with the force at
        # its start): an explicit force held from the start pumps energy into every impact
        r0 = self.at(e, v)
        return self.at(e + 0.5 * (e_next + ge * r0 - e), v + 0.5 * (v_next + gv * r0 - v))


def build_suspension(subject, form, p, sigma):
    masses, links = dict(subject[0]), dict(subject[1])
    i, j, k, c = links["suspension"]
    if form in ("stick-slip", "dahl"):
        links["suspension"] = (i, j, k, c + p["c_viscous_ns_m"])
        law = StickSlip(p["f_c_n"], p["f_c_n"] * p["f_s_over_f_c"]) if form == "stick-slip" else \
            Dahl(p["f_c_n"], p["f_c_n"] / p["presliding_m"])
    else:
        gap = p["gap_over_sigma_high"] * sigma["susp_high"]
        alpha = 3 * (1 - p["restitution"]) / (2 * max(sigma["susp_rate_high"], 1e-6))
        law = BumpStop(gap, p["k_b_over_k_s"] * k, p["p0_over_gap"] * gap, alpha, p["sides"], form[5:])
        p.update(gap_m=gap, k_b_n_m=p["k_b_over_k_s"] * k, alpha_s_m=alpha)
    return Plant(masses, links, (), (i, j, law))


def draw_spectrum_s1(rng, fs):
    """The reference spectra or (35 %) an ISO 7096-like earth-moving-machinery input: a resonant
    band peaking at 2-4 Hz (not the standard's tabulated EM classes)."""
    if rng.uniform() < 0.35:
        return {"kind": "em", "f_peak": rng.uniform(2.0, 4.0), "zeta": rng.uniform(0.2, 0.4),
                "f_hp": rng.uniform(0.5, 1.0)}
    return draw_spectrum(rng, fs)


def em_signal(rng, sp, n, fs):
    def psd(f):
        r = np.maximum(f, 1e-9) / sp["f_peak"]
        res = 1 / np.abs(1 - r ** 2 + 2j * sp["zeta"] * r) ** 2
        return res / (1 + (sp["f_hp"] / np.maximum(f, 1e-9)) ** 8) / (1 + (f / (4 * sp["f_peak"])) ** 4)
    return shaped_noise(rng, n, fs, psd)


def susp_law_check():
    """Closed forms for the suspension laws through simulate() on one mass on a spring (45 kg,
    250 kN/m, no damper), kicked by a 20 ms half-sine base pulse and then free: Coulomb friction (the
    stick-slip law with F_s = F_c) loses exactly 2 F_c/k of amplitude per half cycle and comes to rest
    inside ±F_c/k; with an undamped (e = 1) cubic bump stop the energy ½mv² + ½kx² measured inside the
    free travel fixes the turning point x_m by ½k x_m² + k_b (p²/2 + p⁴/(4 p0²)) = E, p = x_m − gap."""
    m, k, fc = 45.0, 250000.0, 100.0
    h = 1 / 8192.0
    n = int(1.5 / h)
    t = np.arange(n) * h
    u = np.where(t < 0.02, 40.0 * np.sin(np.pi * t / 0.02), 0.0)
    free = t > 0.03

    def run(law):
        pl = Plant({"seat_frame": m}, {"suspension": ("seat_frame", None, k, 0.0)}, (), ("seat_frame", None, law))
        out = {"x": ("lin", pl.deflection_row("seat_frame", None), 0.0),
               "v": ("lin", pl.rate_row("seat_frame", None), 0.0)}
        y = simulate(pl, u, h, out)
        return y["x"][free], y["v"][free]

    x, v = run(StickSlip(fc, fc))
    turns = [x[q] for q in range(1, len(x) - 1) if (x[q] - x[q - 1]) * (x[q + 1] - x[q]) < 0]
    drops = np.abs(np.diff(np.abs(turns)))[:5]
    print("stick-slip: amplitude drop per half cycle %s mm (closed form 2 F_c/k = %.4f mm); at rest %.4f mm "
          "(|x| <= F_c/k = %.4f mm)" % (np.round(1e3 * drops, 4).tolist(), 2e3 * fc / k, 1e3 * x[-1], 1e3 * fc / k))
    gap, kb, p0 = 0.001, 1e6, 0.0005
    x, v = run(BumpStop(gap, kb, p0, 0.0, "both", "cubic"))
    q = int(np.argmax(np.abs(x) < 0.5 * gap))
    E = 0.5 * m * v[q] ** 2 + 0.5 * k * x[q] ** 2
    xm = optimize.brentq(lambda z: 0.5 * k * z ** 2 + kb * ((z - gap) ** 2 / 2 + (z - gap) ** 4 / (4 * p0 ** 2)) - E,
                         gap, 0.1)
    q2 = q + int(np.argmax(np.abs(x[q:]) > gap))  # the next contact, its turning point
    q3 = q2 + int(np.argmax(np.abs(x[q2:]) < gap))
    print("bump stop (cubic, e = 1): turning point %.5f mm, closed form %.5f mm (free travel %.1f mm); "
          "after 1.4 s %.5f mm" % (1e3 * np.max(np.abs(x[q2:q3])), 1e3 * xm, 1e3 * gap, 1e3 * np.max(np.abs(x[-2000:]))))


# ----------------------------------------------------------------------------------------------
# One case
# ----------------------------------------------------------------------------------------------
RATES = (256, 500, 512, 1000, 1024, 2000)
DAQ_NAMES = {"a_base_z": ["CH1 Floor Z", "Base Acc Z", "Acc Z base", "Plattform Z"],
             "a_seat_z": ["CH2 Seat pad Z", "SAE pad Az", "Acc Z seat", "Sitz Z"],
             "a_head_z": ["CH3 Bite bar Z", "Head Az", "Acc Z head", "Kopf Z"],
             "f_seat_z": ["CH4 Force plate Fz", "Fz plate", "Force Z seat", "Kraft Z"],
             "f_back_z": ["CH5 Backrest Fz", "Fz back", "Force Z backrest", "Kraft Z Lehne"]}


def outputs_for(plant, force, back=False):
    out = {"a_seat_z": ("acc", "cushion"), "a_head_z": ("acc", "head"),
           "defl_cushion": ("lin", plant.deflection_row("cushion", plant.links["cushion"][1]), 0.0),
           "defl_k4": ("lin", plant.deflection_row("pelvis", "cushion"), 0.0),
           "defl_torso": ("lin", plant.deflection_row("upper_torso", None), 0.0),
           "defl_pelvis": ("lin", plant.deflection_row("pelvis", None), 0.0),
           "defl_head": ("lin", plant.deflection_row("head", None), 0.0)}
    if force:
        _, _, k4, c4 = plant.links["k4"]
        row = -k4 * plant.deflection_row("pelvis", "cushion") - c4 * plant.rate_row("pelvis", "cushion")
        # the seat-pan force carries a nonlinear law on the pelvis-cushion link, not a lap belt's
        on_k4 = plant.nonlinear is not None and plant.nonlinear[:2] == ("pelvis", "cushion")
        out["f_seat_z"] = ("lin", row, 1.0 if on_k4 else 0.0)
    if back and "extra" in plant.links and plant.links["extra"][0] == "upper_torso":
        # an instrumented backrest: the vertical force of the back link on the upper torso, up positive
        node, _, kb, cb = plant.links["extra"]
        out["f_back_z"] = ("lin", -kb * plant.deflection_row(node, None) - cb * plant.rate_row(node, None), 0.0)
    if "suspension" in plant.links:  # suspension stroke and its rate (seed001-full)
        out["defl_susp"] = ("lin", plant.deflection_row("seat_frame", None), 0.0)
        out["defl_susp_rate"] = ("lin", plant.rate_row("seat_frame", None), 0.0)
    return out


def welch_paths(y, fs):
    nper = int(8 * fs)
    f, Pbb = signal.welch(y["a_base_z"], fs, nperseg=nper)
    _, Pbs = signal.csd(y["a_base_z"], y["a_seat_z"], fs, nperseg=nper)
    _, Pss = signal.welch(y["a_seat_z"], fs, nperseg=nper)
    _, Psh = signal.csd(y["a_seat_z"], y["a_head_z"], fs, nperseg=nper)
    return f, Pbs / Pbb, Psh / Pss, Pbb


def detectability(twins, effs, fs):
    """Own figure: over runs and the two paths (base->seat, seat->head) the largest of the change of the
    transmissibility peak (% of magnitude, % of frequency) and the 90th percentile over the excited
    bins in 1-30 Hz of |H_effect - H_twin| / |H_twin|, noise-free; the twin is the same subject and
    input without the effect."""
    best = {"peak_mag_pct": 0.0, "peak_freq_pct": 0.0, "p90_complex_pct": 0.0}
    for tw, ef in zip(twins, effs):
        f, H0s, H0h, Pbb = welch_paths(tw, fs)
        _, H1s, H1h, _ = welch_paths(ef, fs)
        exc = (f >= 1) & (f <= 30) & (Pbb > 1e-3 * Pbb[(f >= 0.5) & (f <= 40)].max())
        for H0, H1 in ((H0s, H1s), (H0h, H1h)):
            m0, f0 = peak(f, H0)
            m1, f1 = peak(f, H1)
            best["peak_mag_pct"] = max(best["peak_mag_pct"], 100 * abs(m1 / m0 - 1))
            best["peak_freq_pct"] = max(best["peak_freq_pct"], 100 * abs(f1 / f0 - 1))
            if exc.any():
                best["p90_complex_pct"] = max(best["p90_complex_pct"],
                                              float(100 * np.percentile(np.abs(H1[exc] - H0[exc]) / np.abs(H0[exc]), 90)))
    best["detect_pct"] = max(best.values())
    return best


def between_run_detectability(effs, fs, order):
    """Magnitude-scheduled effect: change of the peaks between the lowest and highest run."""
    lo, hi = order[0], order[-1]
    f, Hls, Hlh, _ = welch_paths(effs[lo], fs)
    _, Hhs, Hhh, _ = welch_paths(effs[hi], fs)
    d = {"peak_mag_pct": 0.0, "peak_freq_pct": 0.0}
    for Hl, Hh in ((Hls, Hhs), (Hlh, Hhh)):
        ml, fl = peak(f, Hl)
        mh, fh = peak(f, Hh)
        d["peak_mag_pct"] = max(d["peak_mag_pct"], 100 * abs(mh / ml - 1))
        d["peak_freq_pct"] = max(d["peak_freq_pct"], 100 * abs(fh / fl - 1))
    d["detect_pct"] = max(d.values())
    return d


def draw_field(seed, index, family, force):
    """Field conditions (--field), drawn from streams of their own so that the lab draws of a case
    stay as they were: two data loggers (half the sensor cases become a trigger offset of 1-10 ms or
    a clock drift of 20-200 ppm on the occupant's logger: seat, head and, in 70 % of rigs, the force
    plate); logger faults on a quarter of the cases (dropouts holding the last value, or a spike
    train); the rig's wiring stated with --logger in half of the cases; and on half of the cases a
    field logger's MEMS base accelerometer: a white noise floor of 2-6 % of the base's r.m.s. on top
    of the lab noise (the base's motion falls under it where its spectrum falls)."""
    r = np.random.default_rng([seed, index, 11])
    out = {}
    if family == "sensor" and r.uniform() < 0.5:
        form = "logger-offset" if r.uniform() < 0.5 else "logger-drift"
        sign = float(r.choice([-1.0, 1.0]))
        force_late = force and bool(r.uniform() < 0.7)
        late = ["a_seat_z", "a_head_z"] + (["f_seat_z"] if force_late else [])
        if form == "logger-offset":
            off, drift = sign * r.uniform(0.001, 0.01), 0.0
        else:
            off, drift = r.uniform(-0.003, 0.003), sign * r.uniform(20e-6, 200e-6)
        out["logger"] = {"form": form, "channels": late, "offset_s": float(off), "drift": float(drift)}
    else:
        late = ["a_seat_z", "a_head_z"] + (["f_seat_z"] if force else [])
    f = np.random.default_rng([seed, index, 12])
    if f.uniform() < 0.25:
        out["fault"] = str(f.choice(["dropouts", "spikes"]))
    st = np.random.default_rng([seed, index, 13])
    if st.uniform() < 0.5:
        on_base = ["a_base_z"] + (["f_seat_z"] if force and "f_seat_z" not in late else [])
        out["stated"] = ["--logger", "rig:" + ",".join(on_base), "--logger", "occupant:" + ",".join(late)]
    fl = np.random.default_rng([seed, index, 15])
    if fl.uniform() < 0.5:
        out["base_floor"] = float(fl.uniform(0.02, 0.06))
    return out


def clock_filter(x, fs, offset_s, drift):
    """A second logger's timing on the fine grid: the value at t is the signal at t - (offset + drift t)
    (linear interpolation on the >= 4 kHz grid; zero before the start)."""
    t = np.arange(len(x)) / fs
    return np.interp(t - (offset_s + drift * t), t, x, left=0.0)


def plant_fault(chans, fs, kind, r):
    """Logger faults at the output rate: dropouts (the logger repeats its last value for 0.05-0.5 s,
    one to four times, on every channel but the base) or a spike train (one sample off by 10-50 x the
    channel's r.m.s. every 1-10 s on one occupant channel)."""
    names = [c for c in chans if c != "a_base_z"]
    n = len(chans["a_base_z"])
    if kind == "dropouts":
        for _ in range(int(r.integers(1, 5))):
            ln = int(r.uniform(0.05, 0.5) * fs)
            at = int(r.integers(0, n - ln - 1))
            for c in names:
                chans[c][at:at + ln] = chans[c][at]
    else:
        c = names[int(r.integers(len(names)))]
        sd = float(np.std(chans[c]))
        every = r.uniform(1.0, 10.0) * fs
        t = r.uniform() * every
        while t < n:
            chans[c][int(t)] += float(r.choice([-1, 1])) * r.uniform(10, 50) * sd
            t += every * r.uniform(0.5, 1.5)


def make_case(case_dir, seed, index, override=None, model="reference"):
    """One case. `override` (controlled experiments): keys fs_hz, spectrum (kind), force_plate, base_dc
    replace the drawn nuisance after the draws; `params`/`strength` reuse a truth.json's effect."""
    override = override or {}
    rng = np.random.default_rng([seed, index])
    fs = int(rng.choice(RATES))
    fs = int(override.get("fs_hz", fs))
    m = max(2, math.ceil(4000 / fs))
    ffs = fs * m
    subject = draw_subject(rng, model)
    if model != "reference":
        family, form = draw_family_s1(rng)
    elif rng.uniform() < 0.25:
        family, form = "none", "none"
    else:
        family = str(rng.choice(list(FAMILIES)))
        form = str(rng.choice(FAMILIES[family]))
    if "family" in override:
        # study sets (--family/--form): the same draws as a random case, then the effect is forced,
        # so every nuisance of case i is the one a random case i would have had
        family = override["family"]
        form = "none" if family == "none" else (
            override.get("form") or str(np.random.default_rng([seed, index, 5]).choice(FAMILIES[family])))
    mags = [(0.25, 1.0, 0.5), (0.4, 1.6, 0.8)][int(rng.integers(2))]
    if override and override.get("magnitudes"):
        mags = tuple(override["magnitudes"])
    elif override and override.get("extrapolate"):
        # a check run at a magnitude the training runs do not bracket (its own stream, so every
        # other draw stays the random case's): case i % 3 == 0 at 1.5-2x the high run, 1 at
        # 0.5-0.7x the low run, 2 inside, about the training runs' geometric mean
        xr = np.random.default_rng([seed, index, 31])
        lo, hi = mags[0], mags[1]
        mags = (lo, hi, [hi * xr.uniform(1.5, 2.0), lo * xr.uniform(0.5, 0.7),
                         math.sqrt(lo * hi) * xr.uniform(0.8, 1.25)][index % 3])
    T = rng.uniform(60, 180)
    durs = [max(60.0, round(T * rng.uniform(0.97, 1.03), 2)) for _ in mags]
    spectrum = draw_spectrum(rng, fs) if model == "reference" else draw_spectrum_s1(rng, fs)
    if "spectrum" in override and override["spectrum"] != spectrum["kind"]:
        spectrum = _spectrum_of(override["spectrum"], np.random.default_rng([seed, index, 7]), fs)
    force = bool(rng.uniform() < 0.4)
    force = bool(override.get("force_plate", force))
    force_static = bool(rng.uniform() < 0.5)
    noise = {ch: float(rng.uniform(0.005, 0.03)) for ch in ("a_base_z", "a_seat_z", "a_head_z", "f_seat_z")}
    # an instrumented backrest (--backrest-force) on backrest cases; its noise from its own stream
    back = bool(override.get("backrest_force")) and form == "backrest"
    if back:
        noise["f_back_z"] = float(np.random.default_rng([seed, index, 21]).uniform(0.005, 0.03))
    field = draw_field(seed, index, family, force) if override.get("field") else None
    if field and field.get("logger") and "params" in override:
        # --like on a field case: its own logger timing, and the wiring stated to match it (a
        # force plate the experiment adds is on the base's logger unless the case retimed one).
        field["logger"] = dict(override["params"])
        if "stated" in field and not override.get("stated", True):
            del field["stated"]
        if "stated" in field:
            late = [c for c in field["logger"]["channels"] if force or c != "f_seat_z"]
            on_base = ["a_base_z"] + (["f_seat_z"] if force and "f_seat_z" not in late else [])
            field["stated"] = ["--logger", "rig:" + ",".join(on_base), "--logger", "occupant:" + ",".join(late)]
    if field and field.get("logger"):
        form = field["logger"]["form"]
    offsets = {}
    for ch in ("a_base_z", "a_seat_z", "a_head_z"):
        u = rng.uniform()
        offsets[ch] = G if u < 0.25 else (float(rng.uniform(-0.1, 0.1)) if u < 0.45 else 0.0)
    if "base_dc" in override:
        offsets["a_base_z"] = float(override["base_dc"])
    pre = int(2.0 * ffs)
    bases = []
    for (A, T_i) in zip(mags, durs):
        n = int(round(T_i * fs)) * m + pre
        bases.append(A * base_signal(rng, spectrum, n, ffs))
    # linear twins: same subject and inputs, no effect (also give the deflection scales)
    twin_plant = Plant(*subject)
    twins_fine = [simulate(twin_plant, u, 1 / ffs, outputs_for(twin_plant, force)) for u in bases]
    sigma = {"cushion": float(np.std(twins_fine[1]["defl_cushion"][pre:])),
             "k4": float(np.std(twins_fine[1]["defl_k4"][pre:])),
             "torso": float(np.std(twins_fine[1]["defl_torso"][pre:])),
             "pelvis": float(np.std(twins_fine[1]["defl_pelvis"][pre:])),
             "head": float(np.std(twins_fine[1]["defl_head"][pre:]))}
    if model != "reference":
        sigma["susp_high"] = float(np.std(twins_fine[1]["defl_susp"][pre:]))
        sigma["susp_rate_high"] = float(np.std(twins_fine[1]["defl_susp_rate"][pre:]))
    strength = 1.0
    if field and field.get("logger"):
        params = dict(field["logger"])
    else:
        params = draw_effect(rng, family, form, strength) if family != "none" else {}
    if "params" in override:
        params, strength = override["params"], override["strength"]
    noise_rng = np.random.default_rng([seed, index, 99])
    for attempt in range(3):
        effs_fine = []
        for (A, u) in zip(mags, bases):
            if family in ("none", "sensor"):
                effs_fine.append(None)
                continue
            plant = build_plant(subject, family, form, params, A, sigma)
            effs_fine.append(simulate(plant, u, 1 / ffs, outputs_for(plant, force, back)))
        runs_clean, twins_out = [], []
        for (u, tw, ef) in zip(bases, twins_fine, effs_fine):
            ch = {"a_base_z": u, **{k: v for k, v in (ef or tw).items() if not k.startswith("defl")}}
            if family == "sensor" and "drift" in params:
                for c in params["channels"]:
                    if c in ch:
                        ch[c] = clock_filter(ch[c], ffs, params["offset_s"], params["drift"])
            elif family == "sensor":
                ch[params["channel"]] = sensor_filter(ch[params["channel"]], ffs, dict(params, form=form))
            twin_ch = {"a_base_z": u, **{k: v for k, v in tw.items() if not k.startswith("defl")}}
            runs_clean.append({k: v[pre // m:] for k, v in daq(ch, m, fs).items()})
            twins_out.append({k: v[pre // m:] for k, v in daq(twin_ch, m, fs).items()})
        if family == "none":
            det = {"detect_pct": 0.0}
            break
        if form in ("magnitude-saturating", "magnitude-stiffening"):
            det = between_run_detectability(runs_clean, fs, [0, 2, 1])
        else:
            det = detectability(twins_out, runs_clean, fs)
        if det["detect_pct"] >= 3.0 or attempt == 2 or "params" in override or "drift" in params:
            break
        strength *= 2.0
        params = draw_effect(rng, family, form, strength)
    # sensors, offsets, force plate static weight, noise
    body_w = G * sum(v for k, v in subject[0].items() if k != "cushion")
    layout = draw_layout(rng, force, back)
    files = []
    # --coarse-logger: one channel on a coarse converter whose step is fixed by its range, so the
    # quietest run (the first) spans only `codes` codes; the others use more.
    coarse = override.get("coarse")
    coarse_step = None
    for r, (y, T_i) in enumerate(zip(runs_clean, durs)):
        chans = {}
        for ch, v in y.items():
            if ch != "a_base_z" and ch not in ("a_seat_z", "a_head_z", "f_seat_z", "f_back_z"):
                continue
            sd = float(np.std(v))
            v = v + noise[ch] * sd * noise_rng.standard_normal(len(v)) + noise[ch] / 3 * sd * pink(noise_rng, len(v), fs)
            if ch == "a_base_z" and field and field.get("base_floor"):
                floor_rng = np.random.default_rng([seed, index, 16, r])
                v = v + field["base_floor"] * sd * floor_rng.standard_normal(len(v))
            if ch in offsets:
                v = v + offsets[ch]
            if ch == "f_seat_z" and force_static:
                v = v + body_w
            chans[ch] = v
        if field and field.get("fault"):
            plant_fault(chans, fs, field["fault"], np.random.default_rng([seed, index, 14, r]))
        if coarse and coarse[0] in chans:
            v = chans[coarse[0]]
            if coarse_step is None:
                coarse_step = float(np.ptp(v)) / coarse[1]
            chans[coarse[0]] = np.round(v / coarse_step) * coarse_step
        name = ["run-low", "run-high", "check-mid"][r] + ".csv"
        write_csv(os.path.join(case_dir, name), chans, fs, layout)
        files.append(name)
    truth = {"model": model, "case": index, "seed": seed, "family": family, "form": form, "params": params,
             "strength_scale": strength, "detectability": det, "twin_sigma_high_run": sigma,
             "subject": {"masses_kg": subject[0], "links": {k: {"k": v[2], "c": v[3]} for k, v in subject[1].items()}},
             "nuisances": {"fs_hz": fs, "fine_rate_hz": ffs, "spectrum": spectrum, "magnitudes_ms2": list(mags),
                           "durations_s": durs, "force_plate": force, "backrest_force": back,
                           "force_static_weight": force and force_static, "noise_frac": noise,
                           "dc_offsets_ms2": offsets, "layout": layout, "field": field,
                           "coarse_logger": coarse and {"channel": coarse[0], "codes_first_run": coarse[1],
                                                        "step": coarse_step}},
             "runs": files, "run_order": "run-low, run-high are --run; check-mid is --check"}
    with open(os.path.join(case_dir, "truth.json"), "w") as fh:
        json.dump(truth, fh, indent=1, default=float)
    cmd = ["--run", files[0], "--run", files[1], "--check", files[2]] + layout["options"]
    if field and field.get("stated"):
        cmd += field["stated"]
    with open(os.path.join(case_dir, "cmd.json"), "w") as fh:
        json.dump(cmd, fh)
    return truth


def draw_layout(rng, force, back=False):
    chans = ["a_base_z", "a_seat_z", "a_head_z"] + (["f_seat_z"] if force else []) + (["f_back_z"] if back else [])
    daq_names = bool(rng.uniform() < 0.5)
    u = rng.uniform()
    units = "ms2" if u < 0.6 else ("g-option" if u < 0.85 or not daq_names else "g-header")
    t = rng.uniform()
    time = "t_s" if t < 0.6 else ("Time" if t < 0.75 else "none")
    semicolon = bool(rng.uniform() < 0.15)
    vari = int(rng.integers(4))
    headers, options = {}, []
    for ch in chans:
        h = DAQ_NAMES[ch][vari] if daq_names else ch
        if daq_names:
            options += ["--column", "%s=%s" % (ch, h)]
        if units == "g-header" and ch.startswith("a_"):
            h += " [g]"
        elif units == "g-header":
            h += " [N]"
        headers[ch] = h
        if units == "g-option" and ch.startswith("a_"):
            options += ["--units", "%s=g" % ch]
    order = list(chans)
    rng.shuffle(order)
    layout = {"daq_names": daq_names, "units": units, "time": time, "semicolon": semicolon,
              "order": order, "headers": headers, "options": options}
    return layout


def write_csv(path, chans, fs, layout):
    n = min(len(v) for v in chans.values())
    cols, heads, fmts = [], [], []
    if layout["time"] != "none":
        cols.append(np.arange(n) / fs)
        heads.append("t_s" if layout["time"] == "t_s" else "Time [s]")
        fmts.append("%.6f")
    for ch in layout["order"]:
        v = chans[ch][:n]
        if layout["units"] != "ms2" and ch.startswith("a_"):
            v = v / G
        cols.append(v)
        heads.append(layout["headers"][ch])
        fmts.append("%.7g")
    delim = ";" if layout["semicolon"] else ","
    data = np.column_stack(cols)
    import io
    buf = io.StringIO()
    np.savetxt(buf, data, fmt=fmts, delimiter=delim)
    body = buf.getvalue()
    if layout["semicolon"]:
        body = body.replace(".", ",")
    tmp = path + ".tmp"
    with open(tmp, "w") as fh:
        fh.write(delim.join(heads) + "\n")
        fh.write(body)
    os.replace(tmp, path)
    if layout["time"] == "none":
        pass  # the rate goes on the command line (--fs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outdir")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=40)
    ap.add_argument("--first", type=int, default=0)
    ap.add_argument("--force", action="store_true", help="replace existing case directories")
    ap.add_argument("--like", help="controlled experiment: a case's truth.json whose effect is reused")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="with --like: fs_hz=N, spectrum=KIND, force_plate=0|1, base_dc=M/S2, "
                         "stated=0 (a field case's wiring not stated)")
    ap.add_argument("--family", choices=sorted(FAMILIES) + ["none"],
                    help="study set: every case gets this effect family (none: no effect)")
    ap.add_argument("--form", help="study set: every case gets this form (implies its family)")
    ap.add_argument("--backrest-force", action="store_true",
                    help="backrest cases also measure the backrest's vertical force f_back_z")
    ap.add_argument("--field", action="store_true",
                    help="vehicle field conditions: two data loggers, logger faults, --logger stated in half")
    ap.add_argument("--model", choices=sorted(MODELS), default="reference",
                    help="the seat: reference (5 DOF) or seed001-full (paper 001 body, cushion, suspension)")
    ap.add_argument("--coarse-logger", metavar="CH=CODES",
                    help="channel CH recorded by a coarse converter whose step makes the first (quietest) "
                         "run span CODES codes (e.g. a_head_z=10: an 8-bit logger on a quiet run)")
    ap.add_argument("--magnitudes", metavar="LOW,HIGH,CHECK",
                    help="base r.m.s. of the two training runs and the check run, m/s^2")
    ap.add_argument("--extrapolate", action="store_true",
                    help="check runs outside the training magnitudes: a third at 1.5-2x the high run, "
                         "a third at 0.5-0.7x the low run, a third inside")
    a = ap.parse_args()
    override = None
    if a.form:
        fam = [f for f, forms in list(FAMILIES.items()) + list(STUDY_FORMS.items()) if a.form in forms]
        if not fam or (a.family and a.family != fam[0]):
            ap.error("--form %s is not a form of %s" % (a.form, a.family or "any family"))
        a.family = fam[0]
    if a.family:
        override = {"family": a.family, "form": a.form if a.family != "none" else None}
    if a.like:
        with open(a.like) as fh:
            like = json.load(fh)
        # The case's own effect (a field case's logger form is drawn again by draw_field, which the
        # same seed and index repeat) and its conditions: a field case stays one.
        override = {"params": like["params"], "strength": like["strength_scale"]}
        if like["family"] != "none":
            override.update(family=like["family"], form=like["form"])
        if like["nuisances"].get("field") is not None:
            override["field"] = True
        for kv in a.set:
            k, v = kv.split("=", 1)
            override[k] = v if k == "spectrum" else (
                bool(int(v)) if k in ("force_plate", "stated", "backrest_force") else float(v))
        a.seed, a.first, a.cases = like["seed"], like["case"], 1
        a.model = like.get("model", "reference")
    if a.field:
        override = dict(override or {}, field=True)
    if a.coarse_logger:
        ch, codes = a.coarse_logger.split("=", 1)
        override = dict(override or {}, coarse=(ch, float(codes)))
    if a.backrest_force:
        override = dict(override or {}, backrest_force=True)
    if a.magnitudes:
        override = dict(override or {}, magnitudes=[float(x) for x in a.magnitudes.split(",")])
    if a.extrapolate:
        override = dict(override or {}, extrapolate=True)
    os.makedirs(a.outdir, exist_ok=True)
    for i in range(a.first, a.first + a.cases):
        d = os.path.join(a.outdir, "case-%03d" % i)
        if os.path.exists(os.path.join(d, "truth.json")) and not a.force:
            continue
        os.makedirs(d, exist_ok=True)
        tr = make_case(d, a.seed, i, override, a.model)
        if override and a.like:
            tr["override"] = {k: v for k, v in override.items()
                              if k not in ("params", "strength", "family", "form", "field")}
            with open(os.path.join(d, "truth.json"), "w") as fh:
                json.dump(tr, fh, indent=1, default=float)
        if tr["nuisances"]["layout"]["time"] == "none":
            with open(os.path.join(d, "cmd.json")) as fh:
                cmd = json.load(fh)
            with open(os.path.join(d, "cmd.json"), "w") as fh:
                json.dump(cmd + ["--fs", str(tr["nuisances"]["fs_hz"])], fh)
        print("case %03d: %-12s %-20s fs %4d Hz %-14s detect %.1f %%" % (
            i, tr["family"], tr["form"], tr["nuisances"]["fs_hz"], tr["nuisances"]["spectrum"]["kind"],
            tr["detectability"]["detect_pct"]), flush=True)


if __name__ == "__main__" and len(sys.argv) > 1 and sys.argv[1] == "--check-frf":
    check_model = sys.argv[3] if sys.argv[2:3] == ["--model"] else "reference"
    frf_check(check_model)
    if check_model != "reference":
        susp_law_check()
    sys.exit(0)

if __name__ == "__main__":
    main()
