# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The two-material example (examples/two_materials.py) runs and shows what it claims: heat flows from the hot
material to the cold one while the total energy is conserved."""

import pathlib
import subprocess
import sys

import pytest

#: The tier of every test here (pyproject.toml's markers).
pytestmark = pytest.mark.validation

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def test_two_materials_example_exchanges_heat_and_conserves_energy():
    """800 isoenergetic steps (8 time units): argon starts at exactly 1.2 T0 and B at 0.8 T0. Expected: argon
    cooler and B warmer than at the start, each by more than 0.02 T0 (the run in docs/types.md moves them by 0.10
    and 0.03 by then; the harmonic mean of 500 particles fluctuates by ~0.005 T0), and the conserved energy constant
    to 1e-6 relative (measured ~3e-8: rounding, and the O(dt^2) energy error of the splitting)."""
    result = subprocess.run([sys.executable, str(EXAMPLES / "two_materials.py"), "--steps", "800"],
                            capture_output=True, text=True, check=True, timeout=600)
    rows = [line.split() for line in result.stdout.splitlines() if line[:1] == " " or line[:1].isdigit()]
    rows = [[float(value) for value in row] for row in rows if len(row) == 5]
    first, last = rows[0], rows[-1]
    assert (first[1], first[2]) == (1.2, 0.8)
    assert last[1] < first[1] - 0.02 and last[2] > first[2] + 0.02, (first, last)
    assert max(abs(row[4]) for row in rows) < 1e-6


def test_adiabatic_compression_heats_the_liquid_as_its_isentrope_says():
    """examples/adiabatic_compression.py, 6 stages of 0.5% of the volume with 50 Conservative steps each (864
    particles). Expected: the mean particle temperature rises with the density (by ~8 K at 3% of the volume; required:
    > 5 K), as the TaitThermalExpansion law's isentrope theta0 exp(beta (1/n0 - 1/n)/C) at the mean density says, to
    5e-3 at every stage (the mean of the particles' isentropes differs from the isentrope of the mean density by the
    density fluctuations, a second-order term: measured <= 2.1e-3), every particle is on its own isentrope to 1e-9
    (rounding), and the conserved energy drifts by < 1e-6 relative between deformations (measured ~5e-8: the O(dt^2)
    error of velocity Verlet)."""
    result = subprocess.run([sys.executable, str(EXAMPLES / "adiabatic_compression.py"), "--stages", "6",
                             "--steps", "50"], capture_output=True, text=True, check=True, timeout=600)
    rows = [[float(value) for value in line.split()] for line in result.stdout.splitlines()
            if line.startswith(" ") and line.split()[0][0].isdigit()]
    assert len(rows) == 7
    first, last = rows[0], rows[-1]
    assert last[2] > first[2] + 5.0, (first, last)
    assert all(abs(row[4]) < 5e-3 for row in rows), rows
    assert all(row[5] < 1e-9 for row in rows), rows
    assert all(abs(row[6]) < 1e-6 for row in rows), rows


def test_shock_jumps_to_the_hugoniot_of_the_models_equation_of_state():
    """examples/shock.py at a small size: the equation of state from 21 equilibrium runs of 256 particles (400
    sampled steps each), one impact at u_p = 200 m/s in a 4 x 4 x 40-cell box (2560 particles). Expected: the
    Rankine-Hugoniot state of the fitted equation of state. The full example (docs/thermal.md) meets it to 2% of the
    temperature jump, 1% of U_s and 0.7% of n1; this small one missed by 8.4%, 5.6% and 0.5% (short tables, a short
    run in which the fronts' formation weighs more). Required: about twice that, 15% of the jump T1 - T0, 10% of U_s and
    1.5% of n1/n0. The jump itself (~60 K) is required (> 40 K): its tolerance, ~9 K, is a small part of it."""
    result = subprocess.run([sys.executable, str(EXAMPLES / "shock.py"), "--table-particles", "256", "--table-melt",
                             "300", "--table-steps", "400", "--speeds", "200", "--length", "40", "--width", "4"],
                            capture_output=True, text=True, check=True, timeout=600)
    lines = result.stdout.splitlines()
    t0 = float(next(line for line in lines if line.startswith("Ahead")).split("T0 = ")[1].split()[0])
    row = [float(value) for value in lines[-1].replace("+-", " ").split()]
    speed, shock_measured, shock_predicted, n_measured, _, n_predicted, t_measured, _, t_predicted, _ = row
    assert speed == 200.0
    assert t_predicted - t0 > 40.0, (t0, row)
    assert abs(t_measured - t_predicted) < 0.15 * (t_predicted - t0), row
    assert abs(shock_measured / shock_predicted - 1) < 0.10, row
    assert abs(n_measured / n_predicted - 1) < 0.015, row


def test_rayleigh_benard_layer_conducts_below_the_onset():
    """examples/rayleigh_benard.py at a small size: nu from one transverse wave, one run at dT = 10 K (below the
    onset, ~16 K in the full example) of 0.05 thermal times (4536 steps; the full runs are 0.6). Expected, from the
    full example (docs/thermal.md): conduction, the flow at the noise's level (flow/noise 2.5 at 12 K, where the
    convecting runs have 5.2-25.6: required < 5); the liquid takes 0.885 of dT (the rest falls at the walls: required
    0.7-1, the short run is not yet steady); D_T* = 0.050 (required 0.025-0.1: the target D_T* that the conductivity
    was chosen for, 0.025, plus what the particles' motion carries; twice the full run's at most); nu* = 0.045 +- 0.006
    (required 0.02-0.1: the floor of the particles' motion, above the mapping's 0.013); an interior gradient."""
    result = subprocess.run([sys.executable, str(EXAMPLES / "rayleigh_benard.py"), "--differences", "10",
                             "--thermal-times", "0.05", "--viscosity-replicas", "1"],
                            capture_output=True, text=True, check=True, timeout=600)
    lines = result.stdout.splitlines()
    nu = float(next(line for line in lines if line.startswith("measured nu")).split("=")[1].split()[0])
    conduction = next(line for line in lines if line.strip().startswith("conduction:"))
    diffusivity = float(conduction.split("D_T = ")[1].split()[0])
    fraction = float(conduction.split("takes ")[1].split()[0])
    row = [float(value) for value in lines[-1].replace("+-", " ").split()]
    difference, _, nusselt, _, flow_over_noise, _, gradient, _ = row
    assert difference == 10.0 and nusselt == 1.0
    assert 0.02 < nu < 0.1, nu
    assert 0.025 < diffusivity < 0.1, conduction
    assert 0.7 < fraction < 1.0 and gradient < 0, (conduction, row)
    assert flow_over_noise < 5, row


@pytest.mark.parametrize("script, arguments, message", [
    ("adiabatic_compression.py", ["--fraction", "1"], "argument --fraction: 1 is not allowed; it must be a finite "
                                                       "number > 0 and < 1"),
    ("adiabatic_compression.py", ["--fraction", "-0.5"], "argument --fraction: -0.5 is not allowed"),
    ("adiabatic_compression.py", ["--fraction", "0.5"], "the box would end 0.058 nm across, less than twice the "
                                                         "cutoff"),
    ("immiscible_pair.py", ["--platform", "Nope"], "argument --platform: invalid choice: 'Nope'"),
    ("immiscible_pair.py", ["--repulsion", "nan"], "argument --repulsion: nan is not allowed; it must be a finite "
                                                    "number >= 0"),
    ("two_materials.py", ["--platform", "Nope"], "argument --platform: invalid choice: 'Nope'"),
    ("shock.py", ["--speeds", "-1"], "argument --speeds: -1 is not allowed; it must be a finite number > 0"),
    ("shock.py", ["--width", "1"], "--width and --length: the box"),
    ("rayleigh_benard.py", ["--grid", "0", "0"], "argument --grid: 0 is not allowed; it must be an integer >= 1"),
    ("rayleigh_benard.py", ["--grid", "14", "3"], "--grid 14 3 is not allowed"),
    ("rayleigh_benard.py", ["--plot", "/missing/x"], "argument --plot: /missing/x.png cannot be written"),
    ("rayleigh_benard.py", ["--differences", "300"], "dT/2 + the perturbation must stay below T0"),
    ("liquid_argon.py", ["--cutoff", "2"], "argument --cutoff: 2 is not allowed; R_cut* must be one of the published"),
])
def test_an_example_refuses_a_bad_argument_at_once(script, arguments, message):
    """Every example checks its arguments before it runs anything: a usage error (status 2) in one line naming the
    option, within seconds (rayleigh_benard.py --grid 0 0 failed after 53 s, --plot /missing/x after the whole run;
    immiscible_pair.py --repulsion nan ran 20000 steps and exited 0)."""
    result = subprocess.run([sys.executable, str(EXAMPLES / script)] + arguments, capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 2 and "Traceback" not in result.stderr and result.stdout == "", result.stderr
    assert message in result.stderr.splitlines()[-1]
