# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The parameters of a fluid's model (GenDPDEParameters): every parameter of its GenDPDEForce and GenDPDEIntegrator
(model.ModelParameters) with the fluid, the coarse-graining and the estimator f_cut was tuned for, and the fluid's
model built from them (liquid). models.fluid.coarse_grain makes them from a fluid's properties; models.fluid_files
writes and reads them."""

import dataclasses
import numbers

from openmm import unit

from ..api import GenDPDEIntegrator, estimator_of, estimator_value
from ..units import BOLTZMANN, ReducedUnits
from .lattice import fcc_box
from .model import Model, ModelParameters
from .properties import HEAT_CAPACITY, Fluid


@dataclasses.dataclass(frozen=True, kw_only=True)
class GenDPDEParameters(ModelParameters):
    """Every parameter of GenDPDEForce and GenDPDEIntegrator for one fluid, coarse-graining level and cutoff, as plain
    floats in OpenMM units (nm, amu, ps, kJ/mol, K: model.ModelParameters, with its law and background pressure),
    with the targets they came from: the fluid, the molecules per particle, the particles within R at n0."""
    fluid: Fluid
    molecules_per_particle: float
    neighbors: float              # particles within R at n0
    #: The density estimator ('VA', 'VB', 'VC') that cutoff_scaling was tuned for; None where none was (a mapping's
    #: first estimate, or a model file of format 1, which did not record it). liquid() refuses another estimator
    #: that reads f_cut: V-C with V-B's f_cut does not give n0.
    estimator: str = None

    @property
    def units(self):
        """The reduced units of the model: mass of a particle, length n0^(-1/3), energy L^3/kappa_T (k_B = 1)."""
        length = self.density ** (-1 / 3)
        return ReducedUnits(mass=self.mass * unit.amu, length=length * unit.nanometer,
                            energy=length**3 * self.tait_exponent * self.bulk_modulus * unit.kilojoule_per_mole)

    def reduced(self):
        """The parameters in the model's reduced units (the paper's Table II for argon)."""
        u = self.units
        kb = BOLTZMANN.value_in_unit(HEAT_CAPACITY)
        return {
            "T0*": u.from_openmm(self.temperature, "temperature"),
            "n0*": u.from_openmm(self.density, "number_density"),
            "pi0*": u.from_openmm(self.reference_pressure, "pressure"),
            "B_T*": u.from_openmm(self.bulk_modulus, "pressure"),
            "gamma_T": self.tait_exponent,
            "R*": u.from_openmm(self.cutoff, "length"),
            "f_cut": self.cutoff_scaling,
            "gamma*": u.from_openmm(self.friction, "friction"),
            "kappa*": u.from_openmm(self.heat_conduction, "heat_conduction"),
            "C_V*": self.heat_capacity / kb,
            "p_b*": u.from_openmm(self.background_pressure or 0.0, "pressure"),
        }

    def targets(self):
        """The fluid's properties that the model should reproduce, in OpenMM units: pressure, bulk modulus
        1/kappa_T, temperature, viscosity, conductivity, the density n0, and the isochoric heat capacity of the
        molecules of one particle (kJ/mol/K); and those it is not fitted to, None where the fluid has none:
        self_diffusion, speed_of_sound and surface_tension (kJ/mol/nm^2)."""
        f = self.fluid.in_openmm()
        return {"density": self.density, "pressure": f["pressure"], "bulk_modulus": 1 / f["compressibility"],
                "temperature": f["temperature"], "shear_viscosity": f["shear_viscosity"],
                "heat_capacity": self.molecules_per_particle * f["heat_capacity"],
                "thermal_conductivity": f["thermal_conductivity"], "self_diffusion": f.get("self_diffusion"),
                "speed_of_sound": f.get("speed_of_sound"), "surface_tension": f.get("surface_tension"),
                "thermal_expansion": f.get("thermal_expansion")}

    def with_cutoff_scaling(self, cutoff_scaling, estimator=None):
        """The parameters with f_cut = ``cutoff_scaling``, tuned for ``estimator`` (default: the one recorded)."""
        return dataclasses.replace(self, cutoff_scaling=cutoff_scaling, estimator=estimator or self.estimator)

    def for_estimator(self, estimator):
        """The parameters with ``estimator`` recorded as the one f_cut is for (calibrate and tune-fcut, which tune
        f_cut for it from this start)."""
        return dataclasses.replace(self, estimator=estimator_of(estimator).name)

    def checked_estimator(self, estimator=None):
        """The estimator's name that liquid() builds with: ``estimator``, by default the recorded one (else 'VB'); a
        ValueError where f_cut was tuned for another estimator that reads f_cut (V-A does not: the table's
        reads_cutoff_scaling)."""
        chosen = estimator_of(estimator or self.estimator or "VB")
        name = chosen.name
        if self.estimator is not None and name != self.estimator and chosen.reads_cutoff_scaling:
            raise ValueError(f"estimator = {name!r} is not allowed for this model: its f_cut = "
                             f"{self.cutoff_scaling:.6g} was tuned for {self.estimator}, and with {name} it does not "
                             f"give the density n0; tune f_cut for {name} (calibrate --fluid FILE --estimator {name} "
                             f"--output NEW, or tune-fcut) and use with_cutoff_scaling(f_cut, {name!r})")
        return name

    def with_transport(self, friction, heat_conduction):
        return dataclasses.replace(self, friction=friction, heat_conduction=heat_conduction)

    def liquid(self, num_particles=None, estimator=None, mode=GenDPDEIntegrator.Isoenergetic, time_step=0.01,
               seed=0, density=None, cells=None):
        """The fluid at n0 (or ``density``, nm^-3) in a periodic box on an FCC lattice: a cube of num_particles = 4 m^3
        particles, or ``cells`` = (n_x, n_y, n_z) cubic FCC cells (any rectangular box: slabs, elongated boxes).
        Returns a model.Model (built by ModelParameters.build) with its System (one GenDPDEForce), GenDPDEIntegrator
        (step ``time_step`` in reduced time units, bath temperature T0), topology and positions (nm). ``estimator``:
        by default the one f_cut was tuned for (else V-B); another that reads f_cut is refused (checked_estimator)."""
        estimator = self.checked_estimator(estimator)
        density = self.density if density is None else density
        if cells is None:
            if num_particles is None:
                raise ValueError("give num_particles (4 m^3, a cube) or cells = (n_x, n_y, n_z)")
            integral = isinstance(num_particles, numbers.Integral) and num_particles > 0
            m = round((num_particles / 4) ** (1 / 3)) if integral else 0
            if m < 1 or 4 * m**3 != num_particles:
                raise ValueError(f"num_particles = {num_particles} is not allowed; a cube holds 4 m^3 "
                                 f"(500, 864, 2048, 4000, ...); give cells for other boxes")
            cells = (m, m, m)
        positions, box = fcc_box(density, cells)
        widths = [box[k][k] for k in range(3)]
        if self.cutoff > min(widths) / 2:
            raise ValueError(f"the box {widths[0]:.3f} x {widths[1]:.3f} x {widths[2]:.3f} nm is less than twice the "
                             f"cutoff {self.cutoff:.3f} nm across; use more cells")
        step = self.units.to_openmm(time_step, "time").value_in_unit(unit.picosecond)
        return self.build(box, positions, estimator_value(estimator), step, seed, mode)


#: The model of a fluid is a model.Model (its parameters a GenDPDEParameters); the name of version 0.2.
FluidModel = Model
