# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Write the force-styles YAML tests of pair_style gendpde (manybody-pair-gendpde*.yaml, LAMMPS's
unittest/force-styles format) with reference data from openmm-gendpde's OpenMM Reference platform, not from LAMMPS:
the energy, virial and forces of LAMMPS's own test system (unittest/force-styles/tests/data.metal: 32 atoms of two
types in a 7 Angstrom box, metal units) at the start ("init_*") and after 4 velocity-Verlet steps of fix nve
("run_*": the steps as fix nve takes them, with LAMMPS's metal ftm2v, and OpenMM's forces). The YAML files then test
LAMMPS against an independent implementation; python/tests/test_lammps_package.py runs them the way LAMMPS's
test_pair_style does (and checks that they are still what this script writes).

    python lammps/unittest/pair_gendpde_yaml.py LAMMPS_SOURCE_DIR       # (re)write the YAML files here

(The plugin's styles disappear at LAMMPS's "clear", which test_pair_style issues before its restart and data
checks, so LAMMPS's own tester cannot run a plugin's YAML file; the Python check does those steps in new processes.)
"""

import datetime
import pathlib
import sys

import numpy as np
import openmm

from openmmgendpde import GenDPDEForce
from openmmgendpde.models.lammps_units import ENERGY

HERE = pathlib.Path(__file__).resolve().parent
#: LAMMPS's metal units: force x time / mass to velocity (update.cpp), for fix nve's steps.
FTM2V = 1.0 / 1.0364269e-4
#: in.metal's time step (ps) and the steps of test_pair_style's run
TIME_STEP, RUN_STEPS = 0.0001, 4
ESTIMATORS = {"va": GenDPDEForce.VA, "vb": GenDPDEForce.VB, "vc": GenDPDEForce.VC}

#: The YAML tests: each a pair style (metal units) and one Tait law per type (n0 in 1/Angstrom^3, pi0 and B_T in
#: eV/Angstrom^3, gamma_T), with the relative error LAMMPS may have against OpenMM per value (test_pair_style's
#: epsilon: every force component, energy and virial component, relative to the smaller of the two; measured
#: largest: 1.4e-12 (V-B, a force component 1.6e-3 of the rms force; 8e-15 of the rms) and 1.7e-13 (V-C)).
CASES = {
    "manybody-pair-gendpde.yaml": {
        "epsilon": 5e-12, "range": 3.4, "estimator": "vb", "cutoff_scaling": 1.35, "background": 0.0,
        "laws": {1: (0.09, 0.017, 0.028, 6.0), 2: (0.1, 0.02, 0.03, 7.0)},
    },
    "manybody-pair-gendpde_vc.yaml": {
        "epsilon": 1e-12, "range": 3.4, "estimator": "vc", "cutoff_scaling": 1.35, "background": 0.005,
        "laws": {1: (0.09, 0.017, 0.028, 6.0), 2: (0.1, 0.02, 0.03, 7.0)},
    },
}


def read_data_metal(path):
    """(box edges, masses by type, ids, types, positions, velocities) of LAMMPS's data.metal (Angstrom, g/mol,
    Angstrom/ps; rows in ID order)."""
    lines = pathlib.Path(path).read_text().splitlines()
    edges = [float(line.split()[1]) - float(line.split()[0]) for line in lines if line.endswith(("xhi", "yhi", "zhi"))]
    sections, name = {}, None
    for line in lines:
        words = line.split()
        if words[:1] in (["Masses"], ["Atoms"], ["Velocities"]):
            name = words[0]
            sections[name] = []
        elif name and words:
            sections[name].append(words)
    masses = {int(w[0]): float(w[1]) for w in sections["Masses"]}
    atoms = sorted(sections["Atoms"], key=lambda w: int(w[0]))
    velocities = {int(w[0]): [float(x) for x in w[1:4]] for w in sections["Velocities"]}
    ids = [int(w[0]) for w in atoms]
    return (edges, masses, ids, np.array([int(w[1]) for w in atoms]),
            np.array([[float(x) for x in w[2:5]] for w in atoms]), np.array([velocities[i] for i in ids]))


def commands(case):
    """(pair_style, [pair_coeff lines]) of a case, as LAMMPS reads them."""
    style = f"gendpde {case['range']!r} {case['estimator']} {case['cutoff_scaling']!r}"
    if case["background"]:
        style += f" background {case['background']!r}"
    return style, [f"{t} {t} Tait " + " ".join(repr(float(p)) for p in law) for t, law in case["laws"].items()]


class Reference:
    """OpenMM's Reference platform on the case's system, in LAMMPS's metal units: energy (eV), forces (eV/Angstrom),
    virial (eV: xx, yy, zz, xy, xz, yz, as LAMMPS's pair->virial)."""

    def __init__(self, case, edges, masses, types):
        pressure = ENERGY * 1e-3   # kJ/mol/nm^3 -> eV/Angstrom^3
        system = openmm.System()
        system.setDefaultPeriodicBoxVectors(*(openmm.Vec3(*(0.1 * edges[k] if k == a else 0 for k in range(3)))
                                              for a in range(3)))
        force = GenDPDEForce(0.1 * case["range"])
        force.setNonbondedMethod(GenDPDEForce.CutoffPeriodic)
        force.setDensityEstimator(ESTIMATORS[case["estimator"]])
        force.setCutoffScaling(case["cutoff_scaling"])
        force.setBackgroundPressure(case["background"] / pressure)
        for t, (n0, pi0, bulk, gamma) in case["laws"].items():
            force.addTypeParameters(t - 1, 1e3 * n0, pi0 / pressure, bulk / pressure, gamma)
        for i, t in enumerate(types):
            system.addParticle(masses[t])
            force.setParticleType(i, int(t) - 1)
        system.addForce(force)
        self.force = force
        self.context = openmm.Context(system, openmm.VerletIntegrator(0.001),
                                      openmm.Platform.getPlatformByName("Reference"))

    def __call__(self, positions):
        self.context.setPositions(0.1 * positions)
        state = self.context.getState(getEnergy=True, getForces=True)
        virial = self.force.getParticleVirials(self.context)._value.sum(axis=0) * ENERGY
        return (state.getPotentialEnergy()._value * ENERGY, np.array(state.getForces()._value) * ENERGY / 10,
                np.array([virial[0, 0], virial[1, 1], virial[2, 2], virial[0, 1], virial[0, 2], virial[1, 2]]))


def reference_values(case, data_file):
    """{init_vdwl, init_stress, init_forces, run_vdwl, run_stress, run_forces, natoms, ids} of a case from OpenMM."""
    edges, masses, ids, types, positions, velocities = read_data_metal(data_file)
    reference = Reference(case, edges, masses, types)
    energy, forces, virial = reference(positions)
    values = {"natoms": len(ids), "ids": ids, "init_vdwl": energy, "init_stress": virial, "init_forces": forces}
    # fix nve as LAMMPS steps it: v += dtf f/m, x += dt v; forces; v += dtf f/m (dtf = dt/2 ftm2v)
    mass = np.array([masses[t] for t in types])[:, None]
    dtf = 0.5 * TIME_STEP * FTM2V
    x, v = positions.copy(), velocities.copy()
    for _ in range(RUN_STEPS):
        v = v + dtf / mass * forces
        x = x + TIME_STEP * v
        energy, forces, virial = reference(x)
        v = v + dtf / mass * forces
    values.update(run_vdwl=energy, run_stress=virial, run_forces=forces)
    return values


def yaml_text(name, case, values, date):
    """The YAML file of a case, in test_pair_style's layout (yaml_writer.cpp's number formats)."""
    style, coefficients = commands(case)

    def stress(v):
        return "! |-\n  " + " ".join(f"{x:23.16e}" for x in v)

    def forces(f):
        return "! |2\n" + "".join(f"  {i:3} {a:23.16e} {b:23.16e} {c:23.16e}\n" for i, (a, b, c) in
                                  zip(values["ids"], f))
    lines = [
        "---",
        "lammps_version: 29 Sep 2021",
        f"date_generated: {date}",
        f"epsilon: {case['epsilon']!r}",
        "skip_tests: single extract",
        "prerequisites: ! |",
        "  atom atomic",
        "pre_commands: ! |",
        "  variable newton_pair delete",
        "  variable newton_pair index on",
        "  plugin load ${gendpde_plugin}",
        "post_commands: ! \"\"",
        "input_file: in.metal",
        f"pair_style: {style}",
        "pair_coeff: ! |",
        *(f"  {line}" for line in coefficients),
        "extract: ! \"\"",
        f"natoms: {values['natoms']}",
        f"init_vdwl: {values['init_vdwl']!r}",
        "init_coul: 0",
        f"init_stress: {stress(values['init_stress'])}",
        f"init_forces: {forces(values['init_forces'])}" + f"run_vdwl: {values['run_vdwl']!r}",
        "run_coul: 0",
        f"run_stress: {stress(values['run_stress'])}",
        f"run_forces: {forces(values['run_forces'])}...",
    ]
    return "\n".join(lines) + "\n"


def data_file(lammps_source):
    return pathlib.Path(lammps_source) / "unittest" / "force-styles" / "tests" / "data.metal"


def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    date = datetime.datetime.now(datetime.timezone.utc).strftime("%a %b %d %H:%M:%S %Y")
    for name, case in CASES.items():
        (HERE / name).write_text(yaml_text(name, case, reference_values(case, data_file(sys.argv[1])), date))
        print(f"wrote {HERE / name}")


if __name__ == "__main__":
    main()
