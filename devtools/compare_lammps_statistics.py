# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Liquid argon, Table III's V-B row at R* = 1.6839, in both engines: the OpenMM CPU platform and the project's
LAMMPS package (pair_style gendpde + fix gendpde), from one melted state; prints a markdown table of the production
averages with block-average standard errors, beside the published values and the exact equilibrium identities.

Protocol (openmmgendpde.models.argon_runs, the `table3` study's; reduced units of ARGON_UNITS, time unit 0.8962 ps):
the FCC lattice melts on OpenMM (CPU platform) with the DPD thermostat at T0 for --thermostat time units, then the
internal energies are drawn from their equilibrium Gamma law at T0 (models.melting.melt_then_switch). That state
(positions, on-step velocities v + (dt/2) F/m) becomes the LAMMPS data file (models.lammps_files.lammps_input, metal
units), and OpenMM's drawn eps_i become the fix's (initial v_theta: an atomfile variable of each particle's
temperature eps_i/C_V): both engines start from the same state and total energy K + U + sum eps_i (printed, to
check). Then each engine runs --equilibration and
--production time units of isoenergetic GenDPDE, sampled every --sample-interval:

- OpenMM: models.argon_runs.production (analysis.thermodynamics.ThermodynamicProbe: T_kin = 2 K_int/((3N - 3) k_B),
  theta_i from the integrator, n-bar from GenDPDEForce.getParticleDensities, P from the exact virial);
- LAMMPS (each of --ranks): thermo temp (K), press (bar), v_conserved = etotal + f_integrate (eV) at each sample, and
  a dump of the positions and eps_i (f_integrate[]) at the same steps; n-bar* of each frame from the same
  GenDPDEForce.getParticleDensities on an OpenMM Context at the frame's positions, theta_i = eps_i/C_V.

Standard errors: analysis.statistics.block_average (10 blocks, with its plateau check; a summary line says whether every
error bar reached its plateau). Drift: the slope of a straight-line fit of K + U + sum eps_i over the production, per
particle (as the speed-vs-error study measures it). Identities (docs/theory.md section 8): T_kin/T_harm = 1 - 1/A and
<theta>/T_harm = (1 + k_B/C_V)(1 - 1/A), A = (3N - 3)/2 + N (C_V/k_B + 1), each as the block average of its per-sample
ratio. The last columns are (LAMMPS - OpenMM)/sqrt(s_L^2 + s_O^2). LAMMPS's metal k_B is 1.13e-6 relatively larger
than OpenMM's (models.lammps_files), so the engines agree statistically, not step by step.

    .venv/bin/python devtools/compare_lammps_statistics.py                      # 4000 particles, the study's lengths
    .venv/bin/python devtools/compare_lammps_statistics.py --ranks 1 --production 20 --particles 2048   # a quick try

Needs lammps/build.sh's build (build/lammps/lammps/lmp with MPI, build/lammps/plugin/gendpdeplugin.so). Time on the
2-core development machine with the defaults (4000 particles, dt* = 0.005, 20 + 20 + 200 time units, ranks 1 and 2):
11 minutes, one run after the other (melt 9 s; OpenMM CPU, 2 threads, 136 s for 44,000 steps with the samples;
LAMMPS 285 s on 1 rank, 6.5 ms/step, and 200 s on 2, 4.5 ms/step, with the dump; each dump ~80 MB).
"""

import argparse
import dataclasses
import math
import pathlib
import shutil
import subprocess
import tempfile
import time
import warnings

import numpy as np
import openmm
from openmm import unit

from openmmgendpde.analysis.statistics import BlockAverageWarning, block_average
from openmmgendpde.models.argon import ARGON_STATE, ARGON_UNITS, PUBLISHED_TABLE3, liquid_argon
from openmmgendpde.models.argon_runs import FULL, Samples, melt_then_draw, production, stepper
from openmmgendpde.models.lammps_files import lammps_input, thermo_table, write_lammps_input
from openmmgendpde.models.lammps_units import ENERGY, in_units
from openmmgendpde.studies.table3 import sampling_summary

CUTOFF = 1.6839
ESTIMATOR = "VB"
ROOT = pathlib.Path(__file__).resolve().parents[1]
KJ = unit.kilojoule_per_mole
PRESSURE = KJ / unit.nanometer**3
#: 1 bar in kJ/mol/nm^3 (LAMMPS's metal pressure unit, per mole).
BAR = (1.0 * unit.bar * unit.AVOGADRO_CONSTANT_NA).value_in_unit(PRESSURE)
#: The script's run section (lammps_files.SECTIONS): equilibration, then production with a dump of the positions and
#: internal energies at every thermo step.
RUNS = """variable equilibration index {equilibration}
variable production index {production}
run ${{equilibration}}
dump frames all custom ${{thermo}} frames.dump id x y z f_integrate
dump_modify frames sort id format float %.10g
run ${{production}}
"""


def arguments():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--particles", type=int, default=FULL.num_particles, help="4 m^3 (default %(default)s)")
    parser.add_argument("--time-step", type=float, default=FULL.time_step, help="dt* (default %(default)s)")
    parser.add_argument("--thermostat", type=float, default=FULL.thermostat_time,
                        help="melting time* with the DPD thermostat, OpenMM (default %(default)s)")
    parser.add_argument("--equilibration", type=float, default=FULL.equilibration_time,
                        help="isoenergetic equilibration time*, each engine (default %(default)s)")
    parser.add_argument("--production", type=float, default=FULL.production_time,
                        help="production time* (default %(default)s)")
    parser.add_argument("--sample-interval", type=float, default=FULL.sample_interval,
                        help="time* between samples (default %(default)s)")
    parser.add_argument("--seed", type=int, default=FULL.seed, help="random seed (default %(default)s)")
    parser.add_argument("--threads", type=int, default=2, help="threads of OpenMM's CPU platform (default 2)")
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2], help="LAMMPS MPI ranks (default 1 2)")
    parser.add_argument("--lmp", type=pathlib.Path, default=ROOT / "build/lammps/lammps/lmp")
    parser.add_argument("--plugin", type=pathlib.Path, default=ROOT / "build/lammps/plugin/gendpdeplugin.so")
    parser.add_argument("--workdir", type=pathlib.Path,
                        help="keep the LAMMPS files (inputs, logs, dumps) here (default: a temporary directory)")
    return parser.parse_args()


def melted_state(protocol, platform="CPU"):
    """The OpenMM run through the melt and the draw of the internal energies (argon_runs.run_argon's first phases):
    (argon, simulation, advance, positions nm, on-step velocities nm/ps, internal energies kJ/mol, K + U + sum eps
    kJ/mol)."""
    argon = liquid_argon(protocol.num_particles, CUTOFF, ESTIMATOR, None, protocol.time_step, seed=protocol.seed)
    simulation = argon.simulation(platform, velocity_seed=protocol.seed)
    advance = stepper(argon.integrator)
    melt_then_draw(argon, protocol.steps(protocol.thermostat_time), protocol.seed, advance)
    state = simulation.context.getState(getPositions=True, getVelocities=True, getForces=True)
    positions = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)
    velocities = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)
    forces = state.getForces(asNumpy=True).value_in_unit(KJ / unit.nanometer)
    mass = argon.system.getParticleMass(0).value_in_unit(unit.amu)
    step = argon.integrator.getStepSize().value_in_unit(unit.picosecond)
    velocities = velocities + 0.5 * step * forces / mass   # OpenMM keeps them half a step behind (docs/integrator.md)
    energies = np.asarray(argon.integrator.getInternalEnergies().value_in_unit(KJ))
    conserved = argon.integrator.getConservedEnergy().value_in_unit(KJ)
    return argon, simulation, advance, positions, velocities, energies, conserved


def run_openmm(protocol, argon, simulation, advance):
    """Equilibration and production (argon_runs.production): (Samples, wall seconds of both)."""
    start = time.perf_counter()
    advance(protocol.steps(protocol.equilibration_time))
    samples = production(argon, simulation, protocol, 0, advance)
    return samples, time.perf_counter() - start


def dump_frames(path, count):
    """{step: array count x 4 (x, y, z in Å, eps_i in eV), sorted by atom id} of a LAMMPS custom dump."""
    lines = pathlib.Path(path).read_text().splitlines()
    frames, block = {}, 9 + count
    for start in range(0, len(lines) - block + 1, block):
        step = int(lines[start + 1])
        table = np.array(" ".join(lines[start + 9:start + block]).split(), dtype=float).reshape(count, 5)
        frames[step] = table[:, 1:]
    return frames


def run_lammps(protocol, directory, texts, ranks, lmp, plugin):
    """Run the LAMMPS input ``texts`` (with each particle's initial temperature: lammps_input's temperatures) in
    ``directory`` on ``ranks`` ranks: (thermo rows, frames, wall seconds, loop seconds)."""
    directory.mkdir(parents=True, exist_ok=True)
    write_lammps_input(directory, texts)
    command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), str(lmp), "-var", "plugin",
               str(plugin), "-in", "in.gendpde", "-log", "log.lammps", "-screen", "none"]
    start = time.perf_counter()
    result = subprocess.run(command, cwd=directory, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.perf_counter() - start
    log = (directory / "log.lammps").read_text() if (directory / "log.lammps").is_file() else ""
    if result.returncode != 0:
        raise SystemExit(f"LAMMPS failed ({' '.join(command)} in {directory}):\n{result.stdout[-3000:]}\n{log[-3000:]}")
    loop = sum(float(line.split()[3]) for line in log.splitlines() if line.startswith("Loop time of"))
    return thermo_table(log), dump_frames(directory / "frames.dump", protocol.num_particles), wall, loop


def lammps_samples(protocol, rows, frames, heat_capacity_ev, density_context, force):
    """Samples (reduced units, as argon_runs.Samples) of the LAMMPS production: each thermo row and dump frame
    after the equilibration."""
    samples = Samples()
    first = protocol.steps(protocol.equilibration_time)
    steps = sorted(step for step in frames if step > first)
    missing = [step for step in steps if step not in rows]
    if missing or len(steps) != protocol.steps(protocol.production_time) // protocol.steps(protocol.sample_interval):
        raise SystemExit(f"LAMMPS output: {len(steps)} production frames, thermo missing at {missing[:5]}")
    for step in steps:
        row, frame = rows[step], frames[step]
        samples.time.append(step * protocol.time_step)
        samples.kinetic_temperature.append(ARGON_UNITS.from_openmm(row["Temp"] * unit.kelvin, "temperature"))
        theta = frame[:, 3] / heat_capacity_ev   # K
        samples.harmonic_temperature.append(ARGON_UNITS.from_openmm(1 / np.mean(1 / theta) * unit.kelvin,
                                                                    "temperature"))
        samples.mean_temperature.append(ARGON_UNITS.from_openmm(np.mean(theta) * unit.kelvin, "temperature"))
        samples.pressure.append(ARGON_UNITS.from_openmm(row["Press"] * BAR * PRESSURE, "pressure"))
        samples.conserved_energy.append(ARGON_UNITS.from_openmm(row["v_conserved"] / ENERGY * KJ, "energy"))
        density_context.setPositions(frame[:, :3] * 0.1)   # Å -> nm
        densities = force.getParticleDensities(density_context).value_in_unit(unit.nanometer**-3)
        samples.density.append(ARGON_UNITS.from_openmm(np.mean(densities) * unit.nanometer**-3, "number_density"))
    samples.steps = len(steps) * protocol.steps(protocol.sample_interval)
    return samples


@dataclasses.dataclass
class Row:
    label: str
    reference: str      # published or exact value, as text
    values: list        # (mean, standard error or None) per engine
    digits: int


def rows_of(samples_by_engine, num_particles):
    """The table's rows from each engine's Samples."""
    published = PUBLISHED_TABLE3[CUTOFF][ESTIMATOR]
    c = ARGON_STATE.heat_capacity
    a = (3 * num_particles - 3) / 2 + num_particles * (c + 1)

    def averages(name, series):
        return [block_average(series(s), name=f"{engine} {name}") for engine, s in samples_by_engine.items()]

    def field(name):
        return lambda s: getattr(s, name)

    def ratio(top, bottom):
        return lambda s: np.array(getattr(s, top)) / np.array(getattr(s, bottom))

    def drift(s):
        return np.polyfit(s.time, s.conserved_energy, 1)[0] / num_particles

    return [
        Row("T* (kinetic)", f"{published['T']:.4f}", averages("T_kin", field("kinetic_temperature")), 5),
        Row("T* (harmonic mean of theta_i)", f"{published['T']:.4f}",
            averages("T_harm", field("harmonic_temperature")), 5),
        Row("n-bar*", f"{published['n']:.3f}", averages("n-bar*", field("density")), 4),
        Row("P*", f"{published['P']:.3f}", averages("P*", field("pressure")), 4),
        Row("T_kin/T_harm", f"{1 - 1 / a:.5f} (1 - 1/A)",
            averages("T_kin/T_harm", ratio("kinetic_temperature", "harmonic_temperature")), 5),
        Row("<theta>/T_harm", f"{(1 + 1 / c) * (1 - 1 / a):.5f} ((1 + k_B/C_V)(1 - 1/A))",
            averages("<theta>/T_harm", ratio("mean_temperature", "harmonic_temperature")), 5),
        Row("drift of K + U + sum eps (u per particle per time*)", "0",
            [(drift(s), None) for s in samples_by_engine.values()], 8),
    ]


def format_table(engines, rows):
    others = engines[1:]
    head = ["quantity", "published / exact", *engines] + [f"({e} - {engines[0]})/sigma" for e in others]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for row in rows:
        cells = [row.label, row.reference]
        for mean, error in row.values:
            cells.append(f"{mean:.{row.digits}f} +- {error:.{row.digits}f}" if error is not None else f"{mean:+.2e}")
        base_mean, base_error = row.values[0]
        for mean, error in row.values[1:]:
            cells.append(f"{(mean - base_mean) / math.hypot(error, base_error):+.1f}" if error is not None else "")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main():
    options = arguments()
    protocol = dataclasses.replace(FULL, num_particles=options.particles, time_step=options.time_step,
                                   thermostat_time=options.thermostat, equilibration_time=options.equilibration,
                                   production_time=options.production, sample_interval=options.sample_interval,
                                   seed=options.seed)
    openmm.Platform.getPlatformByName("CPU").setPropertyDefaultValue("Threads", str(options.threads))
    every = protocol.steps(protocol.sample_interval)
    print(f"Liquid argon, R* = {CUTOFF} {ESTIMATOR}: {protocol.num_particles} particles, dt* = {protocol.time_step}; "
          f"OpenMM CPU ({options.threads} threads) melts {protocol.thermostat_time} time* with the thermostat and "
          f"draws eps_i; then each engine: {protocol.equilibration_time} isoenergetic equilibration + "
          f"{protocol.production_time} production ({protocol.steps(protocol.production_time)} steps), samples every "
          f"{protocol.sample_interval} ({every} steps)", flush=True)

    start = time.perf_counter()
    argon, simulation, advance, positions, velocities, energies, conserved = melted_state(protocol)
    melt_wall = time.perf_counter() - start
    heat_capacity = argon.integrator.getHeatCapacity().value_in_unit(KJ / unit.kelvin)
    temperatures = energies / heat_capacity   # K: the fix's eps_i = C_V theta_i
    fresh = liquid_argon(protocol.num_particles, CUTOFF, ESTIMATOR, None, protocol.time_step, seed=protocol.seed)
    texts = lammps_input(fresh.system, fresh.integrator, positions, velocities, thermo=every,
                         title=f"liquid argon R* = {CUTOFF} {ESTIMATOR} melted on OpenMM", temperatures=temperatures)
    runs = RUNS.format(equilibration=protocol.steps(protocol.equilibration_time),
                       production=protocol.steps(protocol.production_time))
    texts = dataclasses.replace(texts, sections={**texts.sections, "run": runs})
    print(f"Melted in {melt_wall:.0f} s; both engines start from OpenMM's drawn eps_i (theta_i from "
          f"{temperatures.min():.1f} to {temperatures.max():.1f} K)", flush=True)

    samples, walls = {}, {}
    samples["OpenMM CPU"], walls["OpenMM CPU"] = run_openmm(protocol, argon, simulation, advance)
    print(f"OpenMM: {walls['OpenMM CPU']:.0f} s for equilibration and production", flush=True)

    workdir = options.workdir or pathlib.Path(tempfile.mkdtemp(prefix="gendpde-lammps-statistics-"))
    density_context = fresh.simulation("CPU").context
    heat_capacity_ev = in_units(heat_capacity, "heat_capacity", "metal")
    n = protocol.num_particles
    try:
        for ranks in options.ranks:
            name = f"LAMMPS {ranks} rank{'s' if ranks > 1 else ''}"
            rows, frames, wall, loop = run_lammps(protocol, workdir / f"ranks{ranks}", texts, ranks, options.lmp,
                                                  options.plugin)
            start_energy = ARGON_UNITS.from_openmm(rows[0]["v_conserved"] / ENERGY * KJ, "energy")
            per_step = 1e3 * loop / (protocol.steps(protocol.equilibration_time)
                                     + protocol.steps(protocol.production_time))
            print(f"{name}: {wall:.0f} s ({per_step:.2f} ms/step in LAMMPS's loops); "
                  f"K + U + sum eps at the start {start_energy / n:.9f} u per particle, OpenMM's "
                  f"{ARGON_UNITS.from_openmm(conserved * KJ, 'energy') / n:.9f}", flush=True)
            samples[name] = lammps_samples(protocol, rows, frames, heat_capacity_ev, density_context, fresh.force)
            walls[name] = wall
    finally:
        if options.workdir is None:
            shutil.rmtree(workdir, ignore_errors=True)

    lammps = [name for name in samples if name.startswith("LAMMPS")]
    for name in lammps[1:]:   # one trajectory to rounding at first (the same sweep); rounding grows over a long run
        fields = ("kinetic_temperature", "harmonic_temperature", "density", "pressure", "conserved_energy")
        largest = max(float(np.max(np.abs(np.subtract(getattr(samples[name], f), getattr(samples[lammps[0]], f)))
                                   / np.max(np.abs(getattr(samples[lammps[0]], f))))) for f in fields)
        print(f"{name} against {lammps[0]}: largest relative difference of a sample {largest:.1e}")
    with warnings.catch_warnings(record=True) as unsettled:
        warnings.simplefilter("always", BlockAverageWarning)
        rows = rows_of(samples, n)
    print()
    print(format_table(list(samples), rows))
    print()
    print(sampling_summary([w for w in unsettled if issubclass(w.category, BlockAverageWarning)],
                           sum(1 for row in rows for _, error in row.values if error is not None), verbose=True))
    print(f"Published values: Table III (+-0.0001 for T*, +-0.001 otherwise); k_B T0* = {ARGON_STATE.temperature}. "
          f"Wall times: " + ", ".join(f"{engine} {seconds:.0f} s" for engine, seconds in walls.items())
          + f"; melt (OpenMM) {melt_wall:.0f} s.")


if __name__ == "__main__":
    main()
