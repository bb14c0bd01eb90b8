#!/usr/bin/env python3
"""Why the transient lattice's estimate is so far above its error where the robot spins in place or parks.

Parked or spinning in place, the bristles slide towards the drive w = -V_s - omega_z J x (eq. 1), whose zero, the
spin pole x_c, lies within the patch: the deflection field there is u = b(x) w / |w|, which turns by 180 degrees
across x_c. That point discontinuity makes the lattice sum's error O(h^2) with a coefficient set by where x_c falls
between the lattice points. The estimate (BrushTransient::sums) measures the error through the four sub-lattices of
twice the spacing, which see the pole at four other offsets, and takes kSpreadFactor (3) times their spread, twice
where the lattice has seen no other phase (kUnseenPhases: parked, spinning in place).

This script builds that field alone on the package's lattice (resolution n across the diameter 2a, n + 6 points a
side, the parabolic pressure, the sum of q_z normalised to its integral as the package does) at random pole
positions and lattice offsets, and prints the sub-lattices' spread and the full lattice's error against resolution
256, both in units of mu F_z; and the same field without a pole (its direction uniform) for comparison.

Usage: pole_spread.py [--resolution 32] [--samples 200] [--seed 1]
"""
import argparse

import numpy as np


def lattice_sums(n, pole, offset):
    """(F_x, F_y, M_z / a) of the field over the full lattice and its four sub-lattices, over mu F_z (a = 1)."""
    h, w = 2.0 / n, n + 6
    c0 = 0.5 * (w - 1)
    i = np.arange(w)
    X, Y = np.meshgrid((i - c0) * h + offset[0], (i - c0) * h + offset[1], indexing="xy")
    I, J = np.meshgrid(i, i, indexing="xy")
    t = 1.0 - X**2 - Y**2
    inside = t > 0.0
    q = np.where(inside, t, 0.0)  # the parabolic pressure's shape; the bound b is mu q / k
    if pole is None:
        ex, ey = np.ones_like(X), np.zeros_like(X)
    else:
        dx, dy = X - pole[0], Y - pole[1]
        r = np.maximum(np.hypot(dx, dy), 1e-300)
        ex, ey = -dy / r, dx / r  # the drive's direction around the pole (a spin)
    ux, uy = q * ex, q * ey
    total = 0.5 * np.pi  # the integral of q over the unit disc
    sums = []
    for k in range(5):
        m = inside if k == 0 else inside & (I % 2 == (k - 1) % 2) & (J % 2 == (k - 1) // 2)
        weight = total / q[m].sum()
        sums.append([ux[m].sum() * weight, uy[m].sum() * weight, (X * uy - Y * ux)[m].sum() * weight])
    return np.array(sums) / total


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--resolution", type=int, default=32)
    ap.add_argument("--samples", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    h = 2.0 / args.resolution
    for label, with_pole in (("pole within the patch", True), ("no pole (uniform direction)", False)):
        spread, error = [], []
        for _ in range(args.samples):
            pole = (rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)) if with_pole else None
            s = lattice_sums(args.resolution, pole, (rng.uniform(0.0, h), rng.uniform(0.0, h)))
            reference = lattice_sums(256, pole, (0.0, 0.0))[0]
            spread.append(np.abs(s[1:] - s[0]).max())
            error.append(np.abs(s[0] - reference).max())
        spread, error = np.array(spread), np.array(error)
        ratio = spread / np.maximum(error, 1e-300)
        print("%s, resolution %d, %d samples:" % (label, args.resolution, args.samples))
        print("  sub-lattices' spread  median %.2e  max %.2e" % (np.median(spread), spread.max()))
        print("  full lattice's error  median %.2e  max %.2e  (against 256)" % (np.median(error), error.max()))
        print("  spread / error        median %.1f  min %.1f" % (np.median(ratio), ratio.min()))


if __name__ == "__main__":
    main()
