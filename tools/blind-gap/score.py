#!/usr/bin/env python3
"""Runs `wbv gap` on the blind cases written by gen.py and scores the verdicts against truth.json.

Usage: score.py exec CASEDIR [--wbv PATH]  (default $WBV or target/release/wbv)     (per case: gap.json, gap.stderr, gap.rc, gap.wall_s)
       score.py score CASEDIR --out results.json      (Markdown table on stdout)

truth.json is read only here, after wbv has run; wbv never sees it.
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import time

# verdict / candidate id -> family of the truth catalogue (tools/blind-gap/README.md)
FAMILY = {
    "body-softening": "softening", "body-softening-magnitude": "softening",
    "cushion-stiffening": "stiffening", "cushion-contact": "stiffening",
    "cushion-bottoming": "stiffening", "cushion-power-foam": "stiffening",
    "cushion-viscoelastic": "viscoelastic",
    "sensor-delay": "sensor", "sensor-lowpass": "sensor", "sensor-gain": "sensor",
    "sensor-highpass": "sensor", "sensor-force": "sensor", "sensor-mount-force": "sensor",
    "sensor-mount-seat": "sensor", "sensor-mount-head": "sensor", "sensor-mount-base": "sensor",
    "sensor-lowpass-base": "sensor",
    "logger-offset": "sensor", "logger-drift": "sensor",
    "missing-dof": "missing-dof", "body-mode": "missing-dof", "frame-side-mode": "missing-dof",
    "backrest": "support-path", "hands-support": "support-path", "feet-support": "support-path", "thigh-support": "support-path", "harness": "support-path", "lap-belt": "support-path", "head-restraint": "support-path", "feet-lift-off": "support-path", "cushion-fractional": "viscoelastic", "cushion-havriliak-negami": "viscoelastic",
    "suspension-friction": "suspension", "end-stop": "suspension",
    "none": "none", "unexplained": "unexplained", "not-identifiable": "not-identifiable",
}


def fam(cid):
    return FAMILY.get(cid, "?" + str(cid))


def cases(root):
    return sorted(d for d in glob.glob(os.path.join(root, "case-*")) if os.path.isdir(d))


def run_exec(root, wbv, model="reference"):
    for d in cases(root):
        if os.path.exists(os.path.join(d, "gap.rc")):
            continue
        with open(os.path.join(d, "cmd.json")) as fh:
            cmd = json.load(fh)
        argv = ["nice", "-n", "10", wbv, "gap", "--model", model] + cmd + ["--json"]
        t0 = time.monotonic()
        p = subprocess.run(argv, cwd=d, capture_output=True, text=True)
        wall = time.monotonic() - t0
        for name, text in (("gap.json", p.stdout), ("gap.stderr", p.stderr), ("gap.rc", str(p.returncode)),
                           ("gap.wall_s", "%.2f" % wall), ("gap.argv", json.dumps(argv))):
            with open(os.path.join(d, name), "w") as fh:
                fh.write(text)
        print("%s rc %d %.1f s" % (os.path.basename(d), p.returncode, wall), flush=True)


def top_candidates(rep, n=3):
    """Best n by ΔBIC on the check run, each with its ΔBIC over all runs (`delta_bic_all`)."""
    cs = [c for c in rep.get("candidates", []) if c.get("delta_bic") is not None]
    cs.sort(key=lambda c: c["delta_bic"])
    return [(c["id"], c["delta_bic"], c.get("fraction_closed"), c.get("delta_bic_all")) for c in cs[:n]]


def best_all_runs(rep):
    cs = [c for c in rep.get("candidates", []) if c.get("delta_bic_all") is not None]
    if not cs:
        return None
    c = min(cs, key=lambda c: c["delta_bic_all"])
    return (c["id"], c["delta_bic"], c.get("fraction_closed"), c["delta_bic_all"])


def tier(det, family="x"):
    if family == "none":
        return "n/a (no effect)"
    return "<3 %" if det < 3 else ("3-10 %" if det < 10 else ">10 %")


def load(root):
    rows = []
    for d in cases(root):
        with open(os.path.join(d, "truth.json")) as fh:
            tr = json.load(fh)
        r = {"case": os.path.basename(d), "truth": tr}
        rc_path = os.path.join(d, "gap.rc")
        if not os.path.exists(rc_path):
            continue
        r["rc"] = int(open(rc_path).read().strip() or -1)
        r["stderr"] = open(os.path.join(d, "gap.stderr")).read()
        r["wall_s"] = float(open(os.path.join(d, "gap.wall_s")).read())
        rep = None
        if r["rc"] == 0:
            try:
                rep = json.load(open(os.path.join(d, "gap.json")))
            except json.JSONDecodeError as e:
                r["rc"] = -2
                r["stderr"] += "\n(score.py: stdout is not JSON: %s)" % e
        r["report"] = rep
        rows.append(r)
    return rows


def judge(r):
    tr = r["truth"]
    truth_fam = tr["family"]
    out = {"case": r["case"], "truth_family": truth_fam, "form": tr["form"], "rc": r["rc"],
           "detect_pct": tr["detectability"]["detect_pct"], "wall_s": r["wall_s"]}
    if r["rc"] != 0 or r["report"] is None:
        out.update(verdict="error", verdict_family="error", right=False, top2=False,
                   error=r["stderr"].strip().splitlines()[-1] if r["stderr"].strip() else "exit %d" % r["rc"])
        return out
    rep = r["report"]
    v = rep.get("verdict")
    vf = fam(v)
    named = rep.get("named") or []
    top = top_candidates(rep)
    top_fams = []
    for c in top:
        f = fam(c[0])
        if f not in top_fams:
            top_fams.append(f)
    out.update(verdict=v, verdict_family=vf, named=named, named_families=[fam(x) for x in named],
               right=(vf == truth_fam), top=top, best_all=best_all_runs(rep),
               null_at_bound=[p["name"] for p in (rep.get("null") or {}).get("params", []) if p.get("at_bound")],
               base_rms=[r.get("base_rms") for r in rep.get("runs", [])],
               in_named=(truth_fam in [fam(x) for x in named]) or (vf == truth_fam),
               top2=(vf == truth_fam) or (truth_fam != "none" and truth_fam in top_fams[:2]
                                          and vf not in ("none",)),
               warnings=rep.get("warnings", []), verdict_text=rep.get("verdict_text", ""),
               separating=rep.get("separating_measurement"))
    return out


def nuisance_keys(tr):
    nu = tr["nuisances"]
    off = nu["dc_offsets_ms2"]
    dc = "gravity (+1 g) on a channel" if any(abs(v - 9.80665) < 1e-6 for v in off.values()) else (
        "small offset" if any(v != 0 for v in off.values()) else "none")
    dmin = min(nu["durations_s"])
    dur = "60-100 s" if dmin < 100 else ("100-140 s" if dmin < 140 else "140-185 s")
    fp = "no" if not nu["force_plate"] else ("yes, static weight in" if nu["force_static_weight"] else "yes, weight removed")
    lay = nu["layout"]
    return {
        "spectrum": nu["spectrum"]["kind"],
        "rate": "%d Hz" % nu["fs_hz"],
        "force plate": fp,
        "DC offset": dc,
        "duration": dur,
        "magnitudes": "/".join("%g" % m for m in nu["magnitudes_ms2"]),
        "units": lay["units"],
        "time column": lay["time"],
        "delimiter": "; + decimal comma" if lay["semicolon"] else ",",
        "detectability": tier(tr["detectability"]["detect_pct"], tr["family"]),
    }


def frac(k, n):
    return "%d/%d (%.0f %%)" % (k, n, 100.0 * k / n) if n else "-"


def confusion(judged):
    """Planted family against named verdict (the first named effect, or none/unexplained/...), and
    each named candidate's false naming: the share of the cases whose planted family is not the
    candidate's in which it was named anyway."""
    ok = [j for j in judged if j["verdict"] != "error"]
    fams = sorted({j["truth_family"] for j in ok})
    named = sorted({j["verdict"] for j in ok})
    lines = ["Confusion: planted family (rows) against the named verdict (columns); last column each "
             "verdict's false naming where its family was not planted:", ""]
    lines.append("| planted \\ named | " + " | ".join(named) + " |")
    lines.append("|---" * (len(named) + 1) + "|")
    for f in fams:
        row = [sum(1 for j in ok if j["truth_family"] == f and j["verdict"] == v) for v in named]
        lines.append("| %s | " % f + " | ".join(str(x) if x else "" for x in row) + " |")
    lines.append("")
    lines.append("| named | family | named where not planted | rate |")
    lines.append("|---|---|---|---|")
    for v in named:
        vf = fam(v)
        if vf in ("none", "unexplained", "not-identifiable"):
            continue
        elsewhere = [j for j in ok if j["truth_family"] != vf]
        wrong = sum(1 for j in elsewhere if j["verdict"] == v)
        lines.append("| %s | %s | %d / %d | %.3f |" % (v, vf, wrong, len(elsewhere),
                                                    wrong / len(elsewhere) if elsewhere else 0.0))
    lines.append("")
    return lines


def markdown(rows, judged, seed):
    lines = []
    n = len(judged)
    right = sum(j["right"] for j in judged)
    errs = sum(j["verdict"] == "error" for j in judged)
    nulls = [j for j in judged if j["truth_family"] == "none"]
    fp = [j for j in nulls if j["verdict"] not in ("none", "error")]
    eff = [j for j in judged if j["truth_family"] != "none"]
    eff_det = [j for j in eff if j["detect_pct"] >= 3]
    walls = sorted(j["wall_s"] for j in judged)
    lines.append("Blind lab-condition cases (tools/blind-gap, seed %s): %d cases, %d without an effect; "
                 "median `wbv gap` wall time %.1f s." % (seed, n, len(nulls), walls[len(walls) // 2] if walls else 0))
    lines.append("")
    lines.append("| measure | value |")
    lines.append("| --- | --- |")
    lines.append("| verdict family right (all cases) | %s |" % frac(right, n))
    lines.append("| effect cases: top-1 right | %s |" % frac(sum(j["right"] for j in eff), len(eff)))
    lines.append("| effect cases with detectability >= 3 %%: top-1 right | %s |"
                 % frac(sum(j["right"] for j in eff_det), len(eff_det)))
    lines.append("| effect cases: truth family in top-2 candidate families | %s |" % frac(sum(j["top2"] for j in eff), len(eff)))
    lines.append("| effect cases: truth family among the named effects (first or second) | %s |"
                 % frac(sum(j.get("in_named", False) for j in eff), len(eff)))
    lines.append("| `none` cases: false positives (verdict not `none`) | %s |" % frac(len(fp), len(nulls)))
    lines.append("| errors (non-zero exit) | %s |" % frac(errs, n))
    lines.append("")
    lines.append("Per truth family (verdict family right; verdicts given):")
    lines.append("")
    lines.append("| truth family | right | verdicts |")
    lines.append("| --- | --- | --- |")
    fams = sorted(set(j["truth_family"] for j in judged))
    for f in fams:
        js = [j for j in judged if j["truth_family"] == f]
        vs = {}
        for j in js:
            vs[j["verdict"]] = vs.get(j["verdict"], 0) + 1
        lines.append("| %s | %s | %s |" % (f, frac(sum(j["right"] for j in js), len(js)),
                                           ", ".join("%s x%d" % kv for kv in sorted(vs.items()))))
    lines.append("")
    lines.append("Per truth form:")
    lines.append("")
    lines.append("| family / form | right | detectability (own figure, %) |")
    lines.append("| --- | --- | --- |")
    forms = sorted(set((j["truth_family"], j["form"]) for j in judged))
    for (f, fo) in forms:
        js = [j for j in judged if j["truth_family"] == f and j["form"] == fo]
        lines.append("| %s / %s | %s | %s |" % (f, fo, frac(sum(j["right"] for j in js), len(js)),
                                               ", ".join("%.0f" % j["detect_pct"] for j in js)))
    lines.append("")
    lines.append("Per nuisance (all cases; verdict right / errors):")
    lines.append("")
    lines.append("| nuisance | value | right | errors |")
    lines.append("| --- | --- | --- | --- |")
    bykey = {}
    for r, j in zip(rows, judged):
        for k, v in nuisance_keys(r["truth"]).items():
            bykey.setdefault(k, {}).setdefault(v, []).append(j)
    for k in bykey:
        for v in sorted(bykey[k]):
            js = bykey[k][v]
            lines.append("| %s | %s | %s | %d |" % (k, v, frac(sum(j["right"] for j in js), len(js)),
                                                    sum(j["verdict"] == "error" for j in js)))
    lines.append("")
    lines.append("Wrong cases:")
    lines.append("")
    for r, j in zip(rows, judged):
        if j["right"]:
            continue
        tr = r["truth"]
        nu = tr["nuisances"]
        params = json.dumps(tr["params"], default=str)
        lines.append("- **%s** truth %s/%s %s (detect %.1f %%); %s, %d Hz, %s, runs %s s at %s m/s2, force plate %s, "
                     "DC %s, layout units=%s time=%s%s" % (
                         j["case"], j["truth_family"], j["form"], params, j["detect_pct"],
                         nu["spectrum"]["kind"], nu["fs_hz"],
                         "noise " + "/".join("%.1f" % (100 * v) for v in nu["noise_frac"].values()) + " %",
                         "/".join("%.0f" % d for d in nu["durations_s"]),
                         "/".join("%g" % m for m in nu["magnitudes_ms2"]),
                         nuisance_keys(tr)["force plate"], nuisance_keys(tr)["DC offset"],
                         nu["layout"]["units"], nu["layout"]["time"],
                         " ;-CSV" if nu["layout"]["semicolon"] else ""))
        if j["verdict"] == "error":
            lines.append("  - ERROR (exit %d): `%s`" % (j["rc"], j["error"]))
            continue
        lines.append("  - verdict `%s`: %s" % (j["verdict"], j["verdict_text"]))
        lines.append("  - top (check-run ΔBIC; all-run ΔBIC): " + ", ".join(
            "%s %.0f (closes %.0f %%; all %.0f)" % (c, b, 100 * (fc or 0), ba or 0) for c, b, fc, ba in j["top"]))
        ba = j.get("best_all")
        if ba and ba[0] not in [c[0] for c in j["top"]]:
            lines.append("  - best over all runs: %s all-run ΔBIC %.0f (check ΔBIC %.0f)" % (ba[0], ba[3], ba[1]))
        if j.get("null_at_bound"):
            lines.append("  - null re-fit at its ±30 %% bound: %s" % ", ".join(j["null_at_bound"]))
        lines.append("  - base r.m.s. seen by wbv (m/s2): %s" % "/".join("%.3g" % x for x in j["base_rms"]))
        if j.get("separating"):
            lines.append("  - separating measurement: %s" % j["separating"])
        if j["warnings"]:
            lines.append("  - warnings: " + " | ".join(str(w) for w in j["warnings"]))
    lines.append("")
    lines.extend(confusion(judged))
    lines.append("Per case (top 3 by check-run ΔBIC):")
    lines.append("")
    lines.append("| case | truth | detect % | spectrum | verdict | top 3 (ΔBIC) |")
    lines.append("| --- | --- | --- | --- | --- | --- |")
    for r, j in zip(rows, judged):
        lines.append("| %s | %s/%s | %.0f | %s | %s%s | %s |" % (
            j["case"][5:], j["truth_family"], j["form"], j["detect_pct"], r["truth"]["nuisances"]["spectrum"]["kind"],
            j["verdict"], "" if j["right"] else " ✗",
            ", ".join("%s %.0f" % (c, b) for c, b, _, _ in j.get("top", []))))
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest="cmd", required=True)
    e = sub.add_parser("exec")
    e.add_argument("root")
    e.add_argument("--model", default="reference", help="the model the cases were generated for (gen.py --model)")
    e.add_argument("--wbv", default=os.environ.get("WBV", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "target", "release", "wbv")))
    s = sub.add_parser("score")
    s.add_argument("root")
    s.add_argument("--out", required=True)
    s.add_argument("--seed", default="?")
    a = ap.parse_args()
    if a.cmd == "exec":
        run_exec(a.root, a.wbv, a.model)
        return
    rows = load(a.root)
    judged = [judge(r) for r in rows]
    md = markdown(rows, judged, a.seed)
    print(md)
    tmp = a.out + ".tmp"
    with open(tmp, "w") as fh:
        json.dump({"seed": a.seed, "cases": judged, "markdown": md}, fh, indent=1, default=str)
    os.replace(tmp, a.out)


if __name__ == "__main__":
    sys.exit(main())
