#!/usr/bin/env python3
"""Plot the per-message CSV of the calibrate tool, to judge how well the fitted contact parameters explain a run.

Reads the CSV that calibrate writes: comment lines starting with '# ' (the fit's record, e.g. the fitted
bristle stiffness and friction with their uncertainties), one header line, then one row per odometry message:
  t,used,rejection,speed,slip_x,slip_y,spin,sliding,measured_x,measured_y,predicted_x,predicted_y,force_sd,
  residual_x,residual_y
(used: 1 if the message entered the fit; rejection: why not; forces in the ground frame [N]; residuals in units
of force_sd, empty or nan where not used). Writes into OUTDIR:
  force_time.png  measured and predicted force (x, y) against t; spans outside the fit shaded
  force_slip.png  measured and predicted force magnitude against the slip magnitude (used messages)
  residuals.png   normalised residuals against t, and their histogram against the standard normal density
  coverage.png    speed against slip magnitude coloured by sliding share, and the sliding share's histogram
  summary.png     the CSV's comment lines, message counts and rejection reasons as text

Usage: plot_calibration.py CSV OUTDIR [--title TEXT]
"""
import argparse
import collections
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

COLUMNS = ("t", "used", "rejection", "speed", "slip_x", "slip_y", "spin", "sliding", "measured_x", "measured_y",
           "predicted_x", "predicted_y", "force_sd", "residual_x", "residual_y")
TEXT_COLUMNS = ("rejection",)
DPI = 120
MEASURED = dict(color="0.55")
PREDICTED = dict(color="C0")
SHADE = dict(facecolor="C1", alpha=0.15, edgecolor="none")


class CsvError(Exception):
    """The CSV cannot be plotted; the message says why."""


def number(text):
    """The cell as a float; NaN for an empty or unreadable cell."""
    try:
        return float(text)
    except ValueError:
        return math.nan


def read_lines(path):
    """(comment texts without '# ', header cells, data rows as lists of cells) of the file."""
    if not os.path.isfile(path):
        raise CsvError("%s: %s" % (path, "not a file" if os.path.exists(path) else "no such file"))
    comments, header, rows = [], None, []
    try:
        with open(path, newline="") as f:
            for cells in csv.reader(f):
                if not cells or all(not c.strip() for c in cells):
                    continue
                if cells[0].startswith("#"):
                    comments.append(",".join(cells)[1:].strip())
                elif header is None:
                    header = [c.strip() for c in cells]
                else:
                    rows.append(cells)
    except (OSError, UnicodeDecodeError, csv.Error) as err:
        raise CsvError("%s: cannot read: %s" % (path, err))
    if header is None:
        raise CsvError("%s: no header line" % path)
    return comments, header, rows


def to_columns(header, rows, path):
    """{column: array} for the expected columns; float arrays, object arrays for the text columns."""
    missing = [c for c in COLUMNS if c not in header]
    if missing:
        raise CsvError("%s: missing column(s): %s" % (path, ", ".join(missing)))
    if not rows:
        raise CsvError("%s: no data rows (header only)" % path)
    data = {}
    for name in COLUMNS:
        i = header.index(name)
        cells = [r[i].strip() if i < len(r) else "" for r in rows]
        data[name] = np.array(cells, dtype=object) if name in TEXT_COLUMNS else np.array([number(c) for c in cells])
    return data


def load(path):
    """(comment lines, {column: array}) of the CSV; CsvError when it is unusable."""
    comments, header, rows = read_lines(path)
    return comments, to_columns(header, rows, path)


def derive(d):
    """Adds the used mask and the magnitudes the plots need."""
    d["in_fit"] = d["used"] == 1
    d["slip"] = np.hypot(d["slip_x"], d["slip_y"])
    d["measured"] = np.hypot(d["measured_x"], d["measured_y"])
    d["predicted"] = np.hypot(d["predicted_x"], d["predicted_y"])
    return d


def runs(mask):
    """(first, last) index pairs of the stretches where mask is True."""
    edges = np.diff(np.concatenate(([0], mask.astype(np.int8), [0])))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1))


def cell_bounds(t):
    """Per message the time span it stands for: from the midpoint to its predecessor to that to its successor."""
    t = np.where(np.isfinite(t), t, np.nan)
    if len(t) == 1:
        return t - 0.5, t + 0.5
    mid = 0.5 * (t[1:] + t[:-1])
    lower = np.concatenate(([t[0] - (mid[0] - t[0])], mid))
    upper = np.concatenate((mid, [t[-1] + (t[-1] - mid[-1])]))
    return lower, upper


def shade_outside_fit(ax, t, in_fit, label):
    """Shades the time spans of the messages outside the fit over the axes' full height."""
    lower, upper = cell_bounds(t)
    boxes = []
    for first, last in runs(~in_fit):
        a, b = lower[first], upper[last]
        if np.isfinite(a) and np.isfinite(b):
            boxes.append([(a, 0), (b, 0), (b, 1), (a, 1)])
    if boxes:
        ax.add_collection(PolyCollection(boxes, transform=ax.get_xaxis_transform(), label=label, **SHADE))


def note(ax, text):
    """A centred message in an axes that has nothing to show."""
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", color="0.4")


def new_figure(title, **kwargs):
    fig, axes = plt.subplots(**kwargs)
    fig.suptitle(title)
    return fig, axes


def save(fig, outdir, name, **kwargs):
    """Writes the figure as OUTDIR/name, closes it and reports the path."""
    path = os.path.join(outdir, name)
    fig.savefig(path, dpi=DPI, **kwargs)
    plt.close(fig)
    print(path)


def plot_force_time(d, title, outdir):
    fig, axes = new_figure(title, nrows=2, sharex=True, figsize=(11, 6.5))
    for ax, axis in zip(axes, "xy"):
        ax.plot(d["t"], d["measured_" + axis], lw=0.6, label="measured (IMU)", **MEASURED)
        ax.plot(d["t"], d["predicted_" + axis], lw=1.2, label="predicted (fitted parameters)", **PREDICTED)
        shade_outside_fit(ax, d["t"], d["in_fit"], "not in the fit")
        ax.set_ylabel("$F_%s$ (ground frame) [N]" % axis)
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper right", fontsize=8, ncol=3)
    axes[-1].set_xlabel("t [s]")
    fig.tight_layout()
    save(fig, outdir, "force_time.png")


def plot_force_slip(d, title, outdir):
    fig, ax = new_figure(title, figsize=(8, 5.5))
    use = d["in_fit"] & np.isfinite(d["slip"])
    log = np.any(use & (d["slip"] > 0))
    if log:
        use &= d["slip"] > 0
    if not use.any():
        note(ax, "no messages in the fit")
    else:
        style = dict(s=4, linewidths=0, rasterized=True)
        ax.scatter(d["slip"][use], d["measured"][use], label="measured (IMU)", **style, **MEASURED)
        ax.scatter(d["slip"][use], d["predicted"][use], label="predicted (fitted parameters)", **style, **PREDICTED)
        ax.legend(loc="upper left", fontsize=8, markerscale=3)
    if log:
        ax.set_xscale("log")
        dropped = np.count_nonzero(d["in_fit"] & (d["slip"] == 0))
        if dropped:
            ax.text(0.99, 0.01, "%d messages at zero slip not shown" % dropped, transform=ax.transAxes,
                    ha="right", va="bottom", fontsize=8, color="0.4")
    ax.set_xlabel("slip magnitude $\\sqrt{\\sigma_x^2 + \\sigma_y^2}$ [-]")
    ax.set_ylabel("horizontal force magnitude [N]")
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    save(fig, outdir, "force_slip.png")


def residual_stats(r):
    """Text with the count, mean, sd and share beyond +-3 of the residuals."""
    return "n = %d\nmean = %.3g\nsd = %.3g\nbeyond $\\pm$3: %.2f %%" % (
        r.size, np.mean(r), np.std(r), 100.0 * np.mean(np.abs(r) > 3))


def plot_residuals_time(ax, d):
    shown = 0
    for axis, colour in (("x", "C0"), ("y", "C3")):
        r = d["residual_" + axis]
        use = d["in_fit"] & np.isfinite(r)
        shown += np.count_nonzero(use)
        ax.scatter(d["t"][use], r[use], s=3, linewidths=0, color=colour, label="residual " + axis, rasterized=True)
    t = d["t"][np.isfinite(d["t"])]
    if t.size and t.max() > t.min():
        margin = 0.02 * (t.max() - t.min())
        ax.set_xlim(t.min() - margin, t.max() + margin)  # the whole run, as in force_time.png
    if shown:
        ax.legend(loc="upper right", fontsize=8, markerscale=3)
    else:
        note(ax, "no residuals")
    for level in (-2, 2):
        ax.axhline(level, color="0.3", lw=0.8, ls="--")
    ax.axhline(0, color="0.3", lw=0.6)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("residual [force sd]")
    ax.grid(alpha=0.3)


def plot_residual_histogram(ax, d):
    r = np.concatenate([d["residual_" + a][d["in_fit"]] for a in "xy"])
    r = r[np.isfinite(r)]
    ax.set_xlabel("residual [force sd], x and y pooled")
    ax.set_ylabel("density")
    if r.size == 0:
        note(ax, "no residuals")
        return
    half = max(4.0, min(float(np.percentile(np.abs(r), 99.5)), 20.0))
    ax.hist(r, bins=60, range=(-half, half), density=True, color="C0", alpha=0.6, label="residuals")
    z = np.linspace(-half, half, 400)
    ax.plot(z, np.exp(-0.5 * z * z) / math.sqrt(2 * math.pi), color="k", lw=1.2, label="standard normal")
    text = residual_stats(r)
    outside = np.count_nonzero(np.abs(r) > half)
    if outside:
        text += "\n%d beyond $\\pm$%.3g (not shown)" % (outside, half)
    ax.text(0.02, 0.98, text, transform=ax.transAxes, ha="left", va="top", fontsize=8,
            bbox=dict(facecolor="white", alpha=0.8, edgecolor="0.7"))
    ax.legend(loc="upper right", fontsize=8)


def plot_residuals(d, title, outdir):
    fig, (left, right) = new_figure(title, ncols=2, figsize=(12, 5), gridspec_kw=dict(width_ratios=(3, 2)))
    plot_residuals_time(left, d)
    plot_residual_histogram(right, d)
    fig.tight_layout()
    save(fig, outdir, "residuals.png")


def plot_speed_slip(fig, ax, d):
    use = d["in_fit"] & np.isfinite(d["speed"]) & np.isfinite(d["slip"])
    log = np.any(use & (d["slip"] > 0))
    if log:
        use &= d["slip"] > 0
        ax.set_yscale("log")
    ax.set_xlabel("rolling speed $V_r$ [m/s]")
    ax.set_ylabel("slip magnitude [-]")
    ax.set_title("messages in the fit", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    if not use.any():
        note(ax, "no messages in the fit")
        return
    points = ax.scatter(d["speed"][use], d["slip"][use], c=d["sliding"][use], s=5, linewidths=0,
                        cmap="viridis", vmin=0, vmax=1, plotnonfinite=True, rasterized=True)
    fig.colorbar(points, ax=ax, label="sliding share of the contact patch")


def plot_sliding_histogram(ax, d):
    bins = np.linspace(0, 1, 21)
    fit = d["sliding"][d["in_fit"] & np.isfinite(d["sliding"])]
    every = d["sliding"][np.isfinite(d["sliding"])]
    ax.hist(every, bins=bins, histtype="step", color="0.4", label="all messages (%d)" % every.size)
    ax.hist(fit, bins=bins, color="C0", alpha=0.6, label="in the fit (%d)" % fit.size)
    ax.set_xlabel("sliding share of the contact patch [-]")
    ax.set_ylabel("messages")
    ax.legend(loc="upper right", fontsize=8)
    ax.grid(alpha=0.3)


def plot_coverage(d, title, outdir):
    fig, (left, right) = new_figure(title, ncols=2, figsize=(12, 5), gridspec_kw=dict(width_ratios=(3, 2)))
    plot_speed_slip(fig, left, d)
    plot_sliding_histogram(right, d)
    fig.tight_layout()
    save(fig, outdir, "coverage.png")


def summary_lines(comments, d):
    """The CSV's comments, then the message counts and the rejection reasons, most frequent first."""
    n, used = len(d["t"]), int(np.count_nonzero(d["in_fit"]))
    lines = list(comments) + ["", "messages: %d, in the fit: %d, not: %d" % (n, used, n - used)]
    reasons = collections.Counter(r or "(no reason given)" for r in d["rejection"][~d["in_fit"]])
    lines += ["  %6d  %s" % (count, reason) for reason, count in reasons.most_common()]
    return lines


def plot_summary(comments, d, title, outdir):
    lines = summary_lines(comments, d)
    fig = plt.figure(figsize=(8, 0.8 + 0.16 * len(lines)))
    fig.suptitle(title, x=0.02, ha="left")  # the saved figure is cropped to the text
    fig.text(0.02, 1.0 - 0.5 / fig.get_figheight(), "\n".join(lines), ha="left", va="top", family="monospace",
             fontsize=9)
    save(fig, outdir, "summary.png", bbox_inches="tight", pad_inches=0.2)  # long comment lines widen it


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", metavar="CSV", help="the calibrate tool's per-message CSV")
    ap.add_argument("outdir", metavar="OUTDIR", help="directory for the PNGs (created if needed)")
    ap.add_argument("--title", help="figure title (default: the CSV's file name)")
    return ap.parse_args()


def main():
    args = parse_args()
    try:
        comments, d = load(args.csv)
    except CsvError as err:
        print("plot_calibration: %s" % err, file=sys.stderr)
        return 2
    derive(d)
    title = args.title if args.title else os.path.basename(args.csv)
    os.makedirs(args.outdir, exist_ok=True)
    plot_force_time(d, title, args.outdir)
    plot_force_slip(d, title, args.outdir)
    plot_residuals(d, title, args.outdir)
    plot_coverage(d, title, args.outdir)
    plot_summary(comments, d, title, args.outdir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
