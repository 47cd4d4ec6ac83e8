# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The input script that models/lammps_files.py writes for the project's LAMMPS package, section by section: its
variables, the atoms' set-up, pair_style and pair_coeff of each type's law (named and ordered as the table of the
laws describes them: no law is spelt here), the neighbour settings the fix's sweep needs, fix gendpde with the
integrator's parameters by type, the output and the run (docs/lammps.md)."""

import dataclasses

import numpy as np
import openmm
from openmm import unit

from ..api import ESTIMATOR_NAMES, GenDPDEIntegrator, law_description
from .lammps_units import TAIT_KINDS, UNITS, UNITS_NOTE, in_units, kind_of

#: The integrator's modes as the fix names them.
MODES = {"isoenergetic": GenDPDEIntegrator.Isoenergetic, "isothermal": GenDPDEIntegrator.Isothermal,
         "conservative": GenDPDEIntegrator.Conservative}
#: The files lammps_input writes, as the input script reads them.
DATA_FILE = "gendpde.data"
SCRIPT_FILE = "in.gendpde"
#: The atomfile of each particle's initial temperature (lammps_input's temperatures).
TEMPERATURES_FILE = "temperatures"
#: The first words of the files' first comment.
HEADER = "GenDPDE model for the LAMMPS plugin (python -m openmmgendpde lammps-input)"


def number_text(value):
    """A float as the shortest text that reads back to it."""
    return repr(float(value))


def _laws(force, kinds):
    """{OpenMM type: (law, Tait parameters, law parameters)} for the types ``kinds``, each as the force has it."""
    tait = {}
    for k in range(force.getNumTypeParameters()):
        type_, *parameters = force.getTypeParameters(k)
        tait[int(type_)] = parameters
    laws = {}
    for k in range(force.getNumTypeEquationsOfState()):
        type_, law, parameters = force.getTypeEquationOfState(k)
        laws[int(type_)] = (law, parameters)
    default_tait, default_law = force.getTaitParameters(), force.getEquationOfState()
    return {kind: (*laws.get(kind, default_law), tait.get(kind, default_tait)) for kind in kinds}


def _pair_coeff(index, units, law, parameters, tait):
    """One pair_coeff line (in ``units``) of the LAMMPS type ``index``: the law as GenDPDEForce names it and its
    parameters, all as the table of the laws describes them (api.law_description), so that no law is spelt here."""
    name, extends_tait, described = law_description(law)
    if len(parameters) != len(described):
        raise ValueError(f"the law {name} has {len(parameters)} parameters, not {len(described)}")
    values = [in_units(v, k, units) for v, k in zip(tait, TAIT_KINDS)] if extends_tait else []
    values += [in_units(v, kind_of(u), units) for v, (_, u) in zip(parameters, described)]
    return f"pair_coeff {index} {index} {name} " + " ".join(map(number_text, values))


def _transport(integrator, kinds):
    """({OpenMM type: C_V}, {(type a, type b): (gamma, kappa)} for a <= b) as the integrator has them (Quantities)."""
    capacities = {kind: integrator.getHeatCapacity() for kind in kinds}
    for k in range(integrator.getNumTypeHeatCapacities()):
        type_, capacity = integrator.getTypeHeatCapacity(k)
        if int(type_) in capacities:
            capacities[int(type_)] = capacity
    pairs = {(a, b): (integrator.getFriction(), integrator.getHeatConduction())
             for a in kinds for b in kinds if a <= b}
    for k in range(integrator.getNumTypePairs()):
        a, b, friction, conduction = integrator.getTypePairParameters(k)
        key = (min(int(a), int(b)), max(int(a), int(b)))
        if key in pairs:
            pairs[key] = (friction, conduction)
    return capacities, pairs


def _initial_temperature(integrator):
    """The temperature the particles start at in OpenMM (K): those set before a Context (all one value: the fix's
    ``initial`` takes one, else pass them to lammps_input as ``temperatures``), else the bath's."""
    try:
        temperatures = integrator.getParticleTemperatures().value_in_unit(unit.kelvin)
    except openmm.OpenMMException:   # none set: the particles start at the bath temperature
        return integrator.getTemperature().value_in_unit(unit.kelvin)
    values = set(np.asarray(temperatures, dtype=float).tolist())
    if len(values) != 1:
        raise ValueError("the particles' initial temperatures differ; pass them as lammps_input's temperatures "
                         "(an atomfile for the fix's 'initial v_theta')")
    return values.pop()


@dataclasses.dataclass(frozen=True)
class Script:
    """What the script's sections share: the choices of lammps_input and the numbers made from them."""
    units: str
    title: str
    plugin: str
    steps: int
    thermo: int
    seed: int
    cutoff: float
    skin: float
    ghost: float
    temperatures: bool   # each particle's initial temperature from TEMPERATURES_FILE
    restart: str

    def unit(self, kind):
        """The name of this script's unit of ``kind`` (UNITS)."""
        return UNITS[self.units][kind][0]

    def number(self, value, kind):
        """``value`` (OpenMM units) of ``kind`` in this script's units, as text."""
        return number_text(in_units(value, kind, self.units))


def section(*lines):
    """Lines as one section of the script (each line ended)."""
    return "\n".join(lines) + "\n"


def opening_sections(script, integrator):
    """The sections header, variables and setup: what the script is, its variables, the units and the atoms."""
    mode = {value: name for name, value in MODES.items()}[integrator.getMode()]
    initial = ("v_theta" if script.temperatures else
               script.number(_initial_temperature(integrator), "temperature"))
    step = integrator.getStepSize().value_in_unit(unit.picosecond)
    temperature = integrator.getTemperature().value_in_unit(unit.kelvin)
    map_line = "atom_modify map yes   # (atom-style variables of per-atom files need it: initial v_name)"
    # (read_restart brings the atom style and the boundaries back)
    start = ([map_line, "plugin load ${plugin}", f"read_restart {script.restart}"] if script.restart else
             ["atom_style atomic", map_line, "boundary p p p", "plugin load ${plugin}", f"read_data {DATA_FILE}"])
    return {
        "header": section(
            f"# {HEADER}" + (f":\n# {script.title}." if script.title else "."),
            *(f"# {line}" for line in UNITS_NOTE[script.units]),
            f"# Run where {DATA_FILE} is: lmp -var plugin /path/to/gendpdeplugin.so -in {SCRIPT_FILE}",
            "# Each variable below can also be set on the command line (lmp -var steps 5000 ...).", ""),
        "variables": section(
            *([f"variable plugin index {script.plugin}"] if script.plugin else []),
            f"variable steps index {int(script.steps)}",
            f"variable dt index {script.number(step, 'time')}   # {script.unit('time')}",
            f"variable mode index {mode}   # isoenergetic, isothermal or conservative",
            f"variable seed index {script.seed}",
            f"variable temperature index {script.number(temperature, 'temperature')}   # "
            f"{script.unit('temperature')}, the bath of the isothermal mode",
            f"variable initial index {initial}   # {script.unit('temperature')}, the start: eps_i = C_V T"
            + (" (v_theta: each particle's)" if script.temperatures else ""),
            f"variable thermo index {int(script.thermo)}", ""),
        "setup": section(f"units {script.units}", *start, ""),
    }


def model_sections(script, force, integrator, kinds, index):
    """The sections pair, neighbors and fix: the force's and the integrator's parameters by LAMMPS type."""
    laws = _laws(force, kinds)
    background = in_units(force.getBackgroundPressure(), "pressure", script.units)
    capacities, pairs = _transport(integrator, kinds)
    estimator = ESTIMATOR_NAMES[force.getDensityEstimator()].lower()
    length = script.unit("length")
    fix = ["fix integrate all gendpde ${mode} ${seed}"]
    fix += [f"heat_capacity {index[kind]} {script.number(capacities[kind], 'heat_capacity')}" for kind in kinds]
    fix += [f"friction {index[a]} {index[b]} {script.number(gamma, 'friction')}"
            for (a, b), (gamma, _) in pairs.items()]
    fix += [f"conduction {index[a]} {index[b]} {script.number(kappa, 'heat_conduction')}"
            for (a, b), (_, kappa) in pairs.items()]
    fix += ["temperature ${temperature}", "initial ${initial}"]
    return {
        "pair": section(
            f"# R ({length}), the density estimator, f_cut (the reduced range is R/f_cut), background pressure p_b "
            f"({script.unit('pressure')})",
            f"pair_style gendpde {number_text(script.cutoff)} {estimator} {number_text(force.getCutoffScaling())}"
            + (f" background {number_text(background)}" if background != 0 else ""),
            "# per type: the law as GenDPDEForce names it and its parameters (a law that extends Tait takes n0",
            f"# ({script.unit('number_density')}), pi0 and B_T ({script.unit('pressure')}: energy/volume) and "
            f"gamma_T first; docs/lammps.md)",
            *[_pair_coeff(index[kind], script.units, *laws[kind]) for kind in kinds], ""),
        "neighbors": section(
            f"# skin {number_text(script.skin)} {length}; ghosts: 1.5 sweep cells + skin, the fix's sweep needs them "
            f"(lammps_files)",
            f"neighbor {number_text(script.skin)} bin",
            "neigh_modify every 1 delay 0 check yes",
            f"comm_modify cutoff {number_text(script.ghost)}", ""),
        "fix": section(
            f"# heat capacity C_V ({script.unit('heat_capacity')}), friction gamma ({script.unit('friction')}), "
            f"conduction kappa ({script.unit('heat_conduction')})",
            # (an atomfile variable is read when defined: after the atoms)
            *([f"variable theta atomfile {TEMPERATURES_FILE}   # each particle's initial temperature"]
              if script.temperatures else []),
            " &\n    ".join(fix),
            f"variable conserved equal etotal+f_integrate   # f_integrate: the sum of the internal energies "
            f"({script.unit('energy')})",
            "timestep ${dt}"),
    }


def closing_sections(script):
    """The sections output and run."""
    return {
        "output": section(
            "thermo_style custom step temp pe ke etotal f_integrate v_conserved press",
            "# norm no: totals, as f_integrate is (lj units would divide the thermo energies by the atom count)",
            "thermo_modify norm no format float %.15g",
            "thermo ${thermo}"),
        "run": section("run ${steps}"),
    }
