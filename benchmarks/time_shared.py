# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Time the CPU platform alone and with a second copy of the same job running at once: what a user running two jobs
(or a notebook beside a job) sees. Candidates are GenDPDE steps (benchmarks/time_steps.py) under one or more Python
environments, e.g. an earlier build's and this one's, and OpenMM's own CPU platform on a plain Lennard-Jones liquid
of as many atoms with LangevinMiddleIntegrator, for scale. Rounds alternate the candidates; each prints the
milliseconds per step alone and of each of the two copies at once, then the medians and ranges over the rounds.

    python benchmarks/time_shared.py --python /tmp/before/bin/python --python .venv/bin/python --rounds 3

--spin 0 --spin 200 adds the last --python's build with each of these spins of its ThreadTeam (microseconds,
GENDPDE_THREAD_SPIN_US; the default is 20), to choose the default.

Every job uses the CPU platform's default Threads (one per core). Record the machine's load beside the figures: a
third job running meanwhile makes every figure one of contention.
"""

import argparse
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def openmm_job(num_particles, count):
    """ms per step of OpenMM's CPU platform: argon atoms (LJ, cutoff 1 nm) at liquid density, Langevin, 2 fs."""
    import numpy as np
    import openmm
    from openmm import unit
    side = int(round(num_particles ** (1 / 3)))
    spacing = (1 / 21.0) ** (1 / 3)   # 21 atoms/nm^3, liquid argon near 90 K
    grid = np.indices((side, side, side)).reshape(3, -1).T[:num_particles] * spacing
    system = openmm.System()
    box = side * spacing
    system.setDefaultPeriodicBoxVectors((box, 0, 0), (0, box, 0), (0, 0, box))
    force = openmm.NonbondedForce()
    force.setNonbondedMethod(openmm.NonbondedForce.CutoffPeriodic)
    force.setCutoffDistance(1.0)
    for _ in range(len(grid)):
        system.addParticle(39.948)
        force.addParticle(0.0, 0.34, 0.996)
    system.addForce(force)
    integrator = openmm.LangevinMiddleIntegrator(90 * unit.kelvin, 1 / unit.picosecond, 0.002 * unit.picoseconds)
    context = openmm.Context(system, integrator, openmm.Platform.getPlatformByName("CPU"))
    context.setPositions(grid)
    openmm.LocalEnergyMinimizer.minimize(context, maxIterations=50)
    integrator.step(10)
    start = time.perf_counter()
    integrator.step(count)
    return (time.perf_counter() - start) / count * 1e3


def job_command(candidate, arguments):
    """The command line of a candidate ("openmm", a Python, or "python@spin") and its environment."""
    if candidate == "openmm":
        return [sys.executable, __file__, "--job", "openmm", "--particles", str(arguments.particles),
                "--count", str(arguments.count)], dict(os.environ)
    python, _, spin = candidate.partition("@")
    environment = dict(os.environ, **({"GENDPDE_THREAD_SPIN_US": spin} if spin else {}))
    return [python, os.path.join(HERE, "time_steps.py"), "--state", arguments.state, "--platform", "CPU",
            "--count", str(arguments.count)], environment


def run_jobs(jobs):
    """Start the (command, environment) jobs together; return each one's printed milliseconds per step."""
    commands = [command for command, _ in jobs]
    processes = [subprocess.Popen(command, stdout=subprocess.PIPE, text=True, env=environment)
                 for command, environment in jobs]
    results = []
    for process in processes:
        output, _ = process.communicate()
        if process.returncode != 0:
            raise SystemExit(f"{' '.join(commands[0])} failed")
        results.append(float(output.split()[-1]))
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--python", action="append", default=[],
                        help="a Python environment whose openmmgendpde to time (repeat to compare builds)")
    parser.add_argument("--state", default="/tmp/argon4000.npz", help="time_steps.py's state (made if absent)")
    parser.add_argument("--particles", type=int, default=4000)
    parser.add_argument("--count", type=int, default=200, help="steps timed per job")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--spin", action="append", default=[],
                        help="also the last --python's build with this ThreadTeam spin (us; repeatable)")
    parser.add_argument("--no-openmm", action="store_true", help="leave out OpenMM's own CPU platform")
    parser.add_argument("--job", choices=("openmm",), help=argparse.SUPPRESS)
    arguments = parser.parse_args()
    if arguments.job == "openmm":
        print(f"{openmm_job(arguments.particles, arguments.count):.3f}")
        return
    pythons = arguments.python or [sys.executable]
    candidates = pythons + [f"{pythons[-1]}@{spin}" for spin in arguments.spin]
    candidates += [] if arguments.no_openmm else ["openmm"]
    if not os.path.exists(arguments.state):
        subprocess.run([candidates[0], os.path.join(HERE, "time_steps.py"), "--state", arguments.state,
                        "--particles", str(arguments.particles), "--count", "1"], check=True, stdout=subprocess.DEVNULL)
    alone = {c: [] for c in candidates}
    shared = {c: [] for c in candidates}
    for round_index in range(arguments.rounds):
        for candidate in candidates:
            job = job_command(candidate, arguments)
            alone[candidate] += run_jobs([job])
            shared[candidate] += run_jobs([job, job])
            print(f"round {round_index + 1} {candidate}: alone {alone[candidate][-1]:.2f} ms/step, two at once "
                  f"{shared[candidate][-2]:.2f} and {shared[candidate][-1]:.2f} ms/step "
                  f"(load {os.getloadavg()[0]:.2f})", flush=True)
    print("candidate: alone median (min-max) | two at once median (min-max) | slowdown")
    for candidate in candidates:
        a, s = alone[candidate], shared[candidate]
        print(f"{candidate}: {statistics.median(a):.2f} ({min(a):.2f}-{max(a):.2f}) | {statistics.median(s):.2f} "
              f"({min(s):.2f}-{max(s):.2f}) | {statistics.median(s) / statistics.median(a):.1f}x")


if __name__ == "__main__":
    main()
