"""The two-material example (examples/two_materials.py) runs and shows what it claims: heat flows from the hot
material to the cold one while the total energy is conserved."""

import pathlib
import subprocess
import sys

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
