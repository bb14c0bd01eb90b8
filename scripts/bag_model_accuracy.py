#!/usr/bin/env python3
"""The auto brush model along a recorded bag against a converged transient reference.

Runs bag_analyze on the bag: the transient model at --reference-resolution (the reference) and at half of it
(how far the reference itself is from convergence), then the auto model at each target. For each target it
reports, against the reference, the largest error max(|dF_x|, |dF_y|, |dM_z| / a) / (mu F_z) and its 99th
percentile, how many estimates are over the target and how many of those carry the accuracy flag, how many
have an error above their error estimate plus the reference's, and the share of estimates in each model.

Auto runs with auto_noise_fraction 0 (the plain target: "after"), and, when --noise-fraction is given (the package's
default is 0.25), a second time below the noise ("below_noise"): its target then rises to that fraction of the forces'
spread carried from the bag's twist covariance, each message's target in the CSV's brush_accuracy_target, and the
error is checked against it. Both runs are timed (the fastest of three replays).

The other parameters are the package's config/contact_estimator.yaml (bag_analyze's default) unless --params
names another file (--before-params for the earlier release's run). The output is the JSON that benchmark_report.py --bag reads; with --before it also
carries the numbers of an earlier release, measured by this script with that release's bag_analyze:

  bag_model_accuracy.py --bag-analyze OLD/bag_analyze --reference-bag-analyze NEW/bag_analyze \
      --params OLD_SOURCE/config/contact_estimator.yaml --reference-params config/contact_estimator.yaml \
      --label before --out before.json

Usage: bag_model_accuracy.py --bag-analyze PATH [--bag data/demo.bag] [--targets 0.05 0.01] [--before JSON]
                             [--out JSON]
"""
import argparse
import csv
import time
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = {"1": "linear", "2": "steady", "3": "transient"}


def environment(tool):
    """The tool's own libraries first: a workspace sourced for another build would otherwise lend it its
    libraries through LD_LIBRARY_PATH (catkin links with RUNPATH, which LD_LIBRARY_PATH overrides)."""
    env = dict(os.environ)
    lib = os.path.dirname(os.path.dirname(os.path.abspath(tool)))  # <devel>/lib/<package>/bag_analyze
    if os.path.basename(lib) == "lib":
        env["LD_LIBRARY_PATH"] = lib + (":" + env["LD_LIBRARY_PATH"] if env.get("LD_LIBRARY_PATH") else "")
    return env


def run(bag_analyze, bag, csv_path, model, settings, params):
    cmd = [bag_analyze, "--input", bag, "--csv", csv_path, "--brush-model", model, "--estimates-only",
           "--progress", "never"]
    if params:
        cmd += ["--params", params]
    if settings:
        cmd += ["--set"] + ["%s=%s" % kv for kv in settings.items()]
    with tempfile.TemporaryDirectory() as tmp:
        # bag_analyze writes a bag unless only the CSV is asked for; keep it out of the way
        cmd += ["--output", os.path.join(tmp, "out.bag")]
        done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                              env=environment(bag_analyze))
    if done.returncode != 0:
        sys.exit("bag_model_accuracy: %s failed:\n%s" % (" ".join(cmd), done.stderr))
    with open(csv_path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def error(row, ref):
    """max(|dF_x|, |dF_y|, |dM_z| / a) / (mu F_z), the unit of accuracy_target."""
    limit = float(ref["friction"]) * float(ref["load"])
    if limit <= 0.0:
        return 0.0
    a = float(ref["patch_radius"])
    return max(abs(float(row["brush_fx"]) - float(ref["brush_fx"])),
               abs(float(row["brush_fy"]) - float(ref["brush_fy"])),
               abs(float(row["brush_mz"]) - float(ref["brush_mz"])) / a) / limit


def percentile(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(q * len(s)))]


def timed_run(*args):
    """run() three times: its rows and the fastest wall time [s]."""
    best, rows = None, None
    for _ in range(3):
        start = time.time()
        rows = run(*args)
        elapsed = time.time() - start
        best = elapsed if best is None else min(best, elapsed)
    return rows, best


def summary(rows, ref, target):
    if len(rows) != len(ref):
        sys.exit("bag_model_accuracy: %d estimates against %d of the reference" % (len(rows), len(ref)))
    errors = [error(r, q) for r, q in zip(rows, ref)]
    worst = max(range(len(errors)), key=lambda i: errors[i])
    counts = {name: 0 for name in MODELS.values()}
    for r in rows:
        name = MODELS.get(r["brush_model_used"])
        if name:
            counts[name] += 1
    out = {name: counts[name] / len(rows) for name in MODELS.values()}
    out.update({"max_error": errors[worst], "p99_error": percentile(errors, 0.99),
                "worst_at_t": float(rows[worst]["t"]) - float(rows[0]["t"]),
                "worst_rolling_speed": float(rows[worst]["rolling_speed"]),
                "over_target": sum(1 for e in errors if e > target)})
    if "brush_accuracy_target" in rows[0]:
        # below the noise: each message against the target it was computed to (plus the reference's own distance)
        targets = [float(r["brush_accuracy_target"]) for r in rows]
        out["over_own_target"] = sum(1 for e, t in zip(errors, targets) if e > t)
        out["largest_target"] = max(targets)
        out["largest_error_over_own_target"] = max(e / t for e, t in zip(errors, targets) if t > 0)
    if "brush_error_estimate" in rows[0]:
        est = [float(r["brush_error_estimate"]) for r in rows]
        ref_est = [float(q["brush_error_estimate"]) for q in ref]
        out["over_target_flagged"] = sum(1 for e, x in zip(errors, est) if e > target and x > target)
        out["estimate_short"] = sum(1 for e, x, y in zip(errors, est, ref_est) if e > x + y)
        out["worst_estimate"] = est[worst]
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bag-analyze", required=True, help="the bag_analyze to measure")
    ap.add_argument("--bag", default=os.path.join(HERE, "..", "data", "demo.bag"))
    ap.add_argument("--params", help="parameter file (default: bag_analyze's, the package's config)")
    ap.add_argument("--targets", type=float, nargs="+", default=[0.05, 0.01])
    ap.add_argument("--reference-resolution", type=int, default=128)
    ap.add_argument("--reference-csv", help="the reference's CSV: read it if it exists, else write it there")
    ap.add_argument("--reference-bag-analyze", help="bag_analyze for the reference (default: --bag-analyze)")
    ap.add_argument("--reference-params", help="parameter file for the reference (default: --params)")
    ap.add_argument("--before", help="JSON of an earlier release written by this script with --label before")
    ap.add_argument("--label", default="after", choices=["before", "after"])
    ap.add_argument("--provenance", default="", help="free text stored with the numbers (release, command)")
    ap.add_argument("--noise-fraction", type=float, help="also run auto below the noise with this auto_noise_fraction")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()

    with tempfile.TemporaryDirectory() as tmp:
        reference_tool = args.reference_bag_analyze or args.bag_analyze
        reference_params = args.reference_params or args.params
        ref_csv = args.reference_csv or os.path.join(tmp, "reference.csv")
        n = args.reference_resolution
        if os.path.exists(ref_csv):
            with open(ref_csv) as f:
                ref = list(csv.DictReader(line for line in f if not line.startswith("#")))
        else:
            # (the transient model is bound by the work budget: the references have no budget to speak of)
            ref = run(reference_tool, args.bag, ref_csv, "transient", {"resolution": n, "work_budget": 1000000000},
                      reference_params)
        half = run(reference_tool, args.bag, os.path.join(tmp, "half.csv"), "transient",
                   {"resolution": n // 2, "work_budget": 1000000000}, reference_params)
        half_errors = [error(r, q) for r, q in zip(half, ref)]
        targets = []
        for t in args.targets:
            settings = {"accuracy_target": t}
            if args.label == "after":
                settings["auto_noise_fraction"] = 0.0  # the plain target (an earlier release has no such parameter)
            rows, elapsed = timed_run(args.bag_analyze, args.bag, os.path.join(tmp, "auto.csv"), "auto", settings,
                                      args.params)
            entry = {"target": t, args.label: summary(rows, ref, t)}
            entry[args.label]["time"] = elapsed
            if args.noise_fraction is not None:
                rows, elapsed = timed_run(args.bag_analyze, args.bag, os.path.join(tmp, "noise.csv"), "auto",
                                          {"accuracy_target": t, "auto_noise_fraction": args.noise_fraction},
                                          args.params)
                entry["below_noise"] = summary(rows, ref, t)
                entry["below_noise"]["time"] = elapsed
                entry["below_noise"]["noise_fraction"] = args.noise_fraction
            targets.append(entry)

    if args.before:
        with open(args.before) as f:
            before = json.load(f)
        by_target = {e["target"]: e.get("before") for e in before["targets"]}
        for e in targets:
            if by_target.get(e["target"]) is not None:
                e["before"] = by_target[e["target"]]
    result = {
        "bag": os.path.basename(args.bag),
        "messages": len(ref),
        "reference": "transient model at resolution %d; at %d it differs by at most %.3g of mu F_z (p99 %.3g)"
                     % (n, n // 2, max(half_errors), percentile(half_errors, 0.99)),
        "reference_half_max_difference": max(half_errors),
        "targets": targets,
    }
    if args.provenance:
        result["provenance_" + args.label] = args.provenance
    if args.before and "provenance_before" in before:
        result["provenance_before"] = before["provenance_before"]
    with open(args.out, "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    for e in targets:
        for label in ("before", "after", "below_noise"):
            if label in e:
                s = e[label]
                print("target %g %-6s max error %.3g (p99 %.3g)  over target %d  linear %.0f%% steady %.0f%% "
                      "transient %.0f%%" % (e["target"], label, s["max_error"], s["p99_error"], s["over_target"],
                                             100 * s["linear"], 100 * s["steady"], 100 * s["transient"]))
    print(result["reference"])


if __name__ == "__main__":
    main()
