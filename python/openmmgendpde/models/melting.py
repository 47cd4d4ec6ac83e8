# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The one "melt, then switch mode" of the package: a liquid melted from its lattice with the DPD thermostat
(Isothermal mode), then run in another mode with each particle's internal energy drawn from its equilibrium law.

Drawing the internal energies matters: theta_i = T for every particle would leave them k_B T per particle short of
equilibrium (their Gamma law of shape C_V/k_B + 1 has mean C_V T + k_B T), ~7% too cold for argon's C_V = 12.5 k_B.
Every protocol of the package that melts a liquid ends its melt here: the argon studies (argon_runs), a fluid model's
melted Context (fluid.FluidModel.melted), calibrate's runs, the slabs of the slab study and the step-size test."""

from ..api import GenDPDEIntegrator


def switch_after_melting(integrator, temperature, seed, mode=GenDPDEIntegrator.Isoenergetic):
    """The end of a melt: ``integrator`` in ``mode``, each internal energy drawn at ``temperature`` (K, or a
    Quantity) with ``seed`` (GenDPDEIntegrator.setInternalEnergiesToTemperature)."""
    integrator.setMode(mode)
    integrator.setInternalEnergiesToTemperature(temperature, seed)


def melt_then_switch(integrator, thermostat_steps, temperature, seed, mode=GenDPDEIntegrator.Isoenergetic,
                     step=None):
    """``thermostat_steps`` steps with the DPD thermostat at the integrator's temperature (Isothermal mode), then
    switch_after_melting. ``step(n)`` advances n steps: the integrator's own by default (pass e.g. Simulation.step,
    or a stepper that reports progress)."""
    integrator.setMode(GenDPDEIntegrator.Isothermal)
    (step or integrator.step)(thermostat_steps)
    switch_after_melting(integrator, temperature, seed, mode)
