# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The reporters of GenDPDE simulations, following OpenMM's reporter protocol: GenDPDEReporter (the thermodynamic
state) and StateDataReporter (OpenMM's, with the conserved energy and the harmonic-mean particle temperature)."""


from openmm import app, unit

from .analysis.thermodynamics import ThermodynamicProbe, conserved_energy, particle_temperature_means
from .internal.reporting import checked_choice, checked_file, checked_report_interval, open_file
from .units import ReducedUnits

_K = unit.kelvin
_DENSITY = unit.nanometer**-3
_PRESSURE = unit.kilojoule_per_mole / unit.nanometer**3
_ENERGY = unit.kilojoule_per_mole
_BAR_PER_PRESSURE = (1 * _PRESSURE / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.bar)


class GenDPDEReporter:
    """Writes, every ``reportInterval`` steps, one line of comma-separated values:

    step, time, kinetic temperature (in the centre-of-mass frame, 3N - 3 degrees of freedom, since GenDPDE
    conserves momentum), mean and harmonic-mean particle temperature theta_i, mean particle density n_i, the virial
    pressure P = (2K + W)/(3V) of every force but external fields (a body force, any CustomExternalForce: left out,
    docs/flows.md; one that shares a force group with another force that is not a GenDPDEForce is refused at the
    first report), the conserved energy K + U + sum eps_i and its drift relative to the first report, all as
    openmmgendpde.analysis.thermodynamics defines them.

    Use it like ``openmm.app.StateDataReporter``: ``simulation.reporters.append(GenDPDEReporter('log.csv', 100))``.
    It reports what the simulation allows and writes ``nan`` for the rest: theta and the conserved energy need a
    GenDPDEIntegrator, the density a GenDPDEForce, the pressure periodic boundaries; the drift is ``nan`` when the
    dynamics does not conserve the energy (Isothermal mode, other integrators).

    Parameters
    ----------
    file : str or file-like
        Where to write (a path, in an existing directory, is opened for writing, or appending if ``append``; or an
        open text stream).
    reportInterval : int
        Steps between reports, an integer >= 1.
    units : openmmgendpde.units.ReducedUnits, optional
        Report in these reduced units instead of OpenMM units (K, nm^-3, bar, kJ/mol).
    separator : str
        Between values (default ','): a non-empty string without a line break.
    append : bool
        Append to an existing file without a header.

    Every argument is checked when the reporter is made, before the file is created: a bad one raises
    OpenMMException naming it, its value and what is allowed.
    """

    def __init__(self, file, reportInterval, units=None, separator=",", append=False):
        name = "GenDPDEReporter"
        self._interval = checked_report_interval(name, reportInterval)
        file = checked_file(name, file)
        self._units = checked_choice(name, "units", units, lambda u: u is None or isinstance(u, ReducedUnits),
                                     "None (OpenMM units) or an openmmgendpde.units.ReducedUnits")
        self._separator = checked_choice(name, "separator", separator, lambda s: isinstance(s, str) and s != ""
                                         and "\n" not in s and "\r" not in s,
                                         "a non-empty string without a line break")
        append = checked_choice(name, "append", append, lambda a: isinstance(a, bool), "True or False")
        self._out, self._own = open_file(name, file, append)
        self._header_written = append
        self._first_energy = None
        self._probe = None

    def describeNextReport(self, simulation):
        steps = self._interval - simulation.currentStep % self._interval
        return (steps, False, True, False, True)

    def _columns(self):
        if self._units is None:
            return ["Step", "Time (ps)", "Kinetic temperature (K)", "Mean theta (K)", "Harmonic-mean theta (K)",
                    "Mean density (nm^-3)", "Virial pressure (bar)", "Conserved energy (kJ/mol)", "Relative drift"]
        return ["Step", "Time*", "Kinetic temperature*", "Mean theta*", "Harmonic-mean theta*", "Mean density*",
                "Virial pressure*", "Conserved energy*", "Relative drift"]

    def report(self, simulation, state):
        if self._probe is None:
            self._probe = ThermodynamicProbe(simulation.system)
        sample = self._probe.sample(state, simulation.context, simulation.integrator)
        energy = sample.conserved_energy.value_in_unit(_ENERGY)
        drift = float("nan")
        if sample.energy_is_conserved:
            if self._first_energy is None:
                self._first_energy = energy
            drift = (energy - self._first_energy) / abs(self._first_energy)
        if self._units is None:
            values = [sample.time.value_in_unit(unit.picosecond), sample.kinetic_temperature.value_in_unit(_K),
                      sample.mean_temperature.value_in_unit(_K), sample.harmonic_temperature.value_in_unit(_K),
                      sample.density.value_in_unit(_DENSITY),
                      sample.pressure.value_in_unit(_PRESSURE) * _BAR_PER_PRESSURE, energy]
        else:
            u = self._units
            values = [u.from_openmm(sample.time, "time"), u.from_openmm(sample.kinetic_temperature, "temperature"),
                      u.from_openmm(sample.mean_temperature, "temperature"),
                      u.from_openmm(sample.harmonic_temperature, "temperature"),
                      u.from_openmm(sample.density, "number_density"), u.from_openmm(sample.pressure, "pressure"),
                      u.from_openmm(sample.conserved_energy, "energy")]
        if not self._header_written:
            self._out.write("#" + self._separator.join(f'"{name}"' for name in self._columns()) + "\n")
            self._header_written = True
        self._out.write(self._separator.join([str(simulation.currentStep)] + [f"{v:.10g}" for v in values]
                                             + [f"{drift:.3e}"]) + "\n")
        self._out.flush()

    def __del__(self):
        if getattr(self, "_own", False):
            self._out.close()


class StateDataReporter(app.StateDataReporter):
    """openmm.app.StateDataReporter with two more columns for GenDPDE, after OpenMM's own (which are unchanged):

    conservedEnergy : bool=False
        "Conserved Energy (kJ/mole)": K + U + sum eps_i (GenDPDEIntegrator.getConservedEnergy), the energy the
        Isoenergetic and Conservative modes conserve. OpenMM's "Total Energy" is K + U without the particles'
        internal energies, which the dissipative and random forces fill and empty: it changes while this holds.
    harmonicTemperature : bool=False
        "Harmonic-mean Temperature (K)": <1/theta_i>^-1 of the particle temperatures, the thermodynamic temperature
        of GenDPDE (docs/theory.md section 8; the arithmetic mean is higher by 1 + k_B/C_V at equilibrium).

    Both are those of GenDPDEReporter (one definition: analysis.thermodynamics) and ``nan`` with another integrator.
    Every other argument is OpenMM's, in its order (``StateDataReporter(file, reportInterval, step=True, ...)``).
    A value other than True or False for the two raises OpenMMException before the file is opened.
    """

    def __init__(self, file, reportInterval, *args, conservedEnergy=False, harmonicTemperature=False, **kwargs):
        self._openedFile = False   # (read by OpenMM's __del__ if a check below refuses before the file is opened)
        for name, value in (("conservedEnergy", conservedEnergy), ("harmonicTemperature", harmonicTemperature)):
            checked_choice("StateDataReporter", name, value, lambda v: isinstance(v, bool), "True or False")
        super().__init__(file, reportInterval, *args, **kwargs)
        self._conservedEnergy = conservedEnergy
        self._harmonicTemperature = harmonicTemperature

    def _constructHeaders(self):
        headers = super()._constructHeaders()
        if self._conservedEnergy:
            headers.append("Conserved Energy (kJ/mole)")
        if self._harmonicTemperature:
            headers.append("Harmonic-mean Temperature (K)")
        return headers

    def _constructReportValues(self, simulation, state):
        values = super()._constructReportValues(simulation, state)
        if self._conservedEnergy:
            values.append(conserved_energy(simulation.integrator))
        if self._harmonicTemperature:
            values.append(particle_temperature_means(simulation.integrator)[1])
        return values
