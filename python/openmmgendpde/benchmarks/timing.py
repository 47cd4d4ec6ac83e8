"""The analogue of Table IV of Colella et al. (2025) (`timing`): wall time per step of full GenDPDE (isoenergetic,
GenDPDEForce + GenDPDEIntegrator) with VA and with VB for each cutoff, and the VB/VA ratio, measured side by side:
both systems are prepared (thermostat at T0, internal energies drawn at T0), then their production steps run in
alternating rounds (openmmgendpde.benchmarks.measurement) and the ratio is the median of per-round ratios. The paper's
ratios (total simulation time, its own Fortran code) are 1.07, 1.22 and 1.03.
"""

import dataclasses

from openmm import unit

from ..cli.options import COUNT, add_cutoffs, add_rounds, chosen_cutoffs, platform_description
from ..cli.progress import Progress
from ..cli.protocol import add_protocol_arguments, protocol_from_arguments
from ..models.argon import ARGON_UNITS, PUBLISHED_TABLE4_RATIO, liquid_argon
from ..models.argon_runs import melt_then_draw
from .measurement import alternating_rounds, median, median_ratio


@dataclasses.dataclass
class TimingRow:
    cutoff: float
    milliseconds_per_step: dict   # estimator -> ms
    vb_over_va: float
    published: float


def prepared_simulation(cutoff, estimator, protocol, platform, preparation_time):
    """A Simulation of liquid argon ready for isoenergetic steps: melted with the thermostat for
    ``preparation_time`` and its internal energies drawn at T0 (openmmgendpde.models.argon_runs.melt_then_draw)."""
    argon = liquid_argon(protocol.num_particles, cutoff, estimator, time_step=protocol.time_step, seed=protocol.seed)
    simulation = argon.simulation(platform, velocity_seed=protocol.seed)
    melt_then_draw(argon, protocol.steps(preparation_time), protocol.seed)
    return simulation


def run(arguments):
    cutoffs = chosen_cutoffs(arguments)
    protocol = protocol_from_arguments(arguments, cutoffs=cutoffs, estimators=("VA", "VB"))
    rounds = arguments.rounds or (7 if arguments.quick else 15)
    steps = arguments.steps or (20 if arguments.quick else 50)
    preparation = 2.0 if arguments.quick else 10.0
    progress = Progress(len(cutoffs) * rounds, "timing", always=arguments.progress)
    rows = []
    for cutoff in cutoffs:
        progress.label = f"timing R*={cutoff}"
        prepared = {estimator: prepared_simulation(cutoff, estimator, protocol, arguments.platform, preparation)
                    for estimator in ("VA", "VB")}
        candidates = {estimator: (lambda integrator=prepared[estimator].integrator: integrator.step(steps))
                      for estimator in ("VA", "VB")}
        seconds = alternating_rounds(candidates, rounds, progress)
        rows.append(TimingRow(cutoff, {e: 1e3 * median(s) / steps for e, s in seconds.items()},
                              median_ratio(seconds, "VB", "VA"), PUBLISHED_TABLE4_RATIO[cutoff]))
    progress.finish()
    time_unit = ARGON_UNITS.unit("time").value_in_unit(unit.picosecond)
    print(f"Wall time per isoenergetic GenDPDE step, {protocol.num_particles} particles, dt* = {protocol.time_step} "
          f"({protocol.time_step * time_unit:.4f} ps), {platform_description(arguments)}; medians of {rounds} "
          f"alternating rounds of {steps} steps")
    print("| R_cut* | VA (ms/step) | VB (ms/step) | VB/VA | VB/VA published (Table IV) |")
    print("|---|---|---|---|---|")
    for row in rows:
        print(f"| {row.cutoff} | {row.milliseconds_per_step['VA']:.2f} | {row.milliseconds_per_step['VB']:.2f} "
              f"| {row.vb_over_va:.3f} | {row.published} |")
    return rows


def add_arguments(parser):
    add_protocol_arguments(parser)
    add_cutoffs(parser)
    add_rounds(parser, "15, quick 7")
    parser.add_argument("--steps", type=COUNT, help="steps per round (default 50, quick 20)")
    parser.set_defaults(run=run)
