#!/usr/bin/env python3
"""Plot the per-estimate CSV of bag_analyze: brush forces, slips and spins, rolling resistance, friction circle.

Reads the CSV that bag_analyze writes (one header line, one row per estimate; REP 103 contact frame:
x along the rolling direction, y left, z up) and writes four PNG figures, time t [s] on the x axis:
  <prefix>_forces.png              brush F_x, F_y with +-mu F_z, and M_z; mostly sliding spans shaded
  <prefix>_slips.png               V_r; slips sigma_x, sigma_y; spins phi, phi_gamma, phi_psi
  <prefix>_rolling_resistance.png  mu_roll, penetration depth h and force F_R; point contact marked
  <prefix>_friction_circle.png     F_y against F_x coloured by t, with the friction circle(s) mu F_z
Slips and spins are undefined at standstill (slips_defined = 0) and drawn as gaps there; their axes turn
symmetric-log when the data span more than three decades. A model that was off (brush_model or
rr_model 0) is stated in its figure instead of being drawn as zeros. Where the CSV has the standard deviations
carried from the odometry's covariance (brush_fx_std, brush_fy_std, brush_mz_std, rr_force_std; empty where
unknown), the forces, M_z, F_R and mu_roll are drawn with +-2 sigma bands.

Usage: plot_analysis.py CSV [--output DIR] [--prefix NAME] [--start T0] [--end T1]
"""
import argparse
import os
import sys
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.axes_grid1 import make_axes_locatable  # noqa: E402

DPI = 120
REQUIRED = ("t", "rolling_speed", "slips_defined", "slip_x", "slip_y", "spin", "spin_tilt", "spin_turn",
            "load", "friction", "brush_model", "brush_model_used", "brush_fx", "brush_fy", "brush_mz",
            "sliding_fraction", "rr_model", "rr_h", "rr_mu_roll", "rr_force", "rr_regime")
BRUSH_MODELS = {1: "linear", 2: "steady", 3: "transient"}  # brush_model_used
RR_MODELS = {1: "exact", 2: "expansion", 3: "table"}
RR_MARKS = {2: ("C3", "point contact (past $v_c$)"), 3: ("C1", "no steady state")}  # rr_regime
OPTIONAL = ("brush_fx_std", "brush_fy_std", "brush_mz_std", "rr_force_std")  # empty cells: unknown
FLAG_MOTION_WITHIN_NOISE = 64  # ContactEstimate.FLAG_MOTION_WITHIN_NOISE: the motion is within the twist's noise
DECADES = 3.0  # beyond this span a linear axis flattens the typical values to a line at zero
LEGEND = dict(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize=8)


def load_csv(path):
    """{column: array} of the CSV; RuntimeError with a readable message when it is unusable."""
    if not os.path.isfile(path):
        raise RuntimeError("%s: %s" % (path, "not a file" if os.path.exists(path) else "no such file"))
    try:
        with open(path) as f:
            line = f.readline()
            while line.startswith("#"):  # bag_analyze's record of what made the estimates
                line = f.readline()
            header = [h.strip() for h in line.split(",")]
            if header == [""]:
                raise RuntimeError("%s: empty file (no header line)" % path)
            missing = [c for c in REQUIRED if c not in header]
            if missing:
                raise RuntimeError("%s: missing column(s): %s" % (path, ", ".join(missing)))
            def optional(text):
                text = text.strip()
                return float(text) if text else np.nan
            converters = {header.index(c): optional for c in OPTIONAL if c in header}
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # loadtxt warns on a header-only file: reported below
                data = np.loadtxt(f, delimiter=",", ndmin=2, converters=converters or None)
    except (OSError, ValueError) as err:
        raise RuntimeError("%s: cannot read as a numeric CSV: %s" % (path, err))
    if data.size == 0:
        raise RuntimeError("%s: no data rows (header only)" % path)
    if data.shape[1] != len(header):
        raise RuntimeError("%s: %d columns in the header but %d in the rows" % (path, len(header), data.shape[1]))
    return {name: data[:, i] for i, name in enumerate(header)}


def prepare(d):
    """Turns what is undefined (standstill slips, models off) into NaN so that it plots as gaps."""
    d["brush_on"] = (d["brush_model"] != 0) & (d["brush_model_used"] != 0)
    d["rr_on"] = d["rr_model"] != 0
    for keys, on in ((("slip_x", "slip_y", "spin", "spin_tilt", "spin_turn"), d["slips_defined"] != 0),
                     (("brush_fx", "brush_fy", "brush_mz", "sliding_fraction"), d["brush_on"]),
                     (("rr_h", "rr_mu_roll", "rr_force"), d["rr_on"])):
        for k in keys:
            d[k] = np.where(on, d[k], np.nan)
    mu_fz = d["friction"] * d["load"]
    d["mu_fz"] = np.where(mu_fz > 0, mu_fz, np.nan)  # no bound to draw where load or friction are not set
    # M_z's bound, mu F_z a (older CSVs have no patch radius: none)
    d["mu_fz_a"] = d["mu_fz"] * d["patch_radius"] if "patch_radius" in d else np.full(d["t"].shape, np.nan)
    for k in OPTIONAL:  # older CSVs have none: no bands
        d.setdefault(k, np.full(d["t"].shape, np.nan))
    # parked: the forces are the bristles' response to the odometry's noise (older CSVs have no such flag)
    flags = d["flags"].astype(np.int64) if "flags" in d else np.zeros(d["t"].shape, np.int64)
    d["within_noise"] = d["brush_on"] & ((flags & FLAG_MOTION_WITHIN_NOISE) != 0)
    for k in ("brush_fx_std", "brush_fy_std", "brush_mz_std"):
        d[k] = np.where(d["brush_on"], d[k], np.nan)
    d["rr_force_std"] = np.where(d["rr_on"], d["rr_force_std"], np.nan)


def marks(d):
    """A few rows draw no visible line: mark the samples then."""
    return {"marker": ".", "ms": 5} if d["t"].size < 50 else {}


def shade(ax, t, mask, color, label):
    """Shades each run of mask, from halfway to the previous sample to halfway to the next."""
    edges = np.concatenate(([t[0]], 0.5 * (t[:-1] + t[1:]), [t[-1]]))
    change = np.flatnonzero(np.diff(np.concatenate(([0], mask.astype(int), [0]))))
    runs = [(edges[i], edges[j]) for i, j in zip(change[::2], change[1::2]) if edges[j] > edges[i]]
    for k, (t0, t1) in enumerate(runs):
        ax.axvspan(t0, t1, color=color, alpha=0.15, lw=0, label=None if k else label)


def note(ax, text):
    """States on the axes why there is nothing to see."""
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", fontsize=9, color="0.3",
            bbox=dict(boxstyle="round", fc="white", ec="0.6"))


def scale_y(ax, series, linthresh):
    """Symmetric-log y axis when the data span more than DECADES decades (above linthresh), else linear."""
    a = np.abs(np.concatenate(series))
    a = a[np.isfinite(a) & (a > 0)]
    if a.size and np.log10(a.max() / max(np.percentile(a, 10), linthresh)) > DECADES:
        ax.set_yscale("symlog", linthresh=linthresh)
        return " (symlog)"
    return ""


def finish(ax, ylabel):
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(**LEGEND)


def time_axis(ax, t):
    """Whole time range even where every series is a gap (a model off)."""
    ax.set_xlabel("t [s]")
    if t[-1] > t[0]:
        ax.set_xlim(t[0], t[-1])


def lines(ax, d, specs):
    for key, colour, label in specs:
        ax.plot(d["t"], d[key], colour, lw=1, label=label, **marks(d))


def band(ax, t, y, sd, colour, label, limit=None):
    """+-2 sigma about y where sd is known (the odometry's covariance carried through the model), within +-limit where
    given: the friction limit, which the forces never pass (a parked robot's walked spread reaches it)."""
    known = np.isfinite(sd) & np.isfinite(y)
    if known.any():
        lo, hi = y - 2.0 * sd, y + 2.0 * sd
        if limit is not None:
            lo, hi = np.fmax(lo, -limit), np.fmin(hi, limit)  # (no limit where it is not known: NaN)
        ax.fill_between(t, lo, hi, where=known, color=colour, alpha=0.25, lw=0, label=label)


def names(values, table):
    used = [int(v) for v in np.unique(values[np.isfinite(values)]) if int(v) in table]
    return "/".join(table[v] for v in used) or "off"


def plot_forces(d, title):
    t, on = d["t"], d["brush_on"]
    fig, (ax_f, ax_m) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    for s in (1, -1):  # mu and F_z may change over time: the bound follows them
        ax_f.plot(t, s * d["mu_fz"], "k--", lw=0.7, label="$\\pm\\mu F_z$" if s > 0 else None,
                  **marks(d))
    if on.any():
        lines(ax_f, d, (("brush_fx", "C0", "$F_x$ (along rolling)"), ("brush_fy", "C2", "$F_y$ (left)")))
        lines(ax_m, d, (("brush_mz", "C4", "$M_z$ (about z up)"),))
        label = "$\\pm 2\\sigma$ from the odometry\n(within the friction limit)"
        band(ax_f, t, d["brush_fx"], d["brush_fx_std"], "C0", label, d["mu_fz"])
        band(ax_f, t, d["brush_fy"], d["brush_fy_std"], "C2", None, d["mu_fz"])
        band(ax_m, t, d["brush_mz"], d["brush_mz_std"], "C4", label, d["mu_fz_a"])
    for ax in (ax_f, ax_m):
        shade(ax, t, d["sliding_fraction"] > 0.5, "C3", "mostly sliding\n(sliding fraction > 0.5)")
        shade(ax, t, d["within_noise"], "0.5", "motion within the\nodometry's noise (parked)")
        if not on.any():
            note(ax, "brush model off (brush_model = 0):\nno forces estimated")
    finish(ax_f, "$F_x$, $F_y$ [N]")
    finish(ax_m, "$M_z$ [N m]")
    time_axis(ax_m, t)
    ax_f.set_title("%s: brush forces (model %s)" % (title, names(d["brush_model_used"][on], BRUSH_MODELS)),
                   fontsize=10)
    return fig


def plot_slips(d, title):
    t = d["t"]
    fig, (ax_v, ax_s, ax_p) = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    standstill = d["slips_defined"] == 0
    lines(ax_v, d, (("rolling_speed", "k", "$V_r$"),))
    if standstill.all():
        for ax in (ax_s, ax_p):
            note(ax, "standstill throughout:\nslips and spins undefined")
    else:
        lines(ax_s, d, (("slip_x", "C0", "$\\sigma_x$"), ("slip_y", "C2", "$\\sigma_y$")))
        lines(ax_p, d, (("spin", "k", "$\\varphi$ (total)"), ("spin_tilt", "C1", "$\\varphi_\\gamma$ (tilt)"),
                        ("spin_turn", "C4", "$\\varphi_\\psi$ (turn)")))
    for ax in (ax_v, ax_s, ax_p):
        shade(ax, t, standstill, "0.5", "standstill\n(slips undefined)")
    finish(ax_v, "$V_r$ [m/s]")
    finish(ax_s, "$\\sigma_x$, $\\sigma_y$ [-]" + scale_y(ax_s, [d["slip_x"], d["slip_y"]], 1e-2))
    finish(ax_p, "$\\varphi$ [1/m]" + scale_y(ax_p, [d["spin"], d["spin_tilt"], d["spin_turn"]], 1e-1))
    time_axis(ax_p, t)
    ax_v.set_title("%s: rolling speed, slips and spins" % title, fontsize=10)
    return fig


def plot_rolling_resistance(d, title):
    t, on, regime = d["t"], d["rr_on"], d["rr_regime"]
    fig, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    for ax, key, scale, ylabel in ((axes[0], "rr_mu_roll", 1e3, "$\\mu_{roll}$ [mm]"),
                                   (axes[1], "rr_h", 1e3, "h [mm]"), (axes[2], "rr_force", 1.0, "$F_R$ [N]")):
        y = d[key] * scale
        if on.any():
            ax.plot(t, y, "C0", lw=1, label="static / contact patch", **marks(d))
            if key in ("rr_force", "rr_mu_roll"):  # mu_roll = R F_R / (M g): the same relative spread
                with np.errstate(divide="ignore", invalid="ignore"):
                    relative = np.where(d["rr_force"] != 0, d["rr_force_std"] / np.abs(d["rr_force"]), np.nan)
                band(ax, t, y, np.abs(y) * relative if key == "rr_mu_roll" else d["rr_force_std"], "C0",
                     "$\\pm 2\\sigma$ from the odometry")
        for r, (c, label) in RR_MARKS.items():  # drawn over the base line so the switch stays continuous
            if (regime[on] == r).any():
                ax.plot(t, np.where(regime == r, y, np.nan), c, lw=2, marker=".", ms=3, label=label)
        if not on.any():
            note(ax, "rolling-resistance model off (rr_model = 0):\nnothing estimated")
        finish(ax, ylabel)
    time_axis(axes[2], t)
    axes[0].set_title("%s: rolling resistance (model %s)" % (title, names(d["rr_model"], RR_MODELS)), fontsize=10)
    return fig


def friction_circles(mu_fz):
    """[(radius, label)]: each distinct mu F_z (to 4 significant digits) if few, else the largest."""
    u = np.unique(mu_fz[np.isfinite(mu_fz)])
    r = sorted(set(float("%.4g" % v) for v in u), reverse=True)
    if len(r) <= 4:
        return [(v, "$\\mu F_z$ = %.4g N" % v) for v in r]
    return [(r[0], "largest $\\mu F_z$ = %.4g N\n($\\mu F_z$ varies, %.4g to %.4g N)" % (r[0], r[-1], r[0]))]


def plot_friction_circle(d, title):
    fig, ax = plt.subplots(figsize=(7, 6))
    fx, fy = d["brush_fx"], d["brush_fy"]
    if d["brush_on"].any():
        sc = ax.scatter(fx, fy, c=d["t"], s=4, cmap="viridis", label="estimates (colour: t)")
        parked = d["within_noise"]
        if parked.any():  # circled: forces the noise drives, not the robot's motion
            ax.scatter(fx[parked], fy[parked], s=30, facecolors="none", edgecolors="0.4", lw=0.6,
                       label="motion within the odometry's noise\n(parked: the bristles' response to noise)")
        cax = make_axes_locatable(ax).append_axes("right", size="4%", pad=0.1)  # as tall as the square axes
        fig.colorbar(sc, cax=cax, label="t [s]")
    else:
        note(ax, "brush model off (brush_model = 0):\nno forces estimated")
    a = np.linspace(0, 2 * np.pi, 361)
    circles = friction_circles(d["mu_fz"])
    for (r, label), c in zip(circles, ("k", "C3", "C1", "C4")):
        ax.plot(r * np.cos(a), r * np.sin(a), color=c, ls="--", lw=1, label=label)
    reach = [np.nanmax(np.abs(v)) for v in (fx, fy) if np.isfinite(v).any()] + [r for r, _ in circles]
    lim = 1.25 * max(reach) if reach and max(reach) > 0 else 1.0
    ax.axis([-lim, lim, -lim, lim])
    ax.set_aspect("equal")
    ax.set_xlabel("$F_x$ [N] (along rolling)")
    ax.set_ylabel("$F_y$ [N] (left)")
    ax.grid(alpha=0.3)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper left", fontsize=8)
    ax.set_title("%s: friction circle" % title, fontsize=10)
    return fig


def save(fig, path):
    """Writes fig as PNG, closes it and returns the path."""
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", metavar="CSV", help="per-estimate CSV written by bag_analyze")
    ap.add_argument("--output", metavar="DIR", help="directory for the PNG files (default: the CSV's directory)")
    ap.add_argument("--prefix", metavar="NAME",
                    help="file name prefix of the figures (default: the CSV's base name without extension)")
    ap.add_argument("--start", metavar="T0", type=float, help="plot from this time on, column t [s]")
    ap.add_argument("--end", metavar="T1", type=float, help="plot up to this time, column t [s]")
    a = ap.parse_args()
    if a.start is not None and a.end is not None and a.start > a.end:
        ap.error("--start %g is after --end %g" % (a.start, a.end))

    d = load_csv(a.csv)
    base = os.path.splitext(os.path.basename(a.csv))[0]
    title = base
    if a.start is not None or a.end is not None:
        lo = -np.inf if a.start is None else a.start
        hi = np.inf if a.end is None else a.end
        keep = (d["t"] >= lo) & (d["t"] <= hi)
        if not keep.any():
            raise RuntimeError("%s: no rows with t in [%g, %g] s" % (a.csv, lo, hi))
        d = {k: v[keep] for k, v in d.items()}
        title += ", t = %.4g to %.4g s" % (d["t"][0], d["t"][-1])
    prepare(d)
    out = a.output if a.output is not None else (os.path.dirname(a.csv) or ".")
    os.makedirs(out, exist_ok=True)
    prefix = a.prefix if a.prefix is not None else base

    for name, plot in (("forces", plot_forces), ("slips", plot_slips),
                       ("rolling_resistance", plot_rolling_resistance), ("friction_circle", plot_friction_circle)):
        print("wrote " + save(plot(d, title), os.path.join(out, "%s_%s.png" % (prefix, name))))


if __name__ == "__main__":
    try:
        main()
    except (RuntimeError, OSError) as err:  # unreadable input, unwritable output
        sys.exit("plot_analysis.py: error: %s" % err)
