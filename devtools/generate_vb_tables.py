#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Generate core/include/gendpde/VolumeVBTables.h: the tables behind the V-B integrals.

I(k) = int_0^1 y^2 (1-y)^2/(y^2+k) dy and J(k) = -dI/dk (docs/theory.md section 3) are evaluated from two tables:

- Piecewise polynomials for 1/16 <= k < 16, the range of liquids: 8 octaves, each split into 4 equal
  sub-intervals, on each a polynomial of degree DEGREE in t in [-1, 1] with k = 2^e (1 + (j + (t+1)/2)/4).
  Coefficients are Chebyshev interpolants at 60 digits (from the closed forms, exact at that precision) converted
  to monomials in t and rounded to double. The script checks, at 60 digits, that the rounded polynomials reproduce
  I and J to MAX_RELATIVE_ERROR on a fine grid of every sub-interval, and refuses to write otherwise.
- 24-point Gauss-Legendre quadrature on [0, 1] for k >= 16: for the 12 nodes y_m < 1/2, y_m^2, (1 - y_m)^2 and
  w_m y_m^2 (1 - y_m)^2 (the weight of the mirror node 1 - y_m is the same), at 60 digits, rounded to double.

The final double-precision results are tested independently against quadrature
(python/tests/test_volume_estimators.py).

    .venv/bin/python devtools/generate_vb_tables.py [--degree 13]
"""

import argparse
import pathlib

import mpmath as mp

mp.mp.dps = 60
FIRST_OCTAVE, LAST_OCTAVE, SUBINTERVALS = -4, 3, 4
MAX_RELATIVE_ERROR = 4e-16


def integrals(k):
    """(I, J) from the closed forms, at 60 digits."""
    s = mp.sqrt(k)
    arctangent = mp.atan(1 / s)
    logarithm = mp.log((k + 1) / k)
    i = mp.mpf(1) / 3 - k - (1 - k) * s * arctangent + k * logarithm
    j = mp.mpf(3) / 2 - logarithm + (1 - 3 * k) / (2 * s) * arctangent
    return i, j


def k_of(octave, subinterval, t):
    return mp.mpf(2)**octave * (1 + (subinterval + (t + 1) / 2) / SUBINTERVALS)


def monomial_coefficients(function, degree):
    """Chebyshev interpolant of function(t) on [-1, 1] as monomial coefficients c_0..c_degree in t."""
    nodes = [mp.cos(mp.pi * (m + mp.mpf(1) / 2) / (degree + 1)) for m in range(degree + 1)]
    values = [function(t) for t in nodes]
    chebyshev = [2 * mp.fsum(values[m] * mp.cos(mp.pi * p * (m + mp.mpf(1) / 2) / (degree + 1))
                             for m in range(degree + 1)) / (degree + 1) for p in range(degree + 1)]
    chebyshev[0] /= 2
    # T_p(t) in monomials by the recurrence T_{p+1} = 2 t T_p - T_{p-1}.
    basis = [[mp.mpf(1)], [mp.mpf(0), mp.mpf(1)]]
    for p in range(2, degree + 1):
        previous, current = basis[p - 2], basis[p - 1]
        basis.append([(2 * current[q - 1] if q > 0 else 0) - (previous[q] if q < len(previous) else 0)
                      for q in range(p + 1)])
    coefficients = [mp.mpf(0)] * (degree + 1)
    for p in range(degree + 1):
        for q, b in enumerate(basis[p]):
            coefficients[q] += chebyshev[p] * b
    return [float(c) for c in coefficients]


def horner(coefficients, t):
    value = mp.mpf(0)
    for c in reversed(coefficients):
        value = value * t + mp.mpf(c)
    return value


def fit(degree):
    table, worst = [], 0.0
    for octave in range(FIRST_OCTAVE, LAST_OCTAVE + 1):
        for subinterval in range(SUBINTERVALS):
            pieces = []
            for which in (0, 1):
                pieces.append(monomial_coefficients(lambda t: integrals(k_of(octave, subinterval, t))[which], degree))
            for t in [mp.mpf(-1) + 2 * mp.mpf(m) / 64 for m in range(65)]:
                exact = integrals(k_of(octave, subinterval, t))
                for which in (0, 1):
                    worst = max(worst, float(abs(horner(pieces[which], t) / exact[which] - 1)))
            table.append(pieces)
    return table, worst


def gauss_legendre_half(points=24):
    """(y^2, (1-y)^2, w y^2 (1-y)^2) for the points/2 nodes y < 1/2 of the points-point rule on [0, 1]."""
    nodes = []
    for m in range(1, points + 1):
        x = mp.cos(mp.pi * (m - mp.mpf(1) / 4) / (points + mp.mpf(1) / 2))   # initial guess, then Newton
        for _ in range(100):
            p0, p1 = mp.mpf(1), x
            for n in range(2, points + 1):
                p0, p1 = p1, ((2 * n - 1) * x * p1 - (n - 1) * p0) / n
            derivative = points * (x * p1 - p0) / (x * x - 1)
            step = p1 / derivative
            x -= step
            if abs(step) < mp.mpf(10)**(-mp.mp.dps + 5):
                break
        p0, p1 = mp.mpf(1), x
        for n in range(2, points + 1):
            p0, p1 = p1, ((2 * n - 1) * x * p1 - (n - 1) * p0) / n
        derivative = points * (x * p1 - p0) / (x * x - 1)
        weight = 2 / ((1 - x * x) * derivative**2)
        nodes.append(((1 - x) / 2, weight / 2))   # on [0, 1]; cos decreasing, so y increases with m
    half = sorted(nodes)[:points // 2]
    total = 2 * mp.fsum(w * y**2 * (1 - y)**2 for y, w in half)
    if abs(total * 30 - 1) > mp.mpf(10)**-50:   # the rule integrates y^2 (1-y)^2 exactly: 1/30
        raise SystemExit(f"Gauss-Legendre check failed: {total}")
    return [(float(y**2), float((1 - y)**2), float(w * y**2 * (1 - y)**2)) for y, w in half]


def c_array(name, values, per_line=4):
    rows = [", ".join(repr(v) for v in values[k:k + per_line]) for k in range(0, len(values), per_line)]
    return [f"inline constexpr double {name}[{len(values)}] = {{"] + [f"    {row}," for row in rows] + ["};"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--degree", type=int, default=13)
    parser.add_argument("--check-only", action="store_true", help="print the error for degrees 9..16")
    args = parser.parse_args()
    if args.check_only:
        for degree in range(9, 17):
            print(degree, f"{fit(degree)[1]:.2e}")
        return
    table, worst = fit(args.degree)
    if worst > MAX_RELATIVE_ERROR:
        raise SystemExit(f"degree {args.degree}: max relative error {worst:.2e} > {MAX_RELATIVE_ERROR}")
    quadrature = gauss_legendre_half()
    lines = [
        "/* SPDX-License-Identifier: MIT",
        " * Copyright (c) 2026 The openmm-gendpde developers */",
        "/* Generated by devtools/generate_vb_tables.py; do not edit. */",
        "#ifndef GENDPDE_VOLUME_VB_TABLES_H_",
        "#define GENDPDE_VOLUME_VB_TABLES_H_",
        "",
        "namespace GenDPDEPlugin {",
        "namespace Physics {",
        "",
        "namespace VolumeVBPolynomials {",
        "",
        f"/* k in [2^{FIRST_OCTAVE}, 2^{LAST_OCTAVE + 1}): octave e, sub-interval j of {SUBINTERVALS}, local t in "
        "[-1, 1]:",
        f"   k = 2^e (1 + (j + (t+1)/2)/{SUBINTERVALS}). coefficients[(e - ({FIRST_OCTAVE}))*{SUBINTERVALS} + j][p] = "
        "{c_p of I, c_p of J}, powers t^p.",
        f"   Max relative error of the rounded coefficients (exact evaluation): {worst:.2e}. */",
        f"constexpr int firstOctave = {FIRST_OCTAVE}, lastOctave = {LAST_OCTAVE}, subintervals = {SUBINTERVALS}, "
        f"degree = {args.degree};",
        f"alignas(16) inline constexpr double coefficients[{len(table)}][{args.degree + 1}][2] = {{",
    ]
    for index, (piece_i, piece_j) in enumerate(table):
        octave, subinterval = FIRST_OCTAVE + index // SUBINTERVALS, index % SUBINTERVALS
        lines.append(f"    {{ // octave {octave}, sub-interval {subinterval}")
        for a, b in zip(piece_i, piece_j):
            lines.append(f"        {{{a!r}, {b!r}}},")
        lines.append("    },")
    lines += ["};", "", "} // namespace VolumeVBPolynomials", "",
              "namespace VolumeVBQuadrature {", "",
              f"/* {2 * len(quadrature)}-point Gauss-Legendre rule on [0, 1] for the positive integrands of I and J; "
              "the",
              "   nodes come in mirror pairs y_m, 1 - y_m (y_m < 1/2) with one weight w_m each. Twice the sum of the",
              "   coefficients is 1/30 = int_0^1 y^2 (1-y)^2 dy, which the rule integrates exactly. */",
              f"constexpr int numPairs = {len(quadrature)};",
              "/** y_m^2 */"]
    lines += c_array("nodeSquared", [q[0] for q in quadrature])
    lines += ["/** (1 - y_m)^2 */"] + c_array("mirrorNodeSquared", [q[1] for q in quadrature])
    lines += ["/** w_m y_m^2 (1 - y_m)^2 */"] + c_array("coefficient", [q[2] for q in quadrature])
    lines += ["", "} // namespace VolumeVBQuadrature", "", "} // namespace Physics", "} // namespace GenDPDEPlugin",
              "", "#endif /*GENDPDE_VOLUME_VB_TABLES_H_*/", ""]
    output = pathlib.Path(__file__).resolve().parents[1] / "core/include/gendpde/VolumeVBTables.h"
    output.write_text("\n".join(lines))
    print(f"wrote {output} (degree {args.degree}, {len(table)} sub-intervals, max relative error {worst:.2e}; "
          f"{2 * len(quadrature)}-point Gauss-Legendre)")


if __name__ == "__main__":
    main()
