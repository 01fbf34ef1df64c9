#!/usr/bin/env python3
"""Extrapolation bench for `wbv gap --write-model` (issue 73): on blind cases whose check run lies
outside the training magnitudes (gen.py --extrapolate or --magnitudes), how close does each model
come to the check run's measured ISO 2631-1 figures?

For every case directory (gen.py's files, diagnosed with `wbv gap ... --write-model model.toml
--json > gap.json`, e.g. by `tools/blind-gap/run` with WRITE_MODEL=1):
  (a) the nominal model and (b) the linear re-fit: the seat a_w and SEAT gaps the diagnosis reports
      for them (its spectral figures: model and measurement from the same Welch spectra);
  (c) the written model: `wbv simulate --model model.toml --excitation recorded --input CHECK`
      with the check run's measured base acceleration, seat and head a_w and SEAT from the
      simulated run against `wbv analyze CHECK` (both time-domain ISO 2631-1 figures).
Prints one row per case and the shares the issue's acceptance counts; writes extrapolation.json
beside the cases. Usage: extrapolation.py WBV CASE_DIR...
"""
import json
import os
import subprocess
import sys


def run_json(cmd, cwd):
    out = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(cmd[:3]), out.stderr.strip()[-400:]))
    return json.loads(out.stdout)


def input_options(cmd):
    """The case's reader options (--column/--units/--fs/...) from its cmd.json arguments."""
    opts, i = [], 0
    while i < len(cmd):
        if cmd[i] in ("--run", "--check"):
            i += 2
            continue
        opts.append(cmd[i])
        i += 1
    return opts


def figure(doc, channel, key):
    """A channel's figure from an analyze/simulate --json document."""
    for ch in doc["channels"]:
        if ch["name"] == channel:
            return ch[key]
    raise KeyError(channel)


def seat_value(doc):
    """SEAT, % (ISO 2631-1 Annex E seat effective amplitude transmissibility)."""
    return doc["seat_percent"]


def case_row(wbv, case):
    cmd = json.load(open(os.path.join(case, "cmd.json")))
    truth = json.load(open(os.path.join(case, "truth.json")))
    gap = json.load(open(os.path.join(case, "gap.json")))
    check = cmd[cmd.index("--check") + 1]
    opts = input_options(cmd)
    mags = truth["nuisances"]["magnitudes_ms2"]
    where = "above" if mags[2] > mags[1] else "below" if mags[2] < mags[0] else "inside"
    # A DC-coupled base accelerometer records gravity: `wbv simulate --excitation recorded` then
    # drives the model with a 1 g step at its start, whose ringing inflates the run's a_w (an open
    # defect, issue 73's note). Such cases are flagged and left out of the shares below.
    dc = abs(truth["nuisances"].get("dc_offsets_ms2", {}).get("a_base_z", 0.0)) > 1.0
    row = {"case": os.path.basename(case), "family": truth["family"], "form": truth.get("form"),
           "magnitudes": mags, "check": where, "verdict": gap["verdict"],
           "named": gap.get("named", []), "base_dc": dc}
    for stage, key in (("nominal", "a"), ("null", "b")):
        w = (gap[stage]["check"] if stage == "null" else gap[stage])["weighted"]
        row[key + "_aw_seat_pct"] = w["aw_gap_percent"]
        row[key + "_seat_pts"] = w["seat_model"] - w["seat_meas"]
    meas = run_json([wbv, "analyze", check, *opts, "--json"], case)
    model = os.path.join(case, "model.toml")
    # The integrator's step no coarser than the record's (a coarser one would alias it).
    dt = min(1e-3, 1.0 / truth["nuisances"]["fs_hz"])
    sim = run_json([wbv, "simulate", "--model", model, "--excitation", "recorded",
                    "--input", check, *opts, "--dt", repr(dt), "--no-record", "--json"],
                   case)["analysis"]
    for ch in ("a_seat_z", "a_head_z"):
        m, s = figure(meas, ch, "a_w"), figure(sim, ch, "a_w")
        row["c_aw_%s_pct" % ch[2:6]] = 100.0 * (s / m - 1.0)
    row["c_seat_pts"] = seat_value(sim) - seat_value(meas)
    return row


def main():
    wbv, cases = sys.argv[1], sys.argv[2:]
    rows = []
    for case in cases:
        try:
            rows.append(case_row(wbv, case))
        except Exception as e:  # a case that cannot be scored is reported, not skipped silently
            rows.append({"case": os.path.basename(case), "error": str(e)})
    print("| case | family/form | check | verdict | a: a_w % / SEAT | b: a_w % / SEAT | c: a_w seat % / head % / SEAT |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        if "error" in r:
            print("| %s | error: %s |||||" % (r["case"], r["error"]))
            continue
        print("| %s | %s/%s | %s %s | %s | %+.1f / %+.1f | %+.1f / %+.1f | %+.1f / %+.1f / %+.1f%s |" % (
            r["case"], r["family"], r["form"], r["check"], r["magnitudes"], r["verdict"],
            r["a_aw_seat_pct"], r["a_seat_pts"], r["b_aw_seat_pct"], r["b_seat_pts"],
            r["c_aw_seat_pct"], r["c_aw_head_pct"], r["c_seat_pts"],
            " (base with 1 g: left out)" if r["base_dc"] else ""))
    ok = [r for r in rows if "error" not in r and not r["base_dc"]]
    within = [r for r in ok if abs(r["c_aw_seat_pct"]) <= 2 and abs(r["c_seat_pts"]) <= 2]
    off = [r for r in ok if abs(r["b_aw_seat_pct"]) > 1]
    closer = [r for r in off if abs(r["c_aw_seat_pct"]) < abs(r["b_aw_seat_pct"])]
    print("\nwritten model within 2 %% a_w and 2 SEAT points: %d/%d; closer than the linear re-fit where "
          "the re-fit is > 1 %% off: %d/%d; left out (base with 1 g) or errors: %d" % (len(within), len(ok), len(closer), len(off),
                                                       len(rows) - len(ok)))
    out = os.path.join(os.path.dirname(os.path.abspath(cases[0])), "extrapolation.json") if cases else None
    if out:
        json.dump(rows, open(out, "w"), indent=1)


if __name__ == "__main__":
    main()
