#!/usr/bin/env python3
"""Random robots on random manoeuvres: the stream checks of stream_benchmark.py on streams nobody picked.

Each seed draws a robot over the envelope (patch radius 4-50 mm, bristle stiffness 3e7-1e9 N/m^3, mass 1-40 kg,
friction 0.3-1.2, any pressure law; the rest config/contact_estimator.yaml's defaults) and a manoeuvre of three or
four segments (rolling with longitudinal slip, weaving with spin, pivots with lateral sliding, skids, spin in place,
parked) at 30, 100 or 1000 Hz with the demo's noise or up to twice it; demo.launch records it (real time), and
stream_benchmark.py compares every message with the converged reference run of the same stream. A bag already in the
output folder is reused. The summary counts, over all streams: unflagged messages over their target and estimates
below their error (both beyond the reference's own difference; and beyond its own error estimate, a bound; and, for
those between the two, against resolution 256 with its estimate as the slack), at the default target and at 0.1 %,
the work budget's heaviest messages, and why the answers were flagged (held by the work budget, at standstill).

Usage: stream_sweep.py --bag-analyze PATH --dir FOLDER [--streams 24] [--seed 1000] [--set NAME=VALUE ...] [--out JSON]
(--set: a parameter of every robot's file beyond the drawn ones, for the run and its references alike, e.g. tilt=true)
"""
import argparse
import json
import math
import os
import random
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)


def log_uniform(r, lo, hi):
    return math.exp(r.uniform(math.log(lo), math.log(hi)))


def robot(r):
    return {"patch_radius": log_uniform(r, 0.004, 0.05), "bristle_stiffness": log_uniform(r, 3e7, 1e9),
            "robot_mass": log_uniform(r, 1.0, 40.0), "friction": r.uniform(0.3, 1.2),
            "pressure": r.choice(["parabolic", "hertzian", "uniform"])}


def segment(r, i):
    kind = r.choice(["roll", "roll", "weave", "pivot", "skid", "spin", "park"])
    v = r.uniform(0.1, 2.0)
    s = {"name": "%d_%s" % (i, kind), "duration": r.choice([0.5, 1.0, 1.5])}
    if kind == "roll":
        s.update(speed=[round(r.uniform(0, 2), 3), round(r.uniform(0, 2), 3)], sliding=round(r.uniform(-0.3, 0.3), 3))
    elif kind == "weave":
        s.update(speed=round(v, 3), lateral_sliding=round(r.uniform(-0.2, 0.2) * v, 4),
                 yaw_rate=round(r.uniform(-3, 3), 3), spin_rate=round(r.uniform(-25, 25), 3))
    elif kind == "pivot":
        s.update(speed=round(r.uniform(0.1, 1.0), 3), lateral_sliding=round(r.uniform(-0.2, 0.2), 4),
                 yaw_rate=round(r.uniform(-6, 6), 3), spin_rate=round(r.uniform(-35, 35), 3))
    elif kind == "skid":
        s.update(speed=[round(v, 3), 0.0], sliding=[round(r.uniform(0.1, 0.6), 3), round(r.uniform(0, 0.2), 3)])
    elif kind == "spin":
        s.update(spin_rate=round(r.uniform(-30, 30), 3))
    return s  # park: nothing moves but the noise


def scenario(r, seed):
    segments = [segment(r, i) for i in range(r.choice([3, 4]))]
    lines = ["# stream_sweep.py, seed %d" % seed, "rate: 100.0", "noise_omega: %g" % r.choice([0.005, 0.02, 0.05]),
             "noise_velocity: %g" % r.choice([0.002, 0.005, 0.01]), "seed: %d" % seed, "segments:"]
    lines += ["  - " + json.dumps(s) for s in segments]
    return "\n".join(lines) + "\n"


def parameters(p):
    text = open(os.path.join(REPO, "config", "contact_estimator.yaml")).read()
    for k, v in p.items():
        text, n = re.subn(r"(?m)^%s:.*$" % k, "%s: %s" % (k, v), text)
        if n != 1:
            sys.exit("config/contact_estimator.yaml has no single line for %s" % k)
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bag-analyze", required=True)
    ap.add_argument("--dir", required=True, help="folder for the streams' bags, scenarios and parameter files")
    ap.add_argument("--streams", type=int, default=24)
    ap.add_argument("--seed", type=int, default=1000)
    ap.add_argument("--set", nargs="+", default=[], metavar="NAME=VALUE",
                    help="a parameter of every robot's file beyond the drawn ones (e.g. tilt=true)")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    fixed = {}
    for item in a.set:
        name, sep, value = item.partition("=")
        if not sep or not name:
            sys.exit("--set takes NAME=VALUE, not %r" % item)
        fixed[name] = value
    os.makedirs(a.dir, exist_ok=True)
    streams = []
    for seed in range(a.seed, a.seed + a.streams):
        r = random.Random(seed)
        p = robot(r)
        p.update(fixed)
        rate = r.choice([30, 100, 100, 100, 1000])
        files = {k: os.path.join(a.dir, "%s_%d.%s" % (k, seed, ext))
                 for k, ext in (("scenario", "yaml"), ("params", "yaml"), ("stream", "bag"), ("result", "json"))}
        with open(files["scenario"], "w") as f:
            f.write(scenario(r, seed))
        with open(files["params"], "w") as f:
            f.write(parameters(p))
        if not os.path.exists(files["stream"]):
            subprocess.run(["roslaunch", "sphere_contact_estimator", "demo.launch", "scenario:=" + files["scenario"],
                            "rate:=%d" % rate, "record:=" + files["stream"], "output_csv:=" + os.devnull],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if not os.path.exists(files["stream"]):
            sys.exit("seed %d: demo.launch recorded nothing (is a ROS environment sourced?)" % seed)
        done = subprocess.run([sys.executable, os.path.join(HERE, "stream_benchmark.py"), "--bag-analyze",
                               a.bag_analyze, "--params", files["params"], "--scenario", files["scenario"],
                               "--reference-resolution", "128", "--confirm-resolution", "256", "--bags", files["stream"],
                               "--out", files["result"]],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
        if done.returncode != 0:
            sys.exit("seed %d: stream_benchmark.py failed:\n%s" % (seed, done.stderr))
        with open(files["result"]) as f:
            s = json.load(f)["streams"][0]
        row = {"seed": seed, "rate": rate, "robot": p, "segments": list(s["segments"].keys()),
               "messages": s["messages"], "not_compared": s["not_compared"], "default": s["all"], "strict": s["strict"]}
        streams.append(row)
        d, q = s["all"], s["strict"]
        print("seed %d, %d Hz, a %.1f mm, k %.2g, %.1f kg, mu %.2f, %s: %d messages; flagged %.0f %% (%d held by the"
              " work budget, %d at standstill); over the target"
              " %d / %d, estimate below the error %d (%d beyond the reference's estimate, %d at 256) / %d (%d, %d);"
              " max %.0f us, work max %.0f"
              % (seed, rate, 1e3 * p["patch_radius"], p["bristle_stiffness"], p["robot_mass"], p["friction"],
                 p["pressure"], s["messages"], 100.0 * d["flagged"] / s["messages"], d.get("flagged_budget_limited", 0),
                 d.get("flagged_standstill", 0), d["unflagged_over_target"],
                 q["unflagged_over_target"], d["estimate_short"], d["estimate_short_resolved"],
                 d["estimate_short_confirmed_finer"], q["estimate_short"], q["estimate_short_resolved"],
                 q["estimate_short_confirmed_finer"], d["time_us"]["max"], d["work"]["max"]), file=sys.stderr, flush=True)
    total = {k: sum(s[part][key] for s in streams)
             for k, part, key in (("over_target", "default", "unflagged_over_target"),
                                  ("over_target_strict", "strict", "unflagged_over_target"),
                                  ("estimate_short", "default", "estimate_short"),
                                  ("estimate_short_resolved", "default", "estimate_short_resolved"),
                                  ("estimate_short_strict", "strict", "estimate_short"),
                                  ("estimate_short_resolved_strict", "strict", "estimate_short_resolved"),
                                  ("estimate_short_at_256", "default", "estimate_short_confirmed_finer"),
                                  ("estimate_short_at_256_strict", "strict", "estimate_short_confirmed_finer"))}
    # why the default pass's answers were flagged (stream_benchmark.py: BRUSH_FLAG_BUDGET_LIMITED, standstill)
    for k in ("flagged", "flagged_budget_limited", "flagged_substeps_truncated", "flagged_standstill"):
        total[k] = sum(s["default"].get(k, 0) for s in streams)
    total["streams"] = len(streams)
    total["messages"] = sum(s["messages"] for s in streams)
    total["compared"] = sum(s["messages"] - s["not_compared"] for s in streams)
    text = json.dumps({"total": total, "streams": streams}, indent=1)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    else:
        print(text)


if __name__ == "__main__":
    main()
