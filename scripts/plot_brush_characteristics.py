#!/usr/bin/env python3
"""Reproduce Fig. 4 (a)-(c) of Romano et al. 2022 (brush theory of spherical wheels) from the contact_eval CLI.

Steady-state characteristics of a rolling spherical wheel with limited friction (Sect. 6), for several
lateral slips sigma_y with the longitudinal slip sigma_x swept over [-1, 1], under both sliding laws side by
side: left, the approximation Sect. 6 uses for its sketches (a sliding bristle's stress along the rigid sliding
velocity), which is what the paper's Fig. 4 shows; right, the paper's law, eq. (4b) (the stress opposes the
bristle tip's full sliding velocity), the package's default:
  Fig. 4(a): tangential forces F_x and F_y versus sigma_x;
  Fig. 4(b): self-aligning moment M_z versus sigma_x;
  Fig. 4(c): F_y versus F_x, with the friction circle of radius mu F_z.
Solid lines: the rolling sphere of Sect. 3; dashed lines: the rolling and tilting sphere of Sect. 4
(contact_eval brush --tilt --tilt-ratio chi_gamma). The paper reports that the two nearly coincide.
Parameters of the paper: phi = 3.33 1/m, chi_gamma = 0.9, F_z = 3000 N, a = 0.05 m, k = 1.023e8 N/m^3,
mu = 1, parabolic pressure. The paper does not list its sigma_y values; 0, 0.05, 0.1, 0.2 are used.
Forces and moment are in the paper frame (SAE, z down) as printed by contact_eval.

Usage: plot_brush_characteristics.py --output DIR [--contact-eval PATH] [--points N] [--resolution N]
                                     [--sliding-law both|rigid|coulomb]
"""
import argparse
import concurrent.futures
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # also when run through rosrun's wrapper
from contact_eval_tool import contact_eval_command, run_json  # noqa: E402

# Fig. 4 of the paper (Sect. 6)
PAPER = {
    "phi": 3.33,            # total tilt spin [1/m]
    "tilt_ratio": 0.9,      # chi_gamma
    "load": 3000.0,         # F_z [N]
    "patch_radius": 0.05,   # a [m]
    "stiffness": 1.023e8,   # k [N/m^3]
    "friction": 1.0,        # mu
}
SIGMA_Y = (0.0, 0.05, 0.1, 0.2)
LAW_TITLES = {"rigid": "rigid sliding direction (Sect. 6, as the paper's Fig. 4)",
              "coulomb": "Coulomb's law, eq. (4b) (the default)"}


def brush_args(sigma_x, sigma_y, tilt, resolution, params, law):
    args = ["brush", "--model", "steady", "--sliding-law", law,
            "--sigma-x", repr(float(sigma_x)), "--sigma-y", repr(float(sigma_y)),
            "--phi", repr(params["phi"]),
            "--patch-radius", repr(params["patch_radius"]), "--stiffness", repr(params["stiffness"]),
            "--load", repr(params["load"]), "--friction", repr(params["friction"]),
            "--resolution", str(resolution)]
    if tilt:
        args += ["--tilt", "--tilt-ratio", repr(params["tilt_ratio"])]
    return args


def sweep(cmd, sigma_x, sigma_ys, resolution, params, law):
    """{(tilt, sigma_y): {"Fx": array, "Fy": array, "Mz": array}} over sigma_x under one law, CLI calls in parallel."""
    jobs = [(tilt, sy, i, sx) for tilt in (False, True) for sy in sigma_ys for i, sx in enumerate(sigma_x)]
    rows = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=os.cpu_count() or 4) as pool:
        futures = {pool.submit(run_json, cmd, brush_args(sx, sy, tilt, resolution, params, law)): (tilt, sy, i)
                   for tilt, sy, i, sx in jobs}
        try:
            for fut in concurrent.futures.as_completed(futures):
                rows[futures[fut]] = fut.result()
        except RuntimeError as err:
            for f in futures:
                f.cancel()
            sys.exit(str(err))
    curves = {}
    warnings = set()
    for tilt in (False, True):
        for sy in sigma_ys:
            r = [rows[(tilt, sy, i)] for i in range(len(sigma_x))]
            curves[(tilt, sy)] = {k: np.array([x[k] for x in r], dtype=float) for k in ("Fx", "Fy", "Mz")}
            curves[(tilt, sy)]["valid"] = all(x.get("valid", True) for x in r)
            for x in r:
                warnings.update(x.get("warnings") or [])
    return curves, sorted(warnings)


def style_legend(ax, sigma_ys, colours, extra=()):
    """Colour per sigma_y; solid = Sect. 3, dashed = Sect. 4."""
    handles = [plt.Line2D([], [], color=c, lw=1.5, label="$\\sigma_y$ = %g" % sy) for sy, c in zip(sigma_ys, colours)]
    handles += [plt.Line2D([], [], color="k", ls="-", label="rolling (Sect. 3)"),
                plt.Line2D([], [], color="k", ls="--", label="rolling + tilting (Sect. 4)")]
    handles += list(extra)
    ax.legend(handles=handles, fontsize=7)


def plot_forces(ax_x, ax_y, sigma_x, curves, sigma_ys, colours, mu_fz):
    for sy, c in zip(sigma_ys, colours):
        for tilt, ls in ((False, "-"), (True, "--")):
            ax_x.plot(sigma_x, curves[(tilt, sy)]["Fx"], color=c, ls=ls, lw=1.3)
            ax_y.plot(sigma_x, curves[(tilt, sy)]["Fy"], color=c, ls=ls, lw=1.3)
    for ax, name in ((ax_x, "$F_x$ [N]"), (ax_y, "$F_y$ [N]")):
        for s in (1, -1):
            ax.axhline(s * mu_fz, color="gray", ls=":", lw=0.8)
        ax.set_ylabel(name)
        ax.set_xlim(sigma_x[0], sigma_x[-1])
        ax.grid(alpha=0.3)
    ax_y.set_xlabel("$\\sigma_x$ [-]")
    style_legend(ax_x, sigma_ys, colours,
                 [plt.Line2D([], [], color="gray", ls=":", lw=0.8, label="$\\pm\\mu F_z$")])


def plot_moment(ax, sigma_x, curves, sigma_ys, colours):
    for sy, c in zip(sigma_ys, colours):
        for tilt, ls in ((False, "-"), (True, "--")):
            ax.plot(sigma_x, curves[(tilt, sy)]["Mz"], color=c, ls=ls, lw=1.3)
    ax.set_xlabel("$\\sigma_x$ [-]")
    ax.set_ylabel("$M_z$ [N m]")
    ax.set_xlim(sigma_x[0], sigma_x[-1])
    ax.grid(alpha=0.3)
    style_legend(ax, sigma_ys, colours)


def plot_circle(ax, curves, sigma_ys, colours, mu_fz):
    t = np.linspace(0, 2 * np.pi, 361)
    ax.plot(mu_fz * np.cos(t), mu_fz * np.sin(t), color="gray", ls=":", lw=1.0)
    for sy, c in zip(sigma_ys, colours):
        for tilt, ls in ((False, "-"), (True, "--")):
            ax.plot(curves[(tilt, sy)]["Fx"], curves[(tilt, sy)]["Fy"], color=c, ls=ls, lw=1.3)
    ax.set_xlabel("$F_x$ [N]")
    ax.set_ylabel("$F_y$ [N]")
    ax.set_aspect("equal")
    lim = 1.1 * mu_fz
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.grid(alpha=0.3)
    style_legend(ax, sigma_ys, colours,
                 [plt.Line2D([], [], color="gray", ls=":", label="friction circle $\\mu F_z$")])


def save(fig, directory, name):
    """Writes fig as directory/name (PNG, 150 dpi), closes it and returns the path."""
    fig.tight_layout()
    path = os.path.join(directory, name)
    fig.savefig(path, dpi=150)
    plt.close(fig)
    return path


def summarise(curves, sigma_ys, mu_fz):
    """Largest utilisation, and the largest tilt - no tilt differences (F over mu F_z, M_z in N m)."""
    utilisation = max(float(np.max(np.hypot(c["Fx"], c["Fy"]))) for c in curves.values()) / mu_fz
    diff = {key: max(float(np.max(np.abs(curves[(True, sy)][key] - curves[(False, sy)][key]))) for sy in sigma_ys)
            for key in ("Fx", "Fy", "Mz")}
    return utilisation, diff


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--output", required=True, help="directory for the PNG files")
    ap.add_argument("--contact-eval", default=None, help="path to the contact_eval executable")
    ap.add_argument("--points", type=int, default=81, help="number of sigma_x values in [-1, 1]")
    ap.add_argument("--resolution", type=int, default=64, help="contact_eval --resolution (steady model)")
    ap.add_argument("--sliding-law", choices=("both", "rigid", "coulomb"), default="both",
                    help="both side by side (default), or one")
    a = ap.parse_args()
    if a.points < 2:
        ap.error("--points must be at least 2")

    cmd = contact_eval_command(a.contact_eval)
    os.makedirs(a.output, exist_ok=True)
    params = dict(PAPER)
    mu_fz = params["friction"] * params["load"]
    sigma_x = np.linspace(-1.0, 1.0, a.points)
    sigma_ys = SIGMA_Y
    colours = ["C%d" % i for i in range(len(sigma_ys))]
    laws = ("rigid", "coulomb") if a.sliding_law == "both" else (a.sliding_law,)

    curves, warnings = {}, set()
    for law in laws:
        curves[law], w = sweep(cmd, sigma_x, sigma_ys, a.resolution, params, law)
        warnings.update(w)
    subtitle = "$\\varphi$ = %g 1/m, $\\chi_\\gamma$ = %g, $F_z$ = %g N, a = %g m, $\\mu$ = %g" % (
        params["phi"], params["tilt_ratio"], params["load"], params["patch_radius"], params["friction"])
    n = len(laws)

    # Fig. 4(a): F_x and F_y versus sigma_x, a column per law
    fig, axes = plt.subplots(2, n, figsize=(6.5 * n, 7), sharex=True, sharey="row", squeeze=False)
    for j, law in enumerate(laws):
        plot_forces(axes[0][j], axes[1][j], sigma_x, curves[law], sigma_ys, colours, mu_fz)
        axes[0][j].set_title(LAW_TITLES[law], fontsize=10)
    fig.suptitle("Fig. 4(a): tangential forces vs longitudinal slip\n" + subtitle, fontsize=10)
    fig_a = save(fig, a.output, "fig4a_forces.png")

    # Fig. 4(b): M_z versus sigma_x
    fig, axes = plt.subplots(1, n, figsize=(6.5 * n, 4.8), sharey=True, squeeze=False)
    for j, law in enumerate(laws):
        plot_moment(axes[0][j], sigma_x, curves[law], sigma_ys, colours)
        axes[0][j].set_title(LAW_TITLES[law], fontsize=10)
    fig.suptitle("Fig. 4(b): self-aligning moment vs longitudinal slip\n" + subtitle, fontsize=10)
    fig_b = save(fig, a.output, "fig4b_moment.png")

    # Fig. 4(c): F_y versus F_x, friction circle
    fig, axes = plt.subplots(1, n, figsize=(6 * n, 6.4), squeeze=False)
    for j, law in enumerate(laws):
        plot_circle(axes[0][j], curves[law], sigma_ys, colours, mu_fz)
        axes[0][j].set_title(LAW_TITLES[law], fontsize=10)
    fig.suptitle("Fig. 4(c): friction circle\n" + subtitle, fontsize=10)
    fig_c = save(fig, a.output, "fig4c_friction_circle.png")

    print("Fig. 4 of Romano et al. 2022: %d sigma_x points x %d sigma_y x 2 models x %s, resolution %d"
          % (a.points, len(sigma_ys), " and ".join(laws), a.resolution))
    for path in (fig_a, fig_b, fig_c):
        print("  wrote " + path)
    for law in laws:
        utilisation, diff = summarise(curves[law], sigma_ys, mu_fz)
        mz_max = max(float(np.max(np.abs(c["Mz"]))) for c in curves[law].values())
        print("  %s: largest |F_t| / (mu F_z) = %.6f%s" % (law, utilisation, "" if utilisation <= 1 + 1e-6 else "  (EXCEEDS 1)"))
        print("  %s: largest |tilt - no tilt| / (mu F_z): F_x %.4g, F_y %.4g; M_z %.4g N m (max |M_z| %.4g N m)"
              % (law, diff["Fx"] / mu_fz, diff["Fy"] / mu_fz, diff["Mz"], mz_max))
    if n == 2:
        # how far the laws are apart on these curves: max(|dF_x|, |dF_y|, |dM_z| / a) / (mu F_z) per point
        a_ = params["patch_radius"]
        gaps = []
        for key in curves["rigid"]:
            r, c = curves["rigid"][key], curves["coulomb"][key]
            gaps.append(np.maximum.reduce([np.abs(r["Fx"] - c["Fx"]), np.abs(r["Fy"] - c["Fy"]),
                                           np.abs(r["Mz"] - c["Mz"]) / a_]) / mu_fz)
        gaps = np.concatenate(gaps)
        print("  eq. (4b) - rigid: median %.3g, largest %.3g of mu F_z over these curves" % (np.median(gaps), gaps.max()))
    for law in laws:
        invalid = [(t, sy) for (t, sy), c in curves[law].items() if not c["valid"]]
        if invalid:
            print("  %s: curves with invalid points: " % law + ", ".join(
                "%s sigma_y=%g" % ("tilt" if t else "no tilt", sy) for t, sy in invalid))
    if warnings:
        print("  contact_eval warnings: " + "; ".join(sorted(warnings)))


if __name__ == "__main__":
    main()
