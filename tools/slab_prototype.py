"""A numpy prototype for screening density estimators on a free slab before writing them in C++ (docs/interfaces.md).

    .venv/bin/python tools/slab_prototype.py VB 1.35 0 100      # estimator, f_cut, alpha, duration (time units)
    .venv/bin/python tools/slab_prototype.py VC 1.57 2 100
    .venv/bin/python tools/slab_prototype.py VC 1.35 3 100 0.4   # with the threshold t = 0.4 (the plugin's VC)
    .venv/bin/python tools/slab_prototype.py --bulk-run VC 1.35 3 100 0.4   # bulk n* = 1 under VC's own dynamics
    .venv/bin/python tools/slab_prototype.py VF 1.2 1.5 100     # f_cut = 1.2 + 1.5 (n0* - 0.6)
    .venv/bin/python tools/slab_prototype.py --bulk VC 2 1.45 1.57 1.65   # mean n_i of bulk liquids at n* = 0.82, 1

Reduced argon units (m = L = u = k_B = 1; T0* = 0.011054, pi0* = 0.116056, B_T* = 1/6, gamma_T = 6, R* = 1.6839).
The slab: 1000 particles on an FCC lattice at n* = 0.82, 5 x 5 x 10 cells, in a box three times as long; dynamics
velocity Verlet (dt* = 0.01) with an explicit DPD thermostat at T0 (gamma* = 7.37) - not GenDPDE's Shardlow
sweep, which is enough to tell whether a slab holds. Prints the core's true density and mean n_i every 10 time units.

Estimators: VB (docs/theory.md section 3, closed forms, fine for the k of liquids), VF (V-B with the density-
dependent f_cut = a + b (n0* - 0.6), arguments a and b in place of f_cut and alpha) and the candidate VC:
V = V_B (1 + alpha a^2/(1 + a^2)), a^2 = c^2 |g|^2/(n0^2 + eps^2), g = sum_j (r/R)(1 - r/R)^2 e_ij,
c = 30/(pi R^3), eps = 3/(4 pi R^3), with its exact force (the gradient of U = sum_i f(1/V_i)), or with a threshold
(x = max(0, a^2 - t)/w in place of a^2, w = 0.3), the form the plugin's VC has; docs/interfaces.md has what they
measured.
"""

import sys
import time

import numpy as np
from scipy.spatial import cKDTree

T0, PI0, BT, GAMMA_T, R, FRICTION = 0.011054, 0.12711 - 0.011054, 1 / 6, 6.0, 1.6839, 7.37


def volume_integrals_vb(k):
    """I(k), J(k) of docs/theory.md section 3 by their closed forms (k > 0)."""
    s = np.sqrt(k)
    arctangent, logarithm = np.arctan(1 / s), np.log1p(k) - np.log(k)
    return (1 / 3 - k - (1 - k) * s * arctangent + k * logarithm,
            1.5 - logarithm + (1 - 3 * k) / (2 * s) * arctangent)


def forces(x, box, estimator, cutoff_scaling, alpha, threshold=None, width=0.3):
    """Forces, and the particles' densities n_i, for positions x in a periodic box (reduced units). VC: the factor
    1 + alpha s with s = a^2/(1 + a^2), or with a threshold s = x^2/(1 + x^2), x = max(0, a^2 - threshold)/width
    (the plugin's VC: alpha 3, threshold 0.4, width 0.3)."""
    n = len(x)
    rt = R / cutoff_scaling
    pairs = cKDTree(x % box, boxsize=box).query_pairs(R, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    d = x[i] - x[j]
    d -= box * np.round(d / box)
    r = np.linalg.norm(d, axis=1)
    e = d / r[:, None]
    w = 15 / (2 * np.pi * R**3) * (1 - r / R) ** 2
    w_prime = -15 / (np.pi * R**4) * (1 - r / R)
    n0 = np.bincount(i, w, n) + np.bincount(j, w, n)
    if estimator == "VF":
        # f_cut = cutoff_scaling + alpha (n0 - 0.6), at least 1: V-B with a density-dependent f_cut.
        linear = cutoff_scaling + alpha * (n0 - 0.6)
        scaling, d_scaling = np.maximum(linear, 1.0), np.where(linear > 1.0, alpha, 0.0)
        rt = R / scaling
    k = 2 * np.pi / 15 * rt**3 * np.maximum(n0, 1e-300)
    big_i, big_j = volume_integrals_vb(k)
    volume, d_volume = 4 * np.pi * rt**3 * big_i, -8 * np.pi**2 / 15 * rt**6 * big_j
    if estimator == "VF":   # plus dV/dRt dRt/dn0, dV/dRt = 12 pi Rt^2 (I - k J)
        d_volume = d_volume + 12 * np.pi * rt**2 * (big_i - k * big_j) * (-R * d_scaling / scaling**2)
    if estimator == "VC":
        phi = (r / R) * (1 - r / R) ** 2
        phi_prime = (1 - r / R) * (1 - 3 * r / R) / R
        g = np.stack([np.bincount(i, phi * e[:, k], n) - np.bincount(j, phi * e[:, k], n) for k in range(3)], 1)
        c2, eps2 = (30 / (np.pi * R**3)) ** 2, (3 / (4 * np.pi * R**3)) ** 2
        inverse = 1 / (n0**2 + eps2)
        a2 = c2 * (g * g).sum(1) * inverse
        if threshold is None:
            slope = alpha / (1 + a2) ** 2
            factor = 1 + alpha * a2 / (1 + a2)
        else:
            xx = np.maximum(0, a2 - threshold) / width
            slope = alpha * 2 * xx / (1 + xx * xx) ** 2 / width
            factor = 1 + alpha * xx * xx / (1 + xx * xx)
        d_volume_d_moment = volume * slope * c2 * inverse
        d_volume = d_volume * factor - volume * slope * 2 * a2 * n0 * inverse
        volume = volume * factor
    density = 1 / volume
    pressure = PI0 + BT * (density**GAMMA_T - 1)
    coefficient = pressure * d_volume
    pair_force = ((coefficient[i] + coefficient[j]) * w_prime)[:, None] * e
    if estimator == "VC":
        q = 2 * (pressure * d_volume_d_moment)[:, None] * g
        dq = q[i] - q[j]
        along = (e * dq).sum(1)[:, None]
        pair_force += phi_prime[:, None] * along * e + (phi / r)[:, None] * (dq - along * e)
    f = np.zeros((n, 3))
    np.add.at(f, i, pair_force)
    np.add.at(f, j, -pair_force)
    forces.last_a2 = a2 if estimator == "VC" else None
    return f, density, (i, j, e, r)


def fcc(density, cells):
    a = (4 / density) ** (1 / 3)
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]]) + 0.25
    grid = np.array([(p, q, s) for p in range(cells[0]) for q in range(cells[1]) for s in range(cells[2])], float)
    return ((grid[:, None, :] + basis[None]) * a).reshape(-1, 3), np.array(cells, float) * a


def dpd_step(x, v, f, box, model, rng, dt=0.01):
    v += 0.5 * dt * f
    x += dt * v
    f, density, (i, j, e, r) = forces(x, box, *model)
    v += 0.5 * dt * f
    # Explicit DPD pair thermostat: du = 2 impulse, friction gamma on u and <u^2> = 2 T0 for unit masses.
    weight = 1 - r / R
    u = ((v[i] - v[j]) * e).sum(1)
    impulse = -0.5 * FRICTION * weight**2 * u * dt + np.sqrt(FRICTION * T0 * dt) * weight * rng.normal(size=len(r))
    np.add.at(v, i, impulse[:, None] * e)
    np.add.at(v, j, -impulse[:, None] * e)
    return x, v, f, density


def slab(estimator, cutoff_scaling, alpha, duration, seed=1, threshold=None, bulk_run=False):
    """The slab (or, with bulk_run, a bulk liquid of 500 particles at n* = 1, printing its mean n_i and mean a^2)."""
    if bulk_run:
        x, box = fcc(1.0, (5, 5, 5))
        thickness = None
    else:
        x, box = fcc(0.82, (5, 5, 10))
        thickness = box[2]
        box[2] *= 3
        x[:, 2] += thickness
    rng = np.random.default_rng(seed)
    v = rng.normal(0, np.sqrt(T0), x.shape)
    v -= v.mean(0)
    model = (estimator, cutoff_scaling, alpha, threshold)
    f, density, _ = forces(x, box, *model)
    for step in range(int(round(duration / 0.01)) + 1):
        if step % 1000 == 0 and bulk_run:
            a2 = forces.last_a2
            print(f"{estimator} bulk n* = 1, f_cut {cutoff_scaling} alpha {alpha} threshold {threshold}: t* = "
                  f"{step * 0.01:5.1f} mean n_i = {density.mean():.3f}" + ("" if a2 is None else
                  f", mean a^2 = {a2.mean():.3f}, above the threshold {np.mean(a2 > (threshold or 0)):.3f}"),
                  flush=True)
        elif step % 1000 == 0:
            angle = 2 * np.pi * (x[:, 2] % box[2]) / box[2]
            centre = (np.arctan2(np.sin(angle).mean(), np.cos(angle).mean()) % (2 * np.pi)) * box[2] / (2 * np.pi)
            depth = np.abs((x[:, 2] % box[2] - centre + box[2] / 2) % box[2] - box[2] / 2)
            core = depth < thickness / 4
            print(f"{estimator} f_cut {cutoff_scaling} alpha {alpha}: t* = {step * 0.01:5.1f} core true n* = "
                  f"{core.sum() / (box[0] * box[1] * thickness / 2):.3f}, core mean n_i = {density[core].mean():.3f}",
                  flush=True)
        x, v, f, density = dpd_step(x, v, f, box, model, rng)


def bulk(estimator, alpha, scalings):
    """Mean n_i of bulk liquids at n* = 0.7, 0.82 and 1 (1000 VB steps with velocity rescaling at T0 from the
    lattice) evaluated with ``estimator`` at each f_cut (VF: each a, with b = alpha)."""
    for cutoff_scaling in scalings:
        values = []
        for density in (0.7, 0.82, 1.0):
            x, box = fcc(density, (5, 5, 5))
            rng = np.random.default_rng(3)
            v = rng.normal(0, np.sqrt(T0), x.shape)
            f, _, _ = forces(x, box, "VB", 1.35, 0)
            for _ in range(1000):
                v += 0.005 * f
                x += 0.01 * v
                f, _, _ = forces(x, box, "VB", 1.35, 0)
                v += 0.005 * f
                v *= np.sqrt(T0 / ((v * v).sum() / (3 * len(x))))
            values.append(forces(x, box, estimator, cutoff_scaling, alpha)[1].mean())
        print(f"{estimator} alpha {alpha} f_cut {cutoff_scaling}: mean n_i {values[0]:.3f} at n* = 0.7, "
              f"{values[1]:.3f} at 0.82, {values[2]:.3f} at 1", flush=True)


if __name__ == "__main__":
    start = time.time()
    if sys.argv[1] == "--bulk":
        bulk(sys.argv[2], float(sys.argv[3]), [float(value) for value in sys.argv[4:]])
    else:
        run = sys.argv[1] == "--bulk-run"
        arguments = sys.argv[2:] if run else sys.argv[1:]
        slab(arguments[0], float(arguments[1]), float(arguments[2]), float(arguments[3]),
             threshold=float(arguments[4]) if len(arguments) > 4 else None, bulk_run=run)
    print(f"{time.time() - start:.0f} s")
