# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""compression: how a model liquid follows a compression (docs/theory.md section 12).

The liquid of a model file (calibrate --output) or of a fluid's mapping (--fluid), run as calibrate runs it (melted
with the DPD thermostat, then isoenergetic; CPU or any platform) at n0 (1 + c) for each compression c. Each box
reports the mean particle density n-bar and the spread of the n_i, the mean primitive density n0-bar = <sum_j w(r_ij)>
(the structure's own response, before the estimator maps n0_i to n_i), the close pairs g(r < 0.15 R), the bond order
(global Q6, mean local q6: 0.575 in an FCC crystal, ~0.3 in a liquid), the self-diffusion D and the virial pressure P.
Then the particle-density response (n/n-bar) dn-bar/dn (1 where the n_i follow the true density n), the primitive
response, the bulk modulus n dP/dn between the extreme boxes (each with its standard error), and, independently of
the pressure, n dP/dn from the structure factor's k -> 0 limit, n k_B T/S(0), at the central box.

    python -m openmmgendpde compression --model water-model.toml
    python -m openmmgendpde compression --fluid water --cutoff-scaling 1.05 --background-pressure 0
"""

import dataclasses
import math

import numpy as np
from openmm import unit

from ..analysis.rdf import radial_distribution
from ..analysis.statistics import correlated_mean
from ..analysis.thermodynamics import ThermodynamicProbe, self_diffusion
from ..calibration.calibration import Calibration, Measured, Plan, model_positions
from ..models.fluid import KB

#: Pairs closer than this fraction of the cutoff are "close pairs" (water's calibrated model: g = 0.24 there).
CLOSE_PAIR_FRACTION = 0.15


def _pairs(positions, box, cutoff):
    """(i, j, d) of every pair within ``cutoff`` in a rectangular periodic ``box`` (3 edges, nm), d = r_j - r_i
    minimum image."""
    from scipy.spatial import cKDTree
    box = np.asarray(box, dtype=float)
    wrapped = np.mod(positions, box)
    pairs = cKDTree(wrapped, boxsize=box).query_pairs(cutoff, output_type="ndarray")
    d = wrapped[pairs[:, 1]] - wrapped[pairs[:, 0]]
    d -= box * np.round(d / box)
    return pairs[:, 0], pairs[:, 1], d


def bond_order(positions, box, cutoff):
    """(Q6, <q6>) of Steinhardt, Nelson and Ronchetti: Q6 over all bonds shorter than ``cutoff`` (~0 in a liquid or
    a powder, 0.575 in a single FCC crystal), and the mean of each particle's own q6 (0.575 in FCC, ~0.3 in a
    liquid)."""
    from scipy.special import sph_harm_y
    i, j, d = _pairs(positions, box, cutoff)
    r = np.linalg.norm(d, axis=1)
    theta = np.arccos(np.clip(d[:, 2] / r, -1, 1))
    phi = np.arctan2(d[:, 1], d[:, 0])
    count = np.bincount(i, minlength=len(positions)) + np.bincount(j, minlength=len(positions))
    q = np.zeros((len(positions), 13), complex)
    for m in range(-6, 7):
        y = sph_harm_y(6, m, theta, phi)   # Y_6m(-d) = Y_6m(d): l even
        np.add.at(q[:, m + 6], i, y)
        np.add.at(q[:, m + 6], j, y)
    norm = 4 * math.pi / 13
    global_q6 = math.sqrt(norm * np.sum(np.abs(q.sum(axis=0) / max(1, count.sum())) ** 2))
    local = np.sqrt(norm * np.sum(np.abs(q / np.maximum(count, 1)[:, None]) ** 2, axis=1))
    return global_q6, float(local[count > 0].mean())


def structure_factor(frames, box, shells=4):
    """(k, S(k), standard error) for the ``shells`` smallest |k| of a cubic periodic box: k = 2 pi m/L with m^2 = 1,
    2, ..., S(k) = <|sum_j exp(-i k.r_j)|^2>/N averaged over the shell's wave vectors and the frames (the error
    from the frames' scatter, correlated_mean; NaN for one frame)."""
    edge = float(box[0])
    vectors = {}   # m^2 -> one of each pair +-m (|rho_k|^2 = |rho_-k|^2)
    limit = math.isqrt(shells + 2) + 1
    for a in range(-limit, limit + 1):
        for b in range(-limit, limit + 1):
            for c in range(-limit, limit + 1):
                if (a, b, c) > (0, 0, 0):
                    vectors.setdefault(a * a + b * b + c * c, []).append((a, b, c))
    result = []
    for m2 in sorted(vectors)[:shells]:
        k = 2 * math.pi / edge * np.array(vectors[m2], dtype=float)
        values = [np.mean(np.abs(np.exp(-1j * (positions @ k.T)).sum(axis=0)) ** 2) / len(positions)
                  for positions in frames]
        if len(values) < 2:
            result.append((2 * math.pi / edge * math.sqrt(m2), float(values[0]), float("nan")))
            continue
        mean = correlated_mean(values)
        result.append((2 * math.pi / edge * math.sqrt(m2), mean.mean, mean.standard_error))
    return result


@dataclasses.dataclass
class CompressionPoint:
    """One box of the study (OpenMM units; Measured: value and standard error)."""
    compression: float
    density: float            # n = n0 (1 + c), nm^-3
    mean_density: Measured    # n-bar
    spread: float             # sd(n_i)/n-bar over particles and frames
    primitive: float          # <n0_i>/n (GenDPDEForce.getPrimitiveDensities)
    close_pairs: float        # g(r < CLOSE_PAIR_FRACTION R)
    global_q6: float
    local_q6: float
    diffusion: Measured       # nm^2/ps
    pressure: Measured        # kJ/mol/nm^3
    temperature: float        # kinetic, K
    structure: list           # structure_factor(): (k, S, error)


def measure(calibration, compression, plan):
    """A CompressionPoint at n0 (1 + compression), from plan.frames frames every plan.interval steps (a cubic box:
    parameters.liquid of plan.particles)."""
    parameters = calibration.parameters
    density = parameters.density * (1 + compression)
    model, context = calibration._equilibrated(density)
    probe = ThermodynamicProbe(model.system)
    frames, times, means, primitives, spreads, pressures, temperatures = [], [], [], [], [], [], []
    for _ in range(plan.frames):
        calibration._step(model.integrator, plan.interval)
        state = context.getState(getEnergy=True, getVelocities=True, getPositions=True)
        sample = probe.sample(state, context, model.integrator)
        densities = np.asarray(model.force.getParticleDensities(context).value_in_unit(unit.nanometer**-3))
        means.append(densities.mean())
        primitives.append(np.mean(model.force.getPrimitiveDensities(context).value_in_unit(unit.nanometer**-3)))
        spreads.append(densities.std() / densities.mean())
        pressures.append(sample.pressure.value_in_unit(unit.kilojoule_per_mole / unit.nanometer**3))
        temperatures.append(sample.kinetic_temperature.value_in_unit(unit.kelvin))
        times.append(state.getTime().value_in_unit(unit.picosecond))
        frames.append(model_positions(context))
    box = np.array([v.value_in_unit(unit.nanometer)[k] for k, v in enumerate(state.getPeriodicBoxVectors())])
    cutoff = parameters.cutoff
    every = frames[::max(1, len(frames) // 20)]
    r, g = radial_distribution(every, box[0], r_max=cutoff, bin_width=cutoff / 40, length=1.0)
    order = [bond_order(p, box, 1.35 * density ** (-1 / 3)) for p in every[::4]]

    def measured(values):
        mean = correlated_mean(values)
        return Measured(mean.mean, mean.standard_error, mean.independent_samples)

    return CompressionPoint(
        compression=compression, density=density, mean_density=measured(means), spread=float(np.mean(spreads)),
        primitive=float(np.mean(primitives)) / density, close_pairs=float(g[r < CLOSE_PAIR_FRACTION * cutoff].mean()),
        global_q6=float(np.mean([o[0] for o in order])), local_q6=float(np.mean([o[1] for o in order])),
        diffusion=Measured(*self_diffusion(times, frames)), pressure=measured(pressures),
        temperature=float(np.mean(temperatures)),
        structure=structure_factor(frames, box))


def responses(points):
    """(particle-density response, primitive response, n dP/dn) between the first and last points, by logarithmic
    differences: (n/n-bar) dn-bar/dn = d ln n-bar/d ln n, likewise for n0-bar, and n dP/dn = dP/d ln n (Measured,
    errors propagated from the two boxes)."""
    low, high = points[0], points[-1]
    span = math.log(high.density / low.density)
    response = math.log(high.mean_density.value / low.mean_density.value) / span
    response_error = math.hypot(high.mean_density.error / high.mean_density.value,
                                low.mean_density.error / low.mean_density.value) / span
    primitive = math.log(high.primitive * high.density / (low.primitive * low.density)) / span
    modulus = Measured((high.pressure.value - low.pressure.value) / span,
                       math.hypot(high.pressure.error, low.pressure.error) / span)
    return Measured(response, response_error), primitive, modulus


def structure_modulus(point):
    """n dP/dn from the structure factor, n k_B T/S(0) (kJ/mol/nm^3, Measured), with S(0) from a fit
    S(k) = S(0) + a k^2 to the smallest shells (weighted by their errors), or None without shells."""
    if len(point.structure) < 2:
        return None
    k, s, e = (np.array(column, dtype=float) for column in zip(*point.structure))
    weights = 1 / np.maximum(e, 1e-12) ** 2
    design = np.vstack([np.ones_like(k), k**2]).T
    covariance = np.linalg.inv(design.T @ (design * weights[:, None]))
    s0 = (covariance @ design.T @ (weights * s))[0]
    s0_error = math.sqrt(covariance[0, 0])
    kt = KB * point.temperature
    if not s0 > 0:
        return Measured(float("inf"), float("inf"))
    value = point.density * kt / s0
    return Measured(value, value * s0_error / s0)


@dataclasses.dataclass
class Compression:
    """What the study found: a CompressionPoint per box (by compression), and between the extreme boxes the
    particle-density response, the primitive response and n dP/dn (responses; None with one box), and n k_B T/S(0)
    at the central box (structure_modulus; None without shells)."""
    points: list
    response: Measured = None
    primitive_response: float = None
    bulk_modulus: Measured = None
    structure_modulus: Measured = None

    @property
    def central(self):
        return min(self.points, key=lambda p: abs(p.compression))


def quick_plan():
    """The runs of --quick: 500 particles, 40 frames 25 steps apart."""
    return Plan(particles=500, melt=400, melt_block=500, frames=40, interval=25)


def compress(parameters, compressions, estimator="VB", plan=Plan(), platform="CPU", seed=1, report=None):
    """The study (module docstring) of the model ``parameters`` with ``estimator``: a box at n0 (1 + c) for each of
    ``compressions`` (sorted), each run as calibrate runs it (Calibration, ``plan``, ``platform``, ``seed``);
    ``report(point)`` is called after each box. Returns a Compression."""
    calibration = Calibration(parameters, estimator, plan, platform, seed=seed, report=lambda *_: None)
    points = []
    for compression in sorted(compressions):
        points.append(measure(calibration, compression, plan))
        if report is not None:
            report(points[-1])
    result = Compression(points)
    if len(points) >= 2:
        result.response, result.primitive_response, result.bulk_modulus = responses(points)
    result.structure_modulus = structure_modulus(result.central)
    return result


def record(parameters, estimator, plan, result):
    """What --json writes: the fluid, the model's parameters, the estimator, the particles, every box and what was
    derived from them."""
    model = {field.name: getattr(parameters, field.name) for field in dataclasses.fields(parameters)
             if field.name != "fluid"}
    found = {"fluid": parameters.fluid.name, "model": model, "estimator": estimator, "particles": plan.particles,
             "points": [dataclasses.asdict(p) for p in result.points]}
    if result.response is not None:
        found.update(response=dataclasses.asdict(result.response), primitive_response=result.primitive_response,
                     bulk_modulus=dataclasses.asdict(result.bulk_modulus))
    if result.structure_modulus is not None:
        found["structure_modulus"] = dataclasses.asdict(result.structure_modulus)
    return found


def compressions_of(text):
    """The compressions of a comma-separated list; ValueError unless each is a finite number in (-0.5, 0.5)."""
    try:
        values = [float(x) for x in text.split(",")]
    except ValueError:
        raise ValueError(f"{text!r} is not a comma-separated list of numbers") from None
    if len(values) < 1 or not all(math.isfinite(v) and -0.5 < v < 0.5 for v in values):
        raise ValueError(f"{text!r}: each compression must be a finite number in (-0.5, 0.5)")
    return values
