#!/usr/bin/env python3
"""Join the Google Benchmark timings (bench_models) and the accuracies (model_accuracy) into the speed/accuracy
tables docs/benchmarks.md and the Pareto plot docs/figures/pareto.png.

Usage: benchmark_report.py --bench BENCH.json --accuracy ACCURACY.json --docs DOCS_DIR
                           [--node NODE.json] [--bag BAG.json] [--default-brush-model 1..4]

--replay is replay_benchmark's output (odometry only, then with --tf), --replay-profile the write-up of where its time
went; --node is node_benchmark's output (the node over roscpp and the bag replay); --bag is the analysis of the noisy demo
bag by the previous and the current auto model ({"targets": [{"target", "before": {"linear", "steady", "transient",
"max_error"}, "after": {...}}], "reference", "messages"}). Errors are max(|dF_x|, |dF_y|, |dM_z| / a) / (mu F_z).
"""
import argparse
import datetime
import json
import math
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TARGETS = {  # issue 5
    "linear": 100.0,             # ns per evaluation
    "steady 1e-3": 5000.0,       # ns, median over the Fig. 4 set at a target of 1e-3
    "steady 1e-4": 10000.0,      # ns, median over the Fig. 4 set at a target of 1e-4
    "steady error": 1e-4,        # of mu F_z at every random point, at a target of 1e-4
    "estimate share": 0.99,      # error estimate >= the error at this share of the random points, never below half
    "auto": (1e-3, 1e-2, 5e-2),  # no random point over its target
    "cylinder exact": 2000.0,
    "cylinder table": 50.0,
    "node": 5000.0,              # Hz on one core with the default brush model
}
BRUSH_MODELS = {1: "linear", 2: "steady", 3: "transient", 4: "auto"}


def medians(bench):
    """name -> median real time per iteration [ns]"""
    out = {}
    for b in bench["benchmarks"]:
        if b.get("aggregate_name", "median") != "median" or b.get("error_occurred"):
            continue
        name = re.sub(r"_median$", "", b.get("run_name", b["name"]))
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b.get("time_unit", "ns")]
        out[name] = b["real_time"] * scale
    return out


def repetitions(bench):
    return max([b.get("repetitions", 1) for b in bench["benchmarks"]] or [1])


def parse_name(name):
    """'BM_X/key:value/...' -> ('BM_X', {key: value}); parts without a colon (Google Benchmark's own suffixes) are
    ignored."""
    parts = name.split("/")
    return parts[0], dict(p.split(":", 1) for p in parts[1:] if ":" in p)


def group_times(times):
    """The brush benchmarks by family and argument."""
    g = {"figure4": {}, "marching": {}, "transient": {}, "transient_noisy": {}, "spin": {}, "estimator": {},
         "covariance": {}, "covariance_steady": {}}
    for name, t in times.items():
        family, args = parse_name(name)
        if family == "BM_BrushSteadyFigure4":
            key = (float(args["target"]), int(args["tilt"]))
            g["figure4"].setdefault(key, []).append(t)
        elif family == "BM_BrushMarchingFigure4":
            g["marching"][(int(args["resolution"]), int(args["tilt"]))] = t
        elif family == "BM_BrushTransientStep":
            g["transient"][(int(args["resolution"]), int(args["tilt"]))] = t
        elif family == "BM_BrushTransientNoisyStep":
            g["transient_noisy"][(int(args["resolution"]), int(args["tilt"]))] = t
        elif family == "BM_BrushSteadySpinAgainstSlip":
            g["spin"][int(args["target_exponent"])] = t
        elif family == "BM_ForceCovariance":
            g["covariance"][int(args["demo"])] = t
        elif family == "BM_SteadyAtCovarianceTolerance":
            g["covariance_steady"][int(args["demo"])] = t
        elif family == "BM_EstimatorUpdate":
            g["estimator"][int(args["brush_model"])] = t
    return g


def same(a, b):
    return abs(a - b) <= 1e-9 * max(abs(a), abs(b))


def lookup(table, target, tilt=None):
    """table keyed by target (or by (target, tilt)), looked up with a float tolerance"""
    for k, v in table.items():
        t, kt = (k, None) if tilt is None else k
        if same(t, target) and kt == tilt:
            return v
    return None


def quantile(xs, q):
    """linear interpolation between order statistics (numpy's default)"""
    s = sorted(xs)
    if not s:
        return None
    pos = q * (len(s) - 1)
    i = int(math.floor(pos))
    j = min(i + 1, len(s) - 1)
    return s[i] + (s[j] - s[i]) * (pos - i)


def fig4_median(g, target, tilts=(0, 1)):
    pts = []
    for tilt in tilts:
        pts += lookup(g["figure4"], target, tilt) or []
    return quantile(pts, 0.5)


def mean(xs):
    xs = [x for x in xs if x is not None]
    return sum(xs) / len(xs) if xs else None


def fmt_time(ns):
    if ns is None:
        return "-"
    return "%.0f ns" % ns if ns < 1e3 else ("%.2f µs" % (ns / 1e3) if ns < 1e6 else "%.2f ms" % (ns / 1e6))


def fmt_us(us):
    return "-" if us is None else fmt_time(1e3 * us)


def short(text):
    """'1.5e-05' -> '1.5e-5', '2e+08' -> '2e8'"""
    return re.sub(r"e\+?(-?)0*(\d)", r"e\1\2", text)


def fmt_err(x):
    if x is None:
        return "-"
    return "0" if x == 0 else short("%.2g" % x)


def fmt_target(t):
    m, e = ("%e" % t).split("e")
    return "%ge%d" % (float(m), int(e))


def fmt_ratio(r):
    return "%.2g×" % r if r < 1 else ("%.1f×" % r if r < 10 else "%.0f×" % r)


def fmt_share(n, total):
    if not total:
        return "-"
    share = 100.0 * n / total
    return "%.0f %%" % share if share == 0 or share >= 10 else "%.1f %%" % share


def verdict(value, limit, higher_is_better=False):
    if value is None:
        return "not measured"
    if (value >= limit) if higher_is_better else (value <= limit):
        return "met"
    if value > 0 and limit > 0:
        over = limit / value if higher_is_better else value / limit
        return "missed by %.0f %%" % (100.0 * (over - 1.0)) if over < 1.5 else "missed by " + fmt_ratio(over)
    return "missed"


def describe_point(w):
    """a random operating point (model_accuracy's describe()) in a compact form"""
    return short("%s, %s, a = %.3g mm, F_z = %.4g N, μ = %.2f, k = %.2g N/m³, σ = (%.3g, %.3g), φ = %.3g 1/m,"
                 " χ_γ = %.2f" % (
        w.get("pressure", "?"), "tilt" if w.get("tilt") else "no tilt", 1e3 * w.get("a", float("nan")),
        w.get("F_z", float("nan")), w.get("mu", float("nan")), w.get("k", float("nan")),
        w.get("sigma_x", float("nan")), w.get("sigma_y", float("nan")), w.get("phi", float("nan")),
        w.get("chi_gamma", float("nan")))).replace("(-", "(−").replace(" -", " −")


def steady_section(acc, g):
    f4 = acc["figure4"]
    per_tilt = f4.get("points", 168) // 2
    counts = sorted(set(len(v) for v in g["figure4"].values()))
    lines = ["## The steady brush model", "",
             "The Fig. 4 set of Romano et al.: a = 0.05 m, k = 1.023e8 N/m³, F_z = 3000 N, μ = 1, parabolic pressure,"
             " φ = 3.33 1/m, χ_γ = 0.9, σ_x from −1 to 1 in steps of 0.1 and σ_y in {0, 0.05, 0.1, 0.2}: %d points per"
             " tilt value, without and with tilt. Each point is one benchmark of one evaluation; the table gives the"
             " median, 90th percentile and max over the points, and the largest error over the set against the"
             " solver at a target of 1e-8 (model_accuracy), with the number of points where the solver's error"
             " estimate is below its error." % per_tilt]
    if counts and counts != [per_tilt]:
        lines[-1] += " (This run timed %s points per target and tilt.)" % "/".join(str(c) for c in counts)
    lines += ["", "| target | median | p90 | max | median, tilt | p90, tilt | max, tilt | median, both | max error |"
              " max error, tilt | estimate < error |", "|" + "---|" * 11]
    for r in sorted(f4["steady"], key=lambda r: -r["target"]):
        t = r["target"]
        cells = []
        for tilt in (0, 1):
            pts = lookup(g["figure4"], t, tilt) or []
            cells += [fmt_time(quantile(pts, 0.5)), fmt_time(quantile(pts, 0.9)), fmt_time(max(pts) if pts else None)]
        lines.append("| %s | %s | %s | %s | %s | %d of %d |" % (
            fmt_target(t), " | ".join(cells), fmt_time(fig4_median(g, t)), fmt_err(r["max_error"]),
            fmt_err(r["max_error_tilt"]), r.get("estimate_below_error", 0), f4.get("points", 2 * per_tilt)))
    lines.append("")

    # the old scheme
    lines += ["The package's previous steady scheme (marching cells along the bristle paths, kept in test/support) at"
              " resolution n: its cost does not depend on the point, so one benchmark cycles through the set and"
              " gives the average time per evaluation; its error is the largest over the set against the same"
              " reference.", "",
              "| resolution | time | time, tilt | max error | max error, tilt |", "|---|---|---|---|---|"]
    march_acc = {r["resolution"]: r for r in f4.get("marching", [])}
    resolutions = sorted(set(march_acc) | set(n for n, _ in g["marching"]))
    for n in resolutions:
        r = march_acc.get(n, {})
        lines.append("| %d | %s | %s | %s | %s |" % (n, fmt_time(g["marching"].get((n, 0))),
                                                     fmt_time(g["marching"].get((n, 1))),
                                                     fmt_err(r.get("max_error")), fmt_err(r.get("max_error_tilt"))))
    lines.append("")

    def set_time(n):  # average over the whole set, both tilt values
        t = [g["marching"].get((n, tilt)) for tilt in (0, 1)]
        return None if None in t else mean(t)

    reaching = [n for n in sorted(march_acc) if max(march_acc[n]["max_error"], march_acc[n]["max_error_tilt"]) <= 0.01]
    new2, new3 = fig4_median(g, 1e-2), fig4_median(g, 1e-3)
    if not reaching:
        lines += ["No resolution of the old scheme up to %d reaches 1 %% on the set." % max(march_acc or [0]), ""]
    else:
        first = reaching[0]
        timed = [n for n in reaching if set_time(n) is not None]

        def errors(n):
            return "max error %s without tilt, %s with" % (fmt_err(march_acc[n]["max_error"]),
                                                           fmt_err(march_acc[n]["max_error_tilt"]))

        if timed and timed[0] == first:
            text = "The old scheme at resolution %d, which reaches 1 %% (%s), takes" % (first, errors(first))
        elif timed:
            text = ("The old scheme first reaches 1 %% at resolution %d, which this run did not time; at resolution %d,"
                    " the smallest timed one that does (%s), it takes" % (first, timed[0], errors(timed[0])))
        else:
            text = None
            lines += ["The old scheme first reaches 1 %% at resolution %d; this run timed no resolution that does." %
                      first, ""]
        if text and new2 and new3:
            n = timed[0]
            per_tilt_ratio = [g["marching"][(n, tilt)] / fig4_median(g, 1e-2, (tilt,)) for tilt in (0, 1)
                              if fig4_median(g, 1e-2, (tilt,))]
            lines += ["%s %s the time of the new one at 1e-2 (%s at 1e-3), its average over the whole set against the"
                      " new solver's median over it%s." % (
                          text, fmt_ratio(set_time(n) / new2), fmt_ratio(set_time(n) / new3),
                          "; by tilt value at 1e-2: %s without tilt, %s with" % tuple(
                              fmt_ratio(x) for x in per_tilt_ratio) if len(per_tilt_ratio) == 2 else ""), ""]
        elif text:
            lines += ["The old scheme reaches 1 %% at resolution %d; the new solver was not timed at 1e-2 and 1e-3." %
                      timed[0], ""]

    # spin against slip
    lines += ["The previous release's hardest operating point, spin against slip (σ = (0, −0.05), φ = 10 1/m, no tilt,"
              " the Fig. 4 parameters otherwise), slides almost everywhere around a spin centre inside the patch except"
              " a small zone where bristles re-adhere; one evaluation of the new solver there:", "",
              "| target | time |", "|---|---|"]
    for e in sorted(g["spin"]):
        lines.append("| %s | %s |" % (fmt_target(10.0 ** -e), fmt_time(g["spin"][e])))
    lines.append("")
    return lines


def random_section(acc):
    rnd = acc["random"]
    n = rnd["points"]
    lines = ["## Error control on random operating points", "",
             "%d seeded random operating points over the envelope a user reaches: a = 0.01–0.08 m, F_z = 20–5000 N,"
             " μ = 0.2–1.2, k = 10^6.5–10^9 N/m³, |σ_x| ≤ 0.3, |σ_y| ≤ 0.1, |aφ| ≤ 1, χ_γ from −0.5 to 1.5, the three"
             " pressure distributions, without and with tilt, slips and spin scaled together by 10^−3 to 1 (weighted"
             " towards the envelope's edge). The steady solver at each target is compared with itself at 1e-8; the"
             " times are single calls timed inside model_accuracy (steady_clock, not Google Benchmark)." % n, "",
             "| target | max error | points over target | estimate < error | estimate < error/2 | max error/estimate |"
             " median time | p99 time |", "|---|---|---|---|---|---|---|---|"]
    steady = sorted(rnd["steady"], key=lambda r: -r["target"])
    for r in steady:
        lines.append("| %s | %s | %d | %d | %d | %.2g | %s | %s |" % (
            fmt_target(r["target"]), fmt_err(r["max_error"]), r["over_target"], r["estimate_below_error"],
            r["estimate_below_half_error"], r["max_error_over_estimate"], fmt_us(r.get("median_us")),
            fmt_us(r.get("p99_us"))))
    lines += ["", "The worst point at each target:", ""]
    for r in steady:
        lines.append("- %s: %s" % (fmt_target(r["target"]), describe_point(r.get("worst", {}))))
    lines.append("")
    bf = rnd.get("reference_vs_brute_force")
    if bf:
        lines += ["The reference itself: on %d of the points it agrees with the independent brute-force marcher of"
                  " test/support (8000 paths, 400 steps; its own error is about 3e-5 μF_z where a re-adhering island"
                  " lies in the patch) within %s μF_z." % (bf["points"], fmt_err(bf["max_difference"])), ""]
    ref = rnd.get("reference")
    if ref:
        lines += ["Its own estimate: at most %s μF_z; %d of the %d reference evaluations stopped at the solver's work"
                  " budget before meeting 1e-8." % (fmt_err(ref["max_estimate"]), ref["unconverged"], rnd["points"]), ""]
    lb = rnd.get("linear_bound")
    if lb:
        lines += ["The linear model's error bound, at the %d points where it is at most 0.1 (where auto could pick the"
                  " linear model): the error exceeded the bound at %d, and reached at most %.2g of it." % (
                      lb["points"], lb["error_over_bound"], lb["max_error_over_bound"]), ""]
    auto = sorted(rnd.get("auto", []), key=lambda r: -r["target"])
    if auto:
        lines += ["Auto (brush model 4) at each target on the same points, the inputs held as for a robot rolling at"
                  " 1 m/s (five updates at 100 Hz), against the reference; the share of the points at which each model"
                  " gave the last update:", "",
                  "| target | max error | points over target | estimate < error | linear | steady | transient |",
                  "|---|---|---|---|---|---|---|"]
        for r in auto:
            total = r.get("linear", 0) + r.get("steady", 0) + r.get("transient", 0)
            lines.append("| %s | %s | %d | %d | %s | %s | %s |" % (
                fmt_target(r["target"]), fmt_err(r["max_error"]), r["over_target"], r["estimate_below_error"],
                fmt_share(r.get("linear", 0), total), fmt_share(r.get("steady", 0), total),
                fmt_share(r.get("transient", 0), total)))
        lines += ["", "The worst point at each target:", ""]
        for r in auto:
            lines.append("- %s: %s" % (fmt_target(r["target"]), describe_point(r.get("worst", {}))))
        lines.append("")
    return lines


def transient_section(acc, g):
    cases = acc.get("transient", [])
    resolutions = sorted(set(run["resolution"] for c in cases for run in c["runs"]))
    lines = ["## The transient model", "",
             "At held inputs (1 m/s), by resolution, at the issue's example point and at Fig. 4 points: after 6a of"
             " travel from an unloaded patch, the largest error over two lattice spacings more (the error moves with"
             " where the lattice stands, so a single sample can be lucky) against the steady solver at 1e-10, with the"
             " model's largest error estimate over the same updates in parentheses.", "",
             "| case | " + " | ".join("%d" % n for n in resolutions) + " |", "|" + "---|" * (1 + len(resolutions))]
    for c in cases:
        runs = {run["resolution"]: run for run in c["runs"]}
        lines.append("| %s | %s |" % (c["name"], " | ".join(
            "%s (%s)" % (fmt_err(runs[n]["error"]), fmt_err(runs[n]["estimate"])) if n in runs else "-"
            for n in resolutions)))
    summary = acc.get("transient_convergence", [])
    if summary:
        lines += ["", "Over whole sets, the same measurement at resolutions %s: how many points converge monotonically"
                  " (the error falls at every doubling), the largest rise where one does not, the median observed order"
                  " from 32 to 128, and the updates where the estimate fell short of the error (of all updates measured)"
                  " with the largest error / estimate there." % ", ".join(str(n) for n in resolutions), "",
                  "| set | points | monotone | largest rise | median order | estimate < error | largest error / estimate |",
                  "|---|---|---|---|---|---|---|"]
        for c in summary:
            lines.append("| %s | %d | %d | %s | %.2f | %d of %d | %s |" % (
                c["name"], c["points"], c["monotone"], "%.2f×" % c["worst_rise"] if c["worst_rise"] > 0 else "-",
                c["median_order"], c["estimate_short"], c["updates"],
                "%.2f" % c["worst_error_over_estimate"] if c["worst_error_over_estimate"] > 0 else "-"))
        worst = [c for c in summary if c.get("worst_rise_at")]
        if worst:
            lines += ["", "Where a rise was largest:", ""]
            for c in worst:
                w = c["worst_rise_at"]
                lines.append("- %s: %s, %s, a = %.3g mm, F_z = %.4g N, μ = %.2g, k = %.2g N/m³, σ = (%.3g, %.3g),"
                             " φ = %.3g 1/m, χ_γ = %.2g, at resolution %d" % (
                                 c["name"], w["pressure"], "tilt" if w["tilt"] else "no tilt", 1e3 * w["a"], w["F_z"],
                                 w["mu"], w["k"], w["sigma_x"], w["sigma_y"], w["phi"], w["chi_gamma"],
                                 w["resolution"]))
    lines += ["", "One 1 ms step at 1 m/s (a 1 kHz driver) in steady rolling at σ = (0.05, 0.02), φ = 3.33 1/m,"
              " χ_γ = 0.9 on the Fig. 4 parameters, at held inputs and with noise on the slips and the spin at every"
              " step (the rows' correction is then re-evaluated each patch radius of travel):", "",
              "| resolution | time | time, tilt | time, noisy | time, noisy, tilt |", "|---|---|---|---|---|"]
    for n in sorted(set(n for n, _ in g["transient"])):
        lines.append("| %d | %s | %s | %s | %s |" % (
            n, fmt_time(g["transient"].get((n, 0))), fmt_time(g["transient"].get((n, 1))),
            fmt_time(g["transient_noisy"].get((n, 0))), fmt_time(g["transient_noisy"].get((n, 1)))))
    lines.append("")
    return lines


def uncertainty_section(acc, g):
    rows = acc.get("uncertainty", [])
    if not rows:
        return []
    lines = ["## Uncertainty: the forces' covariance", "",
             "The covariance of (F_x, F_y, M_z) from that of the slips and spin (σ_x, σ_y, φ) by the unscented"
             " transform through the steady model (force_covariance.h), against Monte Carlo (2000 draws of the steady"
             " model each, to 1/200 of the spread) at seeded random operating points over the envelope; the slips"
             " spread by the given share of their own size (plus a floor of 1e-5) with random correlations. Errors: of"
             " each standard deviation, relative to the larger of itself and a fifth of the largest (M_z over a; the"
             " sigma points resolve the largest spread, a far smaller one only to that), and absolute, of each"
             " correlation between components so resolved, where the Monte Carlo standard deviation is above 1e-5 μF_z."
             " The Monte Carlo error itself is about 1.6 % on a standard deviation and 0.02 on a correlation. Points"
             " the transform flags as not smooth over the spread (ForceCovariance::smooth: a kink or jump within it,"
             " or the edge of the steady state with tilt; the estimate's status is then APPROXIMATE) are counted"
             " apart.", "",
             "| spread of the slips | points | smooth: largest sd error | smooth: largest correlation error |"
             " smooth: beyond 10 % or 0.1 | flagged not smooth | flagged: beyond 10 % or 0.1 | evaluations per point |"
             " mean time | smooth: largest sd error, linearised instead |", "|" + "---|" * 10]
    for r in rows:
        lines.append("| %g %% | %d | %.3f | %.3f | %d | %d | %d | %.1f | %.0f µs | %s |" % (
            100 * r["relative_spread"], r["points"], r["worst_sd_error"], r["worst_correlation_error"],
            r["over_tolerance"], r.get("flagged", 0), r.get("over_tolerance_flagged", 0), r["mean_evaluations"],
            r["mean_time_us"], "%.3f" % r["worst_sd_error_linearised"] if "worst_sd_error_linearised" in r else "-"))
    lines += ["", "The last column: the same covariance linearised instead, by central differences of the steady model"
              " along the principal axes of the slips' covariance (a hundredth of a standard deviation each way, as"
              " many evaluations): exact where the model is smooth, far off where the spread reaches the onset of"
              " sliding or the friction limit, which is why the package uses the unscented transform there."]
    worst = [r for r in rows if r.get("worst_at")]
    if worst:
        lines += ["", "Where a standard deviation was furthest off among the smooth points:", ""]
        for r in worst:
            w = r["worst_at"]
            lines.append("- %g %%: %s, %s, a = %.3g mm, F_z = %.4g N, μ = %.2g, k = %.2g N/m³, σ = (%.3g, %.3g),"
                         " φ = %.3g 1/m, χ_γ = %.2g" % (100 * r["relative_spread"], w["pressure"],
                                                      "tilt" if w["tilt"] else "no tilt", 1e3 * w["a"], w["F_z"],
                                                      w["mu"], w["k"], w["sigma_x"], w["sigma_y"], w["phi"],
                                                      w["chi_gamma"]))
    if g.get("covariance"):
        lines += ["", "Cost, against one steady evaluation at the tolerance the sigma points use (a twentieth of the"
                  " forces' spread), in the same run:", "",
                  "| point | covariance | one steady evaluation | ratio |", "|---|---|---|---|"]
        names = {0: "Fig. 4, σ = (0.05, 0.02), φ = 3.33 1/m, sd 0.005 and 0.1 1/m",
                 1: "demo robot at the demo bag's slips and noise"}
        for k in sorted(g["covariance"]):
            c, st = g["covariance"][k], g["covariance_steady"].get(k)
            lines.append("| %s | %s | %s | %s |" % (names.get(k, k), fmt_time(c), fmt_time(st),
                                                    "%.1f×" % (c / st) if st else "-"))
    lines.append("")
    return lines


def cylinder_section(acc, times):
    lines = ["## Cylinder models (rolling resistance)", "",
             "The paper's rubber (R = 0.1 m, M = 250 kg/m, k = 1e7, γ = 5e5, m = 100, g = 10): v* = %.3g m/s,"
             " v_c = %.3g m/s. Error: |Δμ_roll| / μ_roll against the exact solution." % (
                 acc["cylinder_speeds"]["v_star"], acc["cylinder_speeds"]["v_critical"]), ""]
    cpts = list(acc["cylinder"][0]["errors"].keys())
    lines += ["| model | time | max error | " + " | ".join(cpts) + " |", "|" + "---|" * (3 + len(cpts))]
    lines.append("| exact | %s | (reference) |" % fmt_time(times["BM_CylinderExact"]) + " |" * len(cpts))
    ctime = {"expansion": times["BM_CylinderExpansion"], "table": times["BM_CylinderTable"]}
    for r in acc["cylinder"]:
        lines.append("| %s | %s | %.2g | %s |" % (r["model"], fmt_time(ctime[r["model"]]), r["max"],
                                                  " | ".join("%.2g" % r["errors"][p] for p in cpts)))
    lines.append("| table, μ_roll only | %s | as above |" % fmt_time(times["BM_CylinderTableMuRoll"]) + " |" * len(cpts))
    lines.append("")
    return lines


def node_section(node):
    lines = ["## The node", "",
             "`contact_estimator_node` with config/contact_estimator.yaml (a 5 kg robot), pinned to one core (taskset),"
             " fed over roscpp on loopback by `node_benchmark` on the other core. Odometry is published at each rate"
             " for 2 s; a rate is sustained when every message is answered and the p99 latency from the odometry stamp"
             " to the estimate's arrival stays below 20 ms (no backlog building up). The odometry has no twist"
             " covariance. Where a model's cost per message is near the period, the highest sustained rate can differ"
             " by one step between runs on these shared machines (seen: transient at 10 and 5 kHz in two runs).",
             "", "| brush model | highest sustained rate | p50 latency | p99 latency | rates tried (received/sent) |",
             "|---|---|---|---|---|"]
    for r in node["node"]:
        tried = ", ".join("%d Hz %d/%d" % (t["rate"], t["received"], t["sent"]) for t in r["tried"])
        lines.append("| %s | %d Hz | %.2f ms | %.2f ms | %s |" % (BRUSH_MODELS.get(r["brush_model"], r["brush_model"]),
                     r["max_rate"], 1e3 * r["p50"], 1e3 * r["p99"], tried))
    lines += ["", "Offline replay of a bag (the demo manoeuvre at 1 kHz, 11 001 odometry messages) by bag_analyze's"
              " own path (analyzeBag: the node's estimator class, writing the output bag and the CSV), without a twist covariance"
              " (no uncertainty to carry: the models alone; with it, the next section):", "",
              "| brush model | messages per second |", "|---|---|"]
    for r in node["replay"]:
        lines.append("| %s | %.0f |" % (BRUSH_MODELS.get(r["brush_model"], r["brush_model"]), r["messages_per_second"]))
    lines.append("")
    return lines


def replay_section(replays, profile):
    """bag_analyze at scale: replay_benchmark's runs (odometry only, and with /tf beside each message), and the
    profile of the replay path before and after issue 14 (bench/replay_profile.md, measured once, by hand)."""
    lines = ["## Offline replay at scale (bag_analyze)", "",
             "`replay_benchmark` writes a bag of the demo manoeuvre at 1 kHz, repeated to %d odometry messages (the"
             " odometry's orientation and noise covariance; in the second run the sphere's pose on /tf beside each"
             " message, which the estimator then looks up), and replays it through bag_analyze's own path (analyzeBag:"
             " the node's estimator class, writing the output bag and the CSV), one core (taskset). The estimator's"
             " own rate is the messages over the time spent in its update() (the models and their uncertainty, with"
             " the covariance propagated as by default): the most a replay could reach with that model."
             % replays[0]["messages"], "",
             "| brush model | replay, odometry only | replay, odometry and /tf | estimator alone | replay / estimator alone |",
             "|---|---|---|---|---|"]
    writers = [w for run in replays for w in run.get("writers", [])]
    replays = [run for run in replays if "replay" in run]
    with_tf = {}
    for run in replays[1:]:
        for r in run["replay"]:
            with_tf[r["brush_model"]] = r
    for r in replays[0]["replay"]:
        t = with_tf.get(r["brush_model"])
        own = r.get("estimator_messages_per_second", 0)
        lines.append("| %s | %.0f msgs/s (%.1f µs each) | %s | %s | %s |" % (
            r["name"], r["messages_per_second"], 1e6 / r["messages_per_second"],
            "%.0f msgs/s" % t["messages_per_second"] if t else "-",
            "%.0f msgs/s (%.1f µs each)" % (own, 1e6 / own) if own else "-",
            "%.2f" % (r["messages_per_second"] / own) if own else "-"))
    lines += [""]
    if profile:
        lines += profile + [""]
    if writers:
        lines += ["| writer (10⁵ odometry messages) | µs per message |", "|---|---|"]
        for w in writers:
            lines.append("| `%s` | %.2f |" % (w["name"], w["us_per_message"]))
        lines += ["", "rosbag::Bag::write / BagWriter::write: %.0f×." % (
            writers[0]["us_per_message"] / writers[-1]["us_per_message"]), ""]
    return lines


def bag_section(bag):
    lines = ["## Auto on the noisy demo bag", "",
             "The demo bag with noise on the odometry%s, replayed with brush model auto at each accuracy target by the"
             " previous release (before) and the current one (after): the share of updates given by each brush model,"
             " and the largest error against the reference (%s) as a fraction of μF_z (- where not measured)." % (
                 " (%d messages)" % bag["messages"] if bag.get("messages") is not None else "",
                 bag.get("reference", "not described")), "",
             "| target | linear, before | steady, before | transient, before | max error, before | linear, after |"
             " steady, after | transient, after | max error, after |", "|" + "---|" * 9]
    for r in sorted(bag.get("targets", []), key=lambda r: -r["target"]):
        cells = []
        for when in ("before", "after"):
            s = r.get(when) or {}
            total = sum(s.get(m) or 0 for m in ("linear", "steady", "transient"))
            cells += [fmt_share(s.get(m) or 0, total) for m in ("linear", "steady", "transient")]
            cells.append(fmt_err(s.get("max_error")))
        lines.append("| %s | %s |" % (fmt_target(r["target"]), " | ".join(cells)))
    noisy = [r for r in bag.get("targets", []) if r.get("below_noise")]
    if noisy:
        f = noisy[0]["below_noise"].get("noise_fraction")
        lines += ["", "Below the noise (issue 13): the bag's odometry carries its noise in its twist covariance, and auto's"
                  " target rises to %s of the forces' spread carried from it where that is larger. Each message against"
                  " the target it was computed to (brush_accuracy_target), and the replay's wall time (fastest of"
                  " three, bag reading and writing included) without and with the rule:" % f, "",
                  "| target | linear / steady / transient | max error | largest target | over its own target |"
                  " largest error / own target | time, plain target | time, below the noise |", "|" + "---|" * 8]
        for r in sorted(noisy, key=lambda r: -r["target"]):
            s_, a = r["below_noise"], r.get("after") or {}
            total = sum(s_.get(m) or 0 for m in ("linear", "steady", "transient"))
            lines.append("| %s | %s | %s | %s | %d | %.2f | %s | %s |" % (
                fmt_target(r["target"]), " / ".join(fmt_share(s_.get(m) or 0, total) for m in ("linear", "steady", "transient")),
                fmt_err(s_.get("max_error")), fmt_err(s_.get("largest_target")), s_.get("over_own_target", 0),
                s_.get("largest_error_over_own_target", 0.0),
                "%.2f s" % a["time"] if a.get("time") else "-", "%.2f s" % s_["time"] if s_.get("time") else "-"))
    lines.append("")
    return lines


def targets_section(acc, times, g, node, default_model):
    lines = ["## Targets", "", "| target | measured | |", "|---|---|---|"]
    lin = times.get("BM_BrushLinear")
    lines.append("| linear ≤ 100 ns | %s | %s |" % (fmt_time(lin), verdict(lin, TARGETS["linear"])))
    for t, key, limit_text in ((1e-3, "steady 1e-3", "5 µs"), (1e-4, "steady 1e-4", "10 µs")):
        both, no_tilt, tilt = fig4_median(g, t), fig4_median(g, t, (0,)), fig4_median(g, t, (1,))
        v = verdict(both, TARGETS[key])
        if both is not None:
            v += " (without tilt: %s; with tilt: %s)" % (verdict(no_tilt, TARGETS[key]), verdict(tilt, TARGETS[key]))
        measured = "%s over both tilt values (%s without tilt, %s with)" % (
            fmt_time(both), fmt_time(no_tilt), fmt_time(tilt)) if both is not None else "not timed"
        lines.append("| steady: median on the Fig. 4 set ≤ %s at %s | %s | %s |" % (
            limit_text, fmt_target(t), measured, v))

    rnd = acc["random"]
    n = rnd["points"]
    r4 = [r for r in rnd["steady"] if same(r["target"], 1e-4)]
    if r4:
        r4 = r4[0]
        limit = TARGETS["steady error"]
        if r4["over_target"] == 0 and r4["max_error"] <= limit:
            v = "met"
        else:
            v = verdict(r4["max_error"], limit) if r4["max_error"] > limit else "missed"
        lines.append("| steady within 1e-4 μF_z of the reference at every random point (target 1e-4) | max error %s,"
                     " %d of %d points over | %s |" % (fmt_err(r4["max_error"]), r4["over_target"], n, v))
    else:
        lines.append("| steady within 1e-4 μF_z of the reference at every random point (target 1e-4) | - |"
                     " not measured |")

    if rnd["steady"]:
        worst = max(rnd["steady"], key=lambda r: (r["estimate_below_error"], r["estimate_below_half_error"]))
        below = max(r["estimate_below_error"] for r in rnd["steady"])
        half = max(r["estimate_below_half_error"] for r in rnd["steady"])
        ratio = max(r["max_error_over_estimate"] for r in rnd["steady"])
        share_below = below / float(n)
        allowed = 1.0 - TARGETS["estimate share"]
        if share_below <= allowed and half == 0:
            v = "met"
        elif share_below > allowed:
            v = "missed by " + fmt_ratio(share_below / allowed)
        else:
            v = "missed"
        lines.append("| error estimate ≥ the error at ≥ 99 %% of random points, never below half of it | below the"
                     " error at %d of %d points (%.1f %%) at worst (target %s), below half of it at %d; error/estimate"
                     " ≤ %.2g | %s |" % (below, n, 100.0 * share_below, fmt_target(worst["target"]), half, ratio, v))

    autos = {r["target"]: r for r in rnd.get("auto", [])}
    measured, over, excess = [], 0, 0.0
    for t in TARGETS["auto"]:
        r = lookup(autos, t)
        if r is None:
            measured.append("%g %%: not measured" % (100 * t))
            continue
        measured.append("%d over at %g %%" % (r["over_target"], 100 * t))
        over += r["over_target"]
        excess = max(excess, r["max_error"] / t)
    if all(lookup(autos, t) is None for t in TARGETS["auto"]):
        v = "not measured"
    elif over == 0 and all(lookup(autos, t) is not None for t in TARGETS["auto"]):
        v = "met"
    elif over == 0:
        v = "met where measured"
    else:
        v = "missed by " + fmt_ratio(excess) if excess > 1 else "missed"
    lines.append("| auto: no random point over its target at 0.1 %%, 1 %%, 5 %% | %s (max error/target %.2g) | %s |" % (
        ", ".join(measured), excess, v))

    for name, bm, key in (("cylinder exact ≤ 2 µs", "BM_CylinderExact", "cylinder exact"),
                          ("cylinder table ≤ 50 ns (full state)", "BM_CylinderTable", "cylinder table"),
                          ("cylinder table ≤ 50 ns (μ_roll)", "BM_CylinderTableMuRoll", "cylinder table")):
        t = times.get(bm)
        lines.append("| %s | %s | %s |" % (name, fmt_time(t), verdict(t, TARGETS[key])))
    if node:
        default = [r for r in node["node"] if r["brush_model"] == default_model]
        rate = default[0]["max_rate"] if default else None
        lines.append("| node ≥ 5 kHz with the default model (%s) on one core | %s | %s |" % (
            BRUSH_MODELS[default_model], "%d Hz" % rate if rate is not None else "-",
            verdict(rate, TARGETS["node"], higher_is_better=True)))
    lines.append("")
    return lines


def pareto_points(acc, g):
    """model -> [(time [ns], max error over the Fig. 4 set, label)]"""
    pts = {"steady": [], "marching": [], "transient": []}
    for r in acc["figure4"]["steady"]:
        t = fig4_median(g, r["target"])
        if t is not None:
            pts["steady"].append((t, max(r["max_error"], r["max_error_tilt"]), fmt_target(r["target"])))
    for r in acc["figure4"].get("marching", []):
        t = [g["marching"].get((r["resolution"], tilt)) for tilt in (0, 1)]
        if None not in t:
            pts["marching"].append((mean(t), max(r["max_error"], r["max_error_tilt"]), str(r["resolution"])))
    fig4_cases = [c for c in acc.get("transient", []) if c["name"].startswith("Fig. 4")]
    for n in sorted(set(n for n, _ in g["transient"])):
        errors = [run["error"] for c in fig4_cases for run in c["runs"] if run["resolution"] == n]
        t = [g["transient"].get((n, tilt)) for tilt in (0, 1)]
        if errors and None not in t:
            pts["transient"].append((mean(t), max(errors), str(n)))
    return pts


def pareto_plot(pts, path):
    fig, ax = plt.subplots(figsize=(7, 4.8))
    styles = {"steady": ("C0o-", "steady (labels: target)"), "marching": ("C2s-", "old marching scheme (resolution)"),
              "transient": ("C3^-", "transient, 1 ms step (resolution)")}
    floor = 1e-12  # a zero error on a log axis
    placed = []  # labels so far, in decades
    for model, (style, label) in styles.items():
        p = sorted(pts[model])
        if not p:
            continue
        ax.loglog([x[0] for x in p], [max(x[1], floor) for x in p], style, label=label, ms=5)
        for t, e, text in p:
            x, y = math.log10(t), math.log10(max(e, floor))
            for dx, dy in ((3, 3), (3, -9), (-14, 5), (-14, -9)):  # first offset whose label clears the others
                at = (x + dx / 150.0, y + dy / 150.0)
                if all(abs(at[0] - q[0]) > 0.12 or abs(at[1] - q[1]) > 0.08 for q in placed):
                    break
            placed.append(at)
            ax.annotate(text, (t, max(e, floor)), textcoords="offset points", xytext=(dx, dy), fontsize=7)
    front = []
    for t, e, _ in sorted(x for model in pts.values() for x in model):
        if not front or e < front[-1][1]:
            front.append((t, e))
    if front:
        ax.step([p[0] for p in front], [max(p[1], floor) for p in front], "k:", where="post", lw=1,
                label="Pareto front")
    ax.axhline(0.01, color="gray", lw=0.8, ls="--", label="1 %")
    ax.set_xlabel("time per evaluation [ns]")
    ax.set_ylabel("max error over the Fig. 4 set [μF_z]")
    ax.set_title("Brush models on the Fig. 4 set: accuracy against cost")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", required=True)
    ap.add_argument("--accuracy", required=True)
    ap.add_argument("--node", help="node_benchmark output")
    ap.add_argument("--bag", help="analysis of the noisy demo bag by the previous and the current auto model")
    ap.add_argument("--replay", nargs="+", help="replay_benchmark outputs: odometry only, then with --tf, then --writers")
    ap.add_argument("--replay-profile", help="markdown: where the replay's time went (bench/replay_profile.md)")
    ap.add_argument("--default-brush-model", type=int, default=4, choices=sorted(BRUSH_MODELS),
                    help="the node's default brush_model (1 linear, 2 steady, 3 transient, 4 auto), for the node"
                    " target")
    ap.add_argument("--docs", required=True)
    a = ap.parse_args()
    with open(a.bench) as f:
        bench = json.load(f)
    with open(a.accuracy) as f:
        acc = json.load(f)
    node = bag = None
    if a.node:
        with open(a.node) as f:
            node = json.load(f)
    if a.bag:
        with open(a.bag) as f:
            bag = json.load(f)
    times = medians(bench)
    g = group_times(times)

    lines = ["# Speed and accuracy of the models", ""]
    ctx = bench.get("context", {})
    reps = repetitions(bench)
    date = ctx.get("date", "")[:10] or datetime.date.today().isoformat()
    lines += ["Measured by `./scripts/benchmark.sh` on %s (%s CPUs at %.0f MHz, %s build of the package), %s. Times are"
              % (ctx.get("host_name", "?"), ctx.get("num_cpus", "?"), ctx.get("mhz_per_cpu", 0), "Release", date),
              "%s of Google Benchmark (real time); the machines are shared, so compare ratios within one run, not"
              " across runs. Brush errors are max(|ΔF_x|, |ΔF_y|, |ΔM_z|/a) / μF_z against a converged reference, the"
              " steady solver at a target of 1e-8 (1e-10 for the transient runs), itself checked against an independent"
              " brute-force marcher below; cylinder errors are against the exact solution of eq. 18." % (
                  "medians of %d repetitions" % reps if reps > 1 else "from one repetition"), ""]
    lines += steady_section(acc, g)
    lines += random_section(acc)
    lines += transient_section(acc, g)
    lines += uncertainty_section(acc, g)
    lines += cylinder_section(acc, times)
    if node:
        lines += node_section(node)
    if a.replay:
        replays = []
        for path in a.replay:
            with open(path) as f:
                replays.append(json.load(f))
        profile = None
        if a.replay_profile:
            with open(a.replay_profile) as f:
                profile = f.read().rstrip("\n").split("\n")
        lines += replay_section(replays, profile)
    if bag:
        lines += bag_section(bag)
    lines += targets_section(acc, times, g, node, a.default_brush_model)
    lines += ["The plot: time per evaluation on the Fig. 4 set (the new solver: its median over both tilt values at"
              " each target; the old scheme: its average over the set; the transient model: one 1 ms step, the mean of"
              " without and with tilt) against the largest error over the set (the transient model: over the Fig. 4"
              " cases of its convergence table). The linear model has no error figure on the set and is left out.", "",
              "![Pareto front](figures/pareto.png)", ""]

    os.makedirs(os.path.join(a.docs, "figures"), exist_ok=True)
    with open(os.path.join(a.docs, "benchmarks.md"), "w") as f:
        f.write("\n".join(lines))
    pareto_plot(pareto_points(acc, g), os.path.join(a.docs, "figures", "pareto.png"))
    print("wrote %s and %s" % (os.path.join(a.docs, "benchmarks.md"), os.path.join(a.docs, "figures", "pareto.png")))


if __name__ == "__main__":
    main()
