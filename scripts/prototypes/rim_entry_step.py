#!/usr/bin/env python3
"""A prototype, not the library's code (built since as lattice::RimEntry, by another quadrature: src/core/brush/lattice/
rim_entry.h): an entry step for a bristle sliding in from the rim under eq. (4b).

docs/speed_and_accuracy.md (the lead of 2026-12-02): a bristle entering at the leading edge under the parabolic
pressure has lambda = |w| / b ~ kappa / s near the rim, kappa = |w| / b'(0) of 1-4 where it slides from its entry, and
the exponential step's answer, -r(d), lags the true T = tan(delta / 2) (delta its angle from the drive) by about
1 / (kappa + 1) whatever the step's length. Since lambda r = omega / 2, from the rim (e^{-Lambda} = 0)
    T(d) = -int_0^d exp(-(Lambda(d) - Lambda(s))) omega(s) / 2 (1 + T(s)^2) ds,   omega = (w x w') / |w|^2,
which this evaluates by Gauss-Legendre in u = sqrt(s / d) (graded towards the rim, where the kernel goes as s^kappa),
the T^2 term by two fixed-point passes with T taken at the end (crude: it limits the accuracy where |T| ~ 0.1), and
compares with the exponential step's -r(d) and with the truth, scipy's Radau from the rim at rtol 1e-12.

Nondimensional: a = 1, the bound at the centre c = 1 (b = t = 1 - |x|^2), rolling speed 1, spin up to 3, sliding up to
3; entries with kappa in (1, 4). Lambda(d) - Lambda(s) by scipy's quad here (RimIntegral's closed form in the library).

Usage: rim_entry_step.py [--cases 12] [--seed 5] [--spans 0.05 0.2] [--nodes 3 4 6 8]
"""
import argparse

import numpy as np
from scipy.integrate import quad, solve_ivp

J = np.array([[0.0, -1.0], [1.0, 0.0]])


def entry_case(rng):
    """A random drive and a point of the leading rim whose bristle slides from its entry with kappa in (1, 4)."""
    while True:
        heading = rng.uniform(0, 2 * np.pi)
        V = np.array([np.cos(heading), np.sin(heading)])
        phi = heading + rng.uniform(-0.45, 0.45) * np.pi
        x0 = np.array([np.cos(phi), np.sin(phi)])
        om = rng.uniform(-3, 3)
        slide_heading = rng.uniform(0, 2 * np.pi)
        V_s = rng.uniform(0, 3) * np.array([np.cos(slide_heading), np.sin(slide_heading)])
        c = {"x": lambda s, x0=x0, V=V: x0 - V * s, "om": om, "V": V}
        c["w"] = lambda s, c=c, V_s=V_s, om=om: -V_s - om * (J @ c["x"](s))
        c["b"] = lambda s, c=c: 1.0 - c["x"](s) @ c["x"](s)
        c["kappa"] = np.linalg.norm(c["w"](0.0)) / (2.0 * x0 @ V)  # |w| / b'(0)
        if 1.0 < c["kappa"] < 4.0:
            return c


def angle_to_T(theta, w):
    delta = (theta - np.arctan2(w[1], w[0]) + np.pi) % (2 * np.pi) - np.pi
    return np.tan(0.5 * delta)


def truth(c, d):
    w, b = c["w"], c["b"]
    theta0 = np.arctan2(w(0.0)[1], w(0.0)[0])
    rate = lambda s, th: [(-np.sin(th[0]) * w(s)[0] + np.cos(th[0]) * w(s)[1]) / b(s)]
    r = solve_ivp(rate, [1e-10, d], [theta0], method="Radau", rtol=1e-12, atol=1e-14)
    return angle_to_T(r.y[0, -1], w(d))


def omega(c, s):
    w, w_dot = c["w"](s), c["om"] * (J @ c["V"])
    return (w[0] * w_dot[1] - w[1] * w_dot[0]) / (w @ w)


def entry_step(c, d, nodes):
    lam = lambda s: np.linalg.norm(c["w"](s)) / c["b"](s)
    x, weights = np.polynomial.legendre.leggauss(nodes)
    u, wu = 0.5 * (x + 1.0), 0.5 * weights
    T = 0.0
    for _ in range(2):
        total = 0.0
        for ui, wi in zip(u, wu):
            s = d * ui * ui
            decay = np.exp(-quad(lam, s, d, epsabs=1e-14, epsrel=1e-13, limit=200)[0])
            total += wi * 2.0 * d * ui * decay * omega(c, s) / 2.0 * (1.0 + T * T)
        T = -total
    return T


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", type=int, default=12)
    ap.add_argument("--seed", type=int, default=5)
    ap.add_argument("--spans", type=float, nargs="+", default=[0.05, 0.2])
    ap.add_argument("--nodes", type=int, nargs="+", default=[3, 4, 6, 8])
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    for _ in range(a.cases):
        c = entry_case(rng)
        for d in a.spans:
            if np.linalg.norm(c["x"](d)) >= 1.0:
                continue  # across the patch within the span
            T = truth(c, d)
            lam_d = np.linalg.norm(c["w"](d)) / c["b"](d)
            exponential = -omega(c, d) / (2.0 * lam_d)  # the exponential step from the rim (E = 0), T^2 left out
            errors = " ".join("%.1e" % abs(entry_step(c, d, n) - T) for n in a.nodes)
            print("kappa %.2f  d %.2f  T %+.3e  |error| exponential step %.1e, entry step at %s nodes: %s"
                  % (c["kappa"], d, T, abs(exponential - T), ",".join(map(str, a.nodes)), errors))


if __name__ == "__main__":
    main()
