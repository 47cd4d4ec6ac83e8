# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The report of a calibration (calibrate.calibrate): its rows in the units a reader of a fluid expects (MPa, mPa s,
W/(m K), J/(kg K)), the tables calibrate prints, the record that --json writes, and its figure (--plot)."""

import math

import numpy as np
from openmm import unit

from ..analysis.thermodynamics import adiabatic_bulk_modulus
from ..models.fluid import CONDUCTIVITY, VISCOSITY
from .calibration import Measured
from .results import PRESSURE_ROWS, Property, comparison, missed_properties

#: Fewer independent samples than this make a standard error itself uncertain by more than ~16%
#: (1/sqrt(2 N/g)): calibrate's table says so beside the row.
FEW_SAMPLES = 20
#: A property the model is not fitted to, measured back (the particles' self-diffusion against the molecules').
UNFITTED_DIFFUSION_ROW = "not fitted: self-diffusion (1e-9 m^2/s)"
#: The speed of sound derived from the written model's measured n dP/dn, (dP/dT)_n and c_v (speed_of_sound).
SOUND_ROW = "not fitted: speed of sound, from n dP/dn, (dP/dT)_n and c_v (m/s)"
#: The same speed measured directly: a standing sound wave (waves.sound_speed; not with --quick).
SOUND_WAVE_ROW = "measured: speed of sound, sound wave (m/s)"


def mpa(value):
    """kJ/mol/nm^3 -> MPa."""
    return (value * unit.kilojoule_per_mole / unit.nanometer**3 / unit.AVOGADRO_CONSTANT_NA).value_in_unit(
        unit.megapascal)


def m2_s(value):
    """nm^2/ps -> 1e-9 m^2/s."""
    return value * 1e-18 / 1e-12 / 1e-9


def j_kgk(value, parameters):
    """kJ/mol/K per particle -> J/(kg K) of the particle's mass."""
    return value * 1e3 / (parameters.mass * 1e-3)


def mpa_s(value):
    """amu/(nm ps) -> mPa s."""
    return (value * VISCOSITY / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.pascal * unit.second) * 1e3


def w_mk(value):
    """kJ/(mol ps nm K) -> W/(m K)."""
    return (value * CONDUCTIVITY / unit.AVOGADRO_CONSTANT_NA).value_in_unit(unit.watt / (unit.meter * unit.kelvin))


def scaled(measured, factor):
    return Measured(measured.value * factor, measured.error * factor, measured.samples)


def speed_of_sound(parameters, bulk_modulus, thermal_pressure, heat_capacity):
    """The model's speed of sound (nm/ps, Measured) at n0 and T0, derived from its measured isothermal n dP/dn
    (``bulk_modulus``, Measured, kJ/mol/nm^3), its measured thermal pressure coefficient (dP/dT)_n
    (``thermal_pressure``, Measured, kJ/mol/nm^3/K: the kinetic n k_B, the law's own and the structure's) and its
    isochoric heat capacity per particle (kJ/mol/K; Calibration.heat_capacity): c_s^2 = K_S/rho, K_S =
    thermodynamics.adiabatic_bulk_modulus. The error is K_T's and (dP/dT)_n's, propagated as independent."""
    n, t = parameters.density, parameters.temperature
    adiabatic = adiabatic_bulk_modulus(n, t, bulk_modulus.value, thermal_pressure.value, heat_capacity)
    rho = n * parameters.mass
    value = math.sqrt(adiabatic / rho)
    error = math.hypot(bulk_modulus.error,
                       2 * t * thermal_pressure.value * thermal_pressure.error / (n * heat_capacity))
    return Measured(value, error / (2 * rho * value))


def calibration_rows(stages, thermo, mapped):
    """The rows of a calibration's report, [(label or Property, target, Measured)], in the report's units, from its
    stages (calibrate.Stages, run), its last thermodynamics and its first round's (``mapped``)."""
    targets, final, m = stages.targets, stages.calibration.parameters, stages.measured
    expanding, conductivity_target = m["expanding"], w_mk(targets["thermal_conductivity"])
    heat = j_kgk(1.0, final)
    sound_target = targets["speed_of_sound"] * 1e3 if targets.get("speed_of_sound") else math.nan
    return [
        (Property.DENSITY, targets["density"], thermo["density"]),
        (PRESSURE_ROWS[0], mpa(targets["pressure"]), scaled(mapped["pressure"], mpa(1.0))),
        (Property.PRESSURE, mpa(targets["pressure"]), scaled(thermo["pressure"], mpa(1.0))),
        ("bulk modulus n dP/dn, B_T as mapped (MPa)", mpa(targets["bulk_modulus"]),
         scaled(m["bulk_runs"][0][1], mpa(1.0))),
        (Property.BULK_MODULUS, mpa(targets["bulk_modulus"]), scaled(m["bulk"], mpa(1.0))),
        ("particle-density response (n/n-bar) dn-bar/dn", 1.0, m["response"]),
        ("isochoric heat capacity c_v, C_V as mapped (J/(kg K))", j_kgk(targets["heat_capacity"], final),
         scaled(m["heat_capacity_mapped"], heat)),
        (Property.HEAT_CAPACITY, j_kgk(targets["heat_capacity"], final), scaled(thermo["heat_capacity"], heat)),
        (Property.KINETIC_TEMPERATURE, targets["temperature"], thermo["kinetic_temperature"]),
        (Property.HARMONIC_TEMPERATURE, targets["temperature"], thermo["harmonic_temperature"]),
        ("shear viscosity, wave, friction as mapped (mPa s)", mpa_s(targets["shear_viscosity"]),
         scaled(m["viscosity_runs"][0][1], mpa_s(1.0))),
        (Property.VISCOSITY_WAVE, mpa_s(targets["shear_viscosity"]), scaled(m["viscosity"], mpa_s(1.0))),
        (Property.VISCOSITY_FLOW, mpa_s(targets["shear_viscosity"]), scaled(m["poiseuille"], mpa_s(1.0))),
        (f"thermal conductivity, {'heat flux' if expanding else 'wave'}, kappa as mapped (W/(m K))",
         conductivity_target, scaled(m["conductivity_runs"][0][1], w_mk(1.0))),
        *([] if expanding else [(Property.CONDUCTIVITY_WAVE, conductivity_target,
                                 scaled(m["conductivity"], w_mk(1.0)))]),
        (Property.CONDUCTIVITY_HEAT_FLUX, conductivity_target, scaled(m["heat_flux"], w_mk(1.0))),
        *m["expansion_rows"],
        (UNFITTED_DIFFUSION_ROW, m2_s(targets["self_diffusion"]) if targets.get("self_diffusion") else math.nan,
         scaled(thermo["self_diffusion"], m2_s(1.0))),
        (SOUND_ROW, sound_target, scaled(m["sound"], 1e3)),
        *([] if m["sound_wave"] is None else [(SOUND_WAVE_ROW, sound_target, scaled(m["sound_wave"], 1e3))]),
    ]


def calibration_record(stages, results, missed, wall_time):
    """What calibrate --json writes: the fluid, the coarse-graining, the parameters before and after (reduced), the
    runs of every iteration, the thermal pressure (dP/dT)_n of the written model (MPa/K, its standard error) that the
    speed of sound is derived with, the results by label and what missed."""
    mapped, final, m = stages.mapped, stages.calibration.parameters, stages.measured
    return {"fluid": mapped.fluid.name, "molecules_per_particle": mapped.molecules_per_particle,
            "estimator": stages.calibration.estimator, "particles": stages.plan.particles,
            "cutoff_scaling": final.cutoff_scaling,
            "reference_pressure_shift": final.reference_pressure - mapped.reference_pressure,
            "parameters": mapped.reduced(), "runs": stages.calibration.runs, "wall_time_s": wall_time,
            "pressure_rounds": [[pi0, mpa(p.value), mpa(p.error)] for pi0, p in stages.pressures],
            "bulk_modulus_runs": [[x, mpa(v.value), mpa(v.error)] for x, v in m["bulk_runs"]],
            "friction_runs": [[x, mpa_s(v.value), mpa_s(v.error)] for x, v in m["viscosity_runs"]],
            "heat_conduction_runs": [[x, w_mk(v.value), w_mk(v.error)] for x, v in m["conductivity_runs"]],
            "thermal_pressure_mpa_per_k": [mpa(m["thermal_pressure"].value), mpa(m["thermal_pressure"].error)],
            "calibrated": final.reduced(), "results": results,
            "missed": [str(miss) for miss in missed], "missed_properties": missed_properties(missed)}


def parameter_table(parameters):
    """The mapped parameters in OpenMM and reduced units, a Markdown table."""
    reduced = parameters.reduced()
    rows = [("n0 (nm^-3)", parameters.density, "n0*"), ("pi0 (kJ/mol/nm^3)", parameters.reference_pressure, "pi0*"),
            ("B_T (kJ/mol/nm^3)", parameters.bulk_modulus, "B_T*"), ("gamma_T", parameters.tait_exponent, "gamma_T"),
            ("background pressure p_b (kJ/mol/nm^3)", parameters.background_pressure or 0.0, "p_b*"),
            ("cutoff R (nm)", parameters.cutoff, "R*"), ("friction (amu/ps)", parameters.friction, "gamma*"),
            ("heat conduction (kJ K/(mol ps))", parameters.heat_conduction, "kappa*"),
            ("C_V per particle (kJ/mol/K)", parameters.heat_capacity, "C_V*"),
            ("mass (amu)", parameters.mass, None), ("T0 (K)", parameters.temperature, "T0*")]
    return "\n".join(["| parameter | value | reduced |", "|---|---|---|"] + [
        f"| {name} | {value:.6g} | {reduced[key]:.6g} |" if key else f"| {name} | {value:.6g} | 1 |"
        for name, value, key in rows])


def melts_line(result):
    """One line on the melts of a calibration (Calibration.melt)."""
    melts = [steps for steps, _ in result.melt_steps] or [0]
    unsettled = sum(not stationary for _, stationary in result.melt_steps)
    return (f"Melts (until n-bar is stationary, Calibration.melt): {min(melts)} to {max(melts)} steps of dt* = "
            f"{result.plan.time_step:g} (the first in each box from the lattice, the others from the last melted "
            f"liquid)" + (f"; {unsettled} of {len(melts)} were not stationary after {result.plan.melt_limit} steps"
                          if unsettled else ""))


def changes_table(mapped, final):
    """The parameters calibrate moves, mapped and calibrated, a Markdown table."""
    lines = ["| parameter | mapped | calibrated | calibrated/mapped |", "|---|---|---|---|"]
    for name, attribute in (("f_cut", "cutoff_scaling"), ("pi0 (kJ/mol/nm^3)", "reference_pressure"),
                            ("B_T (kJ/mol/nm^3)", "bulk_modulus"), ("friction gamma (amu/ps)", "friction"),
                            ("heat conduction kappa (kJ K/(mol ps))", "heat_conduction"),
                            ("C_V (kJ/mol/K)", "heat_capacity"), ("beta (kJ/mol/nm^3/K)", "thermal_pressure")):
        first, last = getattr(mapped, attribute), getattr(final, attribute)
        if first is not None:
            lines.append(f"| {name} | {first:.6g} | {last:.6g} | {last / first if first else math.nan:.4g} |")
    return "\n".join(lines)


def results_table(result):
    """The targets and what the model gives, with model/target and the independent samples, a Markdown table."""
    lines = ["| property | target | model | model/target | independent samples |", "|---|---|---|---|---|"]
    bulk_target = mpa(result.mapped.targets()["bulk_modulus"])
    for row, target, measured in result.rows:
        name = row.label if isinstance(row, Property) else row
        samples = "" if measured.samples is None else f"{measured.samples:.0f}"
        time_series = not name.startswith(("shear", "thermal"))   # (the annotation of the report)
        if measured.samples is not None and measured.samples < FEW_SAMPLES and time_series:
            samples += f" (few: the error is uncertain by ~{100 / math.sqrt(2 * measured.samples):.0f}%)"
        lines.append(f"| {name} | {target:.5g} | {measured.value:.5g} +- {measured.error:.2g} | "
                     f"{comparison(row, target, measured.value, bulk_target).removeprefix('model/target = ')} | "
                     f"{samples} |")
    return "\n".join(lines)


def plot(record, path_stem):
    """The figure of a calibration (``record``: what --json writes) as path_stem.png and .pdf: model/target of every
    judged row with 2 standard errors, and the convergence of the iterations (the transport coefficients over their
    targets against the pair coefficient over its mapped value; the pressure, (P - P0) kappa_T, by round)."""
    from ..internal.plotting import panels, save
    figure, (table, transport, pressure) = panels(3, width=4.6)
    results = record["results"]
    names = [name for name in results if not name.startswith(("particle-density", "pressure"))
             and math.isfinite(results[name]["target"])]
    ratios = [results[name]["model"] / results[name]["target"] for name in names]
    bars = [2 * results[name]["error"] / results[name]["target"] for name in names]
    table.errorbar(ratios, range(len(names)), xerr=bars, fmt="o", color="k")
    table.axvspan(0.95, 1.05, color="0.85")
    table.axvline(1.0, color="0.5", lw=0.8)
    table.set_yticks(range(len(names)), [name.split(" (")[0] for name in names], fontsize=7)
    table.set_xlabel("model / target (2 standard errors)")
    table.invert_yaxis()
    for key, label, target in (("bulk_modulus_runs", "n dP/dn (B_T)", Property.BULK_MODULUS),
                               ("friction_runs", "viscosity (friction)", Property.VISCOSITY_WAVE),
                               ("heat_conduction_runs", "conductivity (kappa)", Property.CONDUCTIVITY_HEAT_FLUX)):
        runs = np.array(record[key])
        target = results[target.label]["target"]
        transport.errorbar(runs[:, 0] / runs[0, 0], runs[:, 1] / target, yerr=2 * runs[:, 2] / target, fmt="o-",
                           label=label)
    transport.axhspan(0.95, 1.05, color="0.85")
    transport.set_xlabel("parameter / mapped")
    transport.set_ylabel("measured / target")
    rounds = np.array(record["pressure_rounds"])
    modulus = results[Property.BULK_MODULUS.label]["target"]
    p0 = results[Property.PRESSURE.label]["target"]
    pressure.errorbar(np.arange(1, len(rounds) + 1), (rounds[:, 1] - p0) / modulus, yerr=2 * rounds[:, 2] / modulus,
                      fmt="o-", color="k")
    pressure.axhspan(-0.01, 0.01, color="0.85")
    pressure.set_xlabel("round of f_cut and pi0")
    pressure.set_ylabel("(P - P0) kappa_T")
    figure.suptitle(f"{record['fluid']}: {record['molecules_per_particle']:g} per particle, {record['estimator']}",
                    fontsize=9)
    save(figure, path_stem, legend_axis=transport)
