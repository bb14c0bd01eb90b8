#!/usr/bin/env python3
"""Every message of a recorded robot's stream: its cost and its error against a converged reference run.

For each bag (a manoeuvre recorded with demo.launch, e.g. data/manoeuvre.bag and its 1 kHz recording), bag_analyze runs
the package's default settings (config/contact_estimator.yaml: auto, the twist's covariance propagated, the work
budget) and, as the reference, the transient model at --reference-resolution with no work budget and, for the
reference's own error, at half that resolution. Per message: the compute time and the counted work, the model auto
used, whether the answer is flagged BRUSH_FLAG_ACCURACY_NOT_MET (and why: held by the work budget,
BRUSH_FLAG_BUDGET_LIMITED; substeps truncated; at standstill, where no finer lattice fills), and the error
max(|dF_x|, |dF_y|, |dM_z| / a) / (mu F_z) against the reference. An unflagged
message whose error is above its accuracy target by more than the reference's own difference is a failure of the
estimate; the summary counts them, and every estimate below its error. A stream's first messages, before the reference
describes the same contact as auto (warm_up: the history before the recording is unknown), are timed but not compared.
A second pass at accuracy_target 0.1 % (auto_noise_fraction 0) is summarised beside the default one. Grouped per
segment of the scenario (--scenario) and over the whole stream. A message's time is the fastest of three replays (which
must answer alike); bag_analyze's speed (the fastest of the three) against the bag's duration gives the times real
time.

Where an estimate is below its error beyond the reference's difference but within the reference's own estimate, the
reference cannot tell; --confirm-resolution N (stream_sweep.py: 256) then runs the transient model at N as well and
counts how many of those are still below their error against it, with its own estimate as the slack.

Usage: stream_benchmark.py --bag-analyze PATH --bags A.bag [B.bag ...] --scenario config/manoeuvre_scenario.yaml
                           [--params config/contact_estimator.yaml] [--reference-resolution 128]
                           [--confirm-resolution 0] [--out JSON]
"""
import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from bag_model_accuracy import environment, error  # noqa: E402  (the tool's own libraries first)

FLAG_SUBSTEPS_TRUNCATED, FLAG_ACCURACY_NOT_MET, FLAG_BUDGET_LIMITED = 8, 16, 64
STRICT = {"accuracy_target": 0.001, "auto_noise_fraction": 0.0}  # a second pass at 0.1 %, not raised to the noise
MODELS = {"0": "off", "1": "linear", "2": "steady", "3": "transient", "4": "auto"}


def run(tool, bag, csv_path, params, settings, brush_model=None):
    cmd = [tool, "--input", bag, "--csv", csv_path, "--estimates-only", "--progress", "never"]
    if params:
        cmd += ["--params", params]
    if brush_model:
        cmd += ["--brush-model", brush_model]
    if settings:
        cmd += ["--set"] + ["%s=%s" % kv for kv in settings.items()]
    with tempfile.TemporaryDirectory() as tmp:
        cmd += ["--output", os.path.join(tmp, "out.bag")]
        start = time.perf_counter()
        done = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True,
                              env=environment(tool))
        wall = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit("bag_analyze failed (%s):\n%s%s" % (" ".join(cmd), done.stdout, done.stderr))
    return wall


def warm_up(rows, path):
    """How many of a stream's first messages have no reference. The contact's history before the recording is unknown:
    the reference's lattice starts there undeformed, while auto, for a stream that starts rolling, starts in the steady
    state of its first inputs (BrushAuto::enterTransient's warm start; at standstill it also starts undeformed). They
    describe the same contact only once every bristle has entered the patch under the stream's inputs: the patch has
    rolled its longest path, a diameter. The first message is never compared (the reference has no step there)."""
    standstill = 0.05
    with open(path) as f:
        for line in f:
            if not line.startswith("#"):
                break
            m = re.search(r"\bstandstill_speed ([0-9.eE+-]+)", line)
            if m:
                standstill = float(m.group(1))
    if float(rows[0]["rolling_speed"]) <= standstill:
        return 1
    travel = 0.0
    for i in range(1, len(rows)):
        travel += 0.5 * (float(rows[i]["rolling_speed"]) + float(rows[i - 1]["rolling_speed"])) * (
            float(rows[i]["stamp"]) - float(rows[i - 1]["stamp"]))
        if travel >= 2.0 * float(rows[i]["patch_radius"]):
            return i + 1
    return len(rows)


def fastest(runs, bag):
    """One replay's rows with each message's compute time the fastest of the replays': a message's cost, not the
    machine's other tenants (a preempted message took 9-14 ms in one replay of a slow hour). The replays must answer
    alike, the work being counted, not timed."""
    rows = runs[0]
    for other in runs[1:]:
        if len(other) != len(rows):
            sys.exit("%s: the replays answered different numbers of messages" % bag)
        for r, o in zip(rows, other):
            for key in ("brush_fx", "brush_fy", "brush_mz", "brush_error_estimate", "brush_flags", "work"):
                if r[key] != o[key]:
                    sys.exit("%s: the replays differ at %s (%s: %s against %s)" % (bag, r["stamp"], key, r[key], o[key]))
            r["compute_time"] = str(min(float(r["compute_time"]), float(o["compute_time"])))
    return rows


def read(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def segments(path):
    """(name, start, end) of the scenario's segments, from its YAML"""
    import yaml
    with open(path) as f:
        s = yaml.safe_load(f)
    out, t = [], 0.0
    for seg in s["segments"]:
        d = float(seg.get("duration", 1.0))
        out.append((seg.get("name", "segment"), t, t + d))
        t += d
    return out


def quantile(v, q):
    if not v:
        return None
    v = sorted(v)
    pos = q * (len(v) - 1)
    i = int(math.floor(pos))
    j = min(i + 1, len(v) - 1)
    return v[i] + (v[j] - v[i]) * (pos - i)


# messages of at least this much counted work say what a unit costs (below, the fixed costs of a message dominate)
HEAVY_WORK = 20000


def described(r):
    """a message for the report: where in the stream, what answered it, its error and estimate"""
    return {"stamp": float(r["stamp"]), "t": r["_t"], "segment": r["_segment"],
            "model": MODELS.get(r["brush_model_used"], r["brush_model_used"]), "resolution": int(r["brush_resolution"]),
            "flags": int(r["brush_flags"]), "error": r["_error"], "estimate": float(r["brush_error_estimate"]),
            "reference_error": r["_reference_error"], "reference_bound": r["_reference_bound"]}


def summarise(rows):
    times = [1e6 * float(r["compute_time"]) for r in rows]
    works = [float(r["work"]) for r in rows]
    # the time a counted unit took [ns], over the heavy messages: the work budget's units are meant as about 10 ns
    per_unit = [1e3 * t / w for t, w in zip(times, works) if w >= HEAVY_WORK]
    flagged = [r for r in rows if int(r["brush_flags"]) & FLAG_ACCURACY_NOT_MET]
    truncated = sum(1 for r in rows if int(r["brush_flags"]) & FLAG_SUBSTEPS_TRUNCATED)
    # why the others were flagged: auto held by the budget (a larger one lets it refine), or at standstill (slips
    # undefined: no finer lattice fills until the robot rolls)
    held = sum(1 for r in flagged if int(r["brush_flags"]) & FLAG_BUDGET_LIMITED)
    standstill = sum(1 for r in flagged if not int(r["brush_flags"]) & (FLAG_BUDGET_LIMITED | FLAG_SUBSTEPS_TRUNCATED)
                     and r["slips_defined"] in ("0", "false", "False"))
    # the messages before the reference's warm-up is over are not compared (warm_up)
    compared = [r for r in rows if r["_error"] is not None]
    flagged_compared = [r for r in flagged if r["_error"] is not None]
    clean = [r for r in compared if not int(r["brush_flags"]) & FLAG_ACCURACY_NOT_MET]
    errors = [r["_error"] for r in clean]
    over = [r for r in clean if r["_error"] > float(r["brush_accuracy_target"]) + r["_reference_error"]]
    # every estimate, flagged or not, must bound its error (with the reference's own estimate beside it)
    short = [r for r in compared if r["_error"] > float(r["brush_error_estimate"]) + r["_reference_error"]]
    worst_short = max(short, key=lambda r: r["_error"] / max(float(r["brush_error_estimate"]) + r["_reference_error"],
                                                             1e-300), default=None)
    # the difference from half the resolution is not a bound on the reference's error: on the hostile stream at 30 Hz
    # the reference at 128 was further from 256 than from 64 at 12 of 181 messages (by up to 3.7e-5 of mu F_z); its own
    # error estimate is one (by the lattice's design; tested), so a miss beyond it is resolved by the reference
    resolved = [r for r in short if r["_error"] > float(r["brush_error_estimate"]) + r["_reference_bound"]]
    models = {}
    for r in rows:
        key = MODELS.get(r["brush_model_used"], r["brush_model_used"])
        if key == "transient":
            key += " %s" % r["brush_resolution"]
        models[key] = models.get(key, 0) + 1
    return {
        "messages": len(rows),
        "time_us": {"p50": quantile(times, 0.5), "p99": quantile(times, 0.99), "max": max(times) if times else None},
        "work": {"p50": quantile(works, 0.5), "p99": quantile(works, 0.99), "max": max(works) if works else None},
        "ns_per_unit": {"heavy_messages": len(per_unit), "p50": quantile(per_unit, 0.5),
                        "max": max(per_unit) if per_unit else None},
        "models": models,
        "flagged": len(flagged),
        "flagged_substeps_truncated": truncated,
        "flagged_budget_limited": held,
        "flagged_standstill": standstill,
        "flagged_error_max": max((r["_error"] for r in flagged_compared), default=None),
        "unflagged_error_max": max(errors) if errors else None,
        "unflagged_error_p99": quantile(errors, 0.99),
        "unflagged_over_target": len(over),
        "estimate_short": len(short),
        "estimate_short_resolved": len(resolved),
        # of those between the difference and the reference's estimate, how many were checked at --confirm-resolution
        # and how many of them were still below the error there
        "estimate_short_checked_finer": sum(1 for r in short if "_confirmed" in r),
        "estimate_short_confirmed_finer": sum(1 for r in short if r.get("_confirmed")),
        "estimate_short_worst": None if worst_short is None else described(worst_short),
        # every estimate below its error beyond the reference's own estimate, where and what
        "estimate_short_resolved_messages": [described(r) for r in resolved[:20]],
        "reference_error_max": max((r["_reference_error"] for r in compared), default=None),
        "target_median": quantile([float(r["brush_accuracy_target"]) for r in rows], 0.5),
    }


def ambiguous(r):
    """an estimate below its error beyond the reference's difference from half its resolution, not beyond its own
    estimate: the reference cannot tell (at seed 1136 of the sweep resolution 128's estimate hid estimates short by 2.1x
    against 256)"""
    return r["_error"] is not None and r["_error"] > float(r["brush_error_estimate"]) + r["_reference_error"] and \
        not r["_error"] > float(r["brush_error_estimate"]) + r["_reference_bound"]


def confirm(a, bag, tmp, name, rows, strict):
    """The ambiguous messages of both passes against the transient model at --confirm-resolution (its own estimate as
    the slack): _confirmed True where the estimate is still below the error, False where not; run only if any."""
    if not any(ambiguous(r) for r in rows + strict):
        return
    path = os.path.join(tmp, "%s_%d.csv" % (name, a.confirm_resolution))
    run(a.bag_analyze, bag, path, a.params,
        {"resolution": a.confirm_resolution, "work_budget": 1000000000, "propagate_covariance": "false"}, "transient")
    finer = read(path)
    if len(finer) != len(rows):
        sys.exit("%s: the confirming run answered %d messages, not %d" % (bag, len(finer), len(rows)))
    cut = sum(1 for f in finer if int(f["brush_flags"]) & FLAG_SUBSTEPS_TRUNCATED)
    if cut:
        print("%s: the confirming run at %d was cut short at %d messages (BRUSH_FLAG_SUBSTEPS_TRUNCATED): its estimate "
              "there is the friction circle's" % (bag, a.confirm_resolution, cut), file=sys.stderr)
    for part in (rows, strict):
        for r, f in zip(part, finer):
            if ambiguous(r):
                r["_confirmed"] = error(r, f) > float(r["brush_error_estimate"]) + float(f["brush_error_estimate"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bag-analyze", required=True)
    ap.add_argument("--bags", nargs="+", required=True)
    ap.add_argument("--scenario", required=True)
    ap.add_argument("--params", default=None)
    ap.add_argument("--reference-resolution", type=int, default=128)
    ap.add_argument("--confirm-resolution", type=int, default=0,
                    help="where an estimate is below its error beyond the reference's difference but not beyond its own "
                         "estimate, run the reference at this resolution too and recount those against it (0: off)")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    parts = segments(a.scenario)
    out = {"reference_resolution": a.reference_resolution, "streams": []}
    with tempfile.TemporaryDirectory() as tmp:
        for bag in a.bags:
            name = os.path.splitext(os.path.basename(bag))[0]
            replays = [os.path.join(tmp, "%s_%d.csv" % (name, k)) for k in range(3)]
            walls = [run(a.bag_analyze, bag, path, a.params, {}) for path in replays]
            default_csv = replays[0]
            reference = {}
            for n in (a.reference_resolution, a.reference_resolution // 2):
                path = os.path.join(tmp, "%s_%d.csv" % (name, n))
                run(a.bag_analyze, bag, path, a.params,
                    {"resolution": n, "work_budget": 1000000000, "propagate_covariance": "false"}, "transient")
                reference[n] = read(path)
            rows = fastest([read(path) for path in replays], bag)
            # the strict target: accuracy_target 0.1 %, not raised to the noise's share
            strict_replays = [os.path.join(tmp, "%s_strict_%d.csv" % (name, k)) for k in range(3)]
            for path in strict_replays:
                run(a.bag_analyze, bag, path, a.params, STRICT)
            strict = fastest([read(path) for path in strict_replays], bag)
            fine, coarse = reference[a.reference_resolution], reference[a.reference_resolution // 2]
            if not (len(rows) == len(fine) == len(coarse) == len(strict)):
                sys.exit("%s: the runs answered different messages (%d, %d, %d, %d)"
                         % (bag, len(rows), len(fine), len(coarse), len(strict)))
            t0 = float(rows[0]["stamp"])
            skipped = warm_up(rows, default_csv)
            for i, (r, q, f, c) in enumerate(zip(rows, strict, fine, coarse)):
                r["_error"], q["_error"] = (error(r, f), error(q, f)) if i >= skipped else (None, None)
                own = error(c, f)  # the reference's difference from half its resolution
                r["_reference_error"] = q["_reference_error"] = own
                r["_reference_bound"] = q["_reference_bound"] = max(own, float(f["brush_error_estimate"]))
                t = r["_t"] = q["_t"] = float(r["stamp"]) - t0
                r["_segment"] = q["_segment"] = next((p[0] for p in parts if p[1] <= t < p[2] + 1e-9), parts[-1][0])
            if a.confirm_resolution:
                confirm(a, bag, tmp, name, rows, strict)
            duration = float(rows[-1]["stamp"]) - t0
            # the references are bound by the work budget too (at its largest, 1e9): where one was cut short its
            # answer claims no more than the friction circle, and the comparisons there say nothing
            cut = sum(1 for f, c in zip(fine, coarse)
                      if (int(f["brush_flags"]) | int(c["brush_flags"])) & FLAG_SUBSTEPS_TRUNCATED)
            if cut:
                print("%s: the reference (or its half resolution) was cut short at %d messages "
                      "(BRUSH_FLAG_SUBSTEPS_TRUNCATED): the comparisons there say nothing" % (bag, cut), file=sys.stderr)
            stream = {"bag": os.path.basename(bag), "messages": len(rows), "not_compared": skipped,
                      "reference_cut_short": cut,
                      "rate": (len(rows) - 1) / duration if duration > 0 else None, "duration": duration,
                      "bag_analyze_seconds": min(walls), "times_real_time": duration / min(walls),
                      "all": summarise(rows), "segments": {}, "strict": dict(summarise(strict), settings=STRICT)}
            for seg in dict.fromkeys(p[0] for p in parts):
                sel = [r for r in rows if r["_segment"] == seg]
                if sel:
                    stream["segments"][seg] = summarise(sel)
            out["streams"].append(stream)
            s = stream["all"]
            print("%s: %d messages at %.0f Hz; bag_analyze %.1fx real time; per message p50 %.0f us, p99 %.0f us, max %.0f us"
                  " (work max %.0f); flagged %d (%.1f %%: %d held by the work budget, %d cut short, %d at standstill);"
                  " unflagged: largest error %.2g, %d over the target; estimate below the error at %d"
                  % (stream["bag"], len(rows), stream["rate"] or 0.0, stream["times_real_time"], s["time_us"]["p50"],
                     s["time_us"]["p99"], s["time_us"]["max"], s["work"]["max"], s["flagged"],
                     100.0 * s["flagged"] / max(1, len(rows)), s["flagged_budget_limited"],
                     s["flagged_substeps_truncated"], s["flagged_standstill"], s["unflagged_error_max"] or 0.0,
                     s["unflagged_over_target"], s["estimate_short"]), file=sys.stderr)
            q = stream["strict"]
            print("  at accuracy_target 0.1 %%: per message p50 %.0f us, p99 %.0f us, max %.0f us; flagged %d (%.1f %%);"
                  " unflagged: largest error %.2g, %d over the target; estimate below the error at %d"
                  % (q["time_us"]["p50"], q["time_us"]["p99"], q["time_us"]["max"], q["flagged"],
                     100.0 * q["flagged"] / max(1, len(strict)), q["unflagged_error_max"] or 0.0,
                     q["unflagged_over_target"], q["estimate_short"]), file=sys.stderr)
    text = json.dumps(out, indent=1)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    else:
        print(text)


if __name__ == "__main__":
    main()
