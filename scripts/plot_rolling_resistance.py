#!/usr/bin/env python3
"""Reproduce Figs. 2 and 3 of Poeschel, Schwager, Brilliantov from the contact_eval CLI.

Fig. 2: penetration depth h(v); Fig. 3: rolling-friction coefficient mu_roll(v). Solid: the exact
solution of eq. 18; dashed: the small-velocity expansions (eqs. 24 and 27). A third figure follows the
exact solution through the critical speed into the point-contact regime (note 13).

Usage: plot_rolling_resistance.py --output DIR [--config YAML] [--contact-eval PATH] [--vmax V]
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import yaml  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # also when run through rosrun's wrapper
from contact_eval_tool import contact_eval_command, run_json  # noqa: E402

# config key -> contact_eval flag
FLAGS = {
    "rolling_radius": "--radius",
    "mass_per_length": "--mass-per-length",
    "surface_stiffness": "--stiffness",
    "surface_damping": "--damping",
    "surface_density": "--surface-density",
    "gravity": "--g",
    "effective_length": "--length",
}


def run(cmd, params, *args):
    flags = []
    for key, flag in FLAGS.items():
        if key in params:
            flags += [flag, repr(float(params[key]))]
    return run_json(cmd, ["cylinder"] + flags + list(args))


def column(rows, key, scale=1.0):
    return [r[key] * scale if r[key] is not None else float("nan") for r in rows]


def finish(ax, fig, ylabel, title, vmax, legend_size=None):
    """Axes of the paper's Figs. 2 and 3: speed from 0 to vmax, quantity from 0."""
    ax.set_xlabel("v [m/s]")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.set_xlim(0, vmax)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=legend_size)
    fig.tight_layout()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--output", required=True, help="directory for the PNG files")
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--config", default=os.path.join(here, "..", "config", "rubber_cylinder_paper.yaml"))
    ap.add_argument("--contact-eval", default=None, help="path to the contact_eval executable")
    ap.add_argument("--vmax", type=float, default=1.5, help="upper speed of Figs. 2 and 3 [m/s]")
    ap.add_argument("--points", type=int, default=301)
    a = ap.parse_args()

    with open(a.config) as f:
        params = yaml.safe_load(f)
    cmd = contact_eval_command(a.contact_eval)
    os.makedirs(a.output, exist_ok=True)

    sweep = ["--sweep", "0", repr(a.vmax), str(a.points)]
    exact = run(cmd, params, *sweep, "--model", "exact")
    expansion = run(cmd, params, *sweep, "--model", "expansion")
    peak = run(cmd, params, "--peak", "--model", "exact")
    v = column(exact, "v")
    # The truncated series turns unphysical (h < 0, mu < 0) and is clamped there: do not draw that part.
    physical = [r["h"] > 0 and r["mu_roll"] > 0 or r["v"] == 0 for r in expansion]
    v_exp = [x for x, ok in zip(v, physical) if ok]

    s = exact[0]
    v_star, mu_star, v_c = s["v_star"], s["mu_star"], s["v_critical"]

    # Fig. 2: h(v)
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.plot(v, column(exact, "h", 1e3), "k-", label="exact, eq. 18")
    ax.plot(v_exp, [x for x, ok in zip(column(expansion, "h", 1e3), physical) if ok], "k--",
            label="expansion, eq. 24")
    finish(ax, fig, "h [mm]", "Fig. 2: penetration depth", a.vmax)
    fig2 = os.path.join(a.output, "fig2_penetration_depth.png")
    fig.savefig(fig2, dpi=150)

    # Fig. 3: mu_roll(v)
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.plot(v, column(exact, "mu_roll", 1e3), "k-", label="exact, eq. 18 with eq. 17")
    ax.plot(v_exp, [x for x, ok in zip(column(expansion, "mu_roll", 1e3), physical) if ok], "k--",
            label="expansion, eq. 27")
    if v_star is not None:
        ax.plot([v_star], [mu_star * 1e3], "o", mfc="none", mec="C0",
                label="$\\mu^*_{roll}$, $v^*$ (eqs. 28, 29): %.4g mm at %.4g m/s" % (mu_star * 1e3, v_star))
    ax.plot([peak["v"]], [peak["mu_roll"] * 1e3], "s", mfc="none", mec="C3",
            label="exact maximum: %.4g mm at %.4g m/s" % (peak["mu_roll"] * 1e3, peak["v"]))
    finish(ax, fig, "$\\mu_{roll}$ [mm]", "Fig. 3: rolling-friction coefficient", a.vmax, legend_size=8)
    fig3 = os.path.join(a.output, "fig3_rolling_friction.png")
    fig.savefig(fig3, dpi=150)

    # Beyond the paper's figures: through the critical speed (log axes).
    v_hi = 5 * v_c if v_c is not None else 100 * a.vmax
    wide = run(cmd, params, "--sweep", repr(1e-3), repr(v_hi), "600", "--log", "--model", "exact")
    vw = column(wide, "v")
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    patch = [r["regime"] == "contact_patch" for r in wide]
    for ax, key, label in ((ax1, "h", "h [m]"), (ax2, "mu_roll", "$\\mu_{roll}$ [m]")):
        y = column(wide, key)
        ax.loglog([x for x, p in zip(vw, patch) if p], [x for x, p in zip(y, patch) if p], "k-",
                  label="contact patch")
        ax.loglog([x for x, p in zip(vw, patch) if not p], [x for x, p in zip(y, patch) if not p], "C3-",
                  label="point contact (note 13)")
        if v_c is not None:
            ax.axvline(v_c, color="gray", ls=":", lw=1)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3, which="both")
    ax1.set_title("Through the critical speed $v_c$ = %.3g m/s" % v_c if v_c else "Exact solution")
    ax1.legend(fontsize=8)
    ax2.set_xlabel("v [m/s]")
    fig.tight_layout()
    fig_c = os.path.join(a.output, "critical_speed.png")
    fig.savefig(fig_c, dpi=150)

    print("rolling resistance of the cylinder (%s)" % os.path.basename(a.config))
    print("  static: xi_+^(0) = %.6g m (eq. 22), h_0 = %.6g m (eq. 25)" % (s["xi_plus_static"], s["h_static"]))
    if v_star is not None:
        print("  expansion maximum: mu*_roll = %.6g m at v* = %.6g m/s (eqs. 28, 29)" % (mu_star, v_star))
    print("  exact maximum:     mu_roll   = %.6g m at v  = %.6g m/s" % (peak["mu_roll"], peak["v"]))
    if v_c is not None:
        print("  critical speed v_c = %.6g m/s: the contact closes to a line, point contact beyond" % v_c)
    for path in (fig2, fig3, fig_c):
        print("  wrote " + path)


if __name__ == "__main__":
    try:
        main()
    except RuntimeError as err:
        sys.exit(str(err))
