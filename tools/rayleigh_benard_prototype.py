"""PROTOTYPE, not an example: it does not show convection. A liquid layer heated from below in gravity
(Rayleigh-Benard), kept for the next attempt (docs/thermal.md, "Not done yet", says why it failed).

Setup: liquid argon with thermal expansion (fluid.ARGON_EXPANDING) coarse-grained to --atoms per particle (20
neighbours within the cutoff); a quasi-2D layer (16 x 3 FCC cells, 8 deep) between two walls of frozen particles
(mass 0, 3 cells each) whose particle temperatures are put back every 20 steps to T0 +- dT/2 (the energy put in and
taken out is the heat flux); gravity and a stiff repulsion at the walls' faces on the liquid (one
CustomExternalForce); the liquid starts on the conduction profile plus one roll's temperature pattern
(--perturbation K), Isoenergetic. Printed per window: the flux over dT (relative to the first dT's last window),
and the root mean square of the window's mean velocity over the grid's cells against that of thermal noise.
Ra = g alpha (dT - dT_ad) H^3/(nu D_T) with the fluid's nu, D_T and alpha (not the model's, unmeasured), and the
adiabatic difference dT_ad = g H alpha T0/c_p.

Measured (this machine, CPU): at 40,000 atoms per particle, dT = 80 K, nominal Ra = 6.2 x 1708, dt* = 0.2, 40,000
steps (100 s): the roll pattern decays (flow/noise 5.65 -> 2.0 in two windows) and the flux stays that of
conduction. The particles do not diffuse at that level (k_B T0 ~ 1e-6 of the model's energy unit L^3/kappa_T): the
layer is a solid lattice.

    .venv/bin/python tools/rayleigh_benard_prototype.py --atoms 40000 --differences 80 --steps 40000 --time-step 0.2
"""

import argparse
import math

import numpy as np
import openmm
from openmm import unit

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.fluid import ARGON_EXPANDING, coarse_grain

CELLS = (16, 3, 14)          # FCC cells along x, y, z: 3 of wall, 8 of liquid, 3 of wall
WALL_CELLS = 3


def build(parameters, gravity, seed, time_step):
    """The model with frozen walls and the CustomExternalForce (gravity and the walls' faces) on the liquid."""
    model = parameters.liquid(cells=CELLS, mode=GenDPDEIntegrator.Isothermal, time_step=time_step, seed=seed)
    cell = model.system.getDefaultPeriodicBoxVectors()[2][2].value_in_unit(unit.nanometer) / CELLS[2]
    z = model.positions[:, 2]
    bottom_face, top_face = (WALL_CELLS - 0.25) * cell, (CELLS[2] - WALL_CELLS - 0.25) * cell
    hot, cold = z < bottom_face, z > top_face
    external = openmm.CustomExternalForce("stiffness*(step(bottom-z)*(bottom-z)^2 + step(z-top)*(z-top)^2)"
                                          " + weight*z")
    external.addGlobalParameter("stiffness", 100 * parameters.bulk_modulus * parameters.density ** (-1 / 3))
    external.addGlobalParameter("bottom", bottom_face)
    external.addGlobalParameter("top", top_face)
    external.addGlobalParameter("weight", parameters.mass * gravity)
    for i in range(model.num_particles):
        if hot[i] or cold[i]:
            model.system.setParticleMass(i, 0.0)
        else:
            external.addParticle(i)
    model.system.addForce(external)
    return model, hot, cold, (bottom_face, top_face)


def run(parameters, difference, gravity, steps, windows, platform, seed, grid, time_step, perturbation,
        reset_every=20, sample_every=100):
    """One run at the wall difference ``difference`` (K), in ``windows`` windows of equal length: for each, the heat
    flux (kJ/mol/ps, the mean of what the hot wall gives and the cold one takes), the flow (root mean square over
    the grid's cells of the window's mean velocity, x and z, nm/ps) and its noise (the same for thermal noise
    alone); and the last window's mean velocity and theta fields."""
    model, hot, cold, (bottom, top) = build(parameters, gravity, seed, time_step)
    integrator = model.integrator
    t0 = parameters.temperature
    t_hot, t_cold = t0 + difference / 2, t0 - difference / 2
    context = model.melted(platform, GenDPDEIntegrator.Isoenergetic, 1000, 0, seed=seed)
    box = [model.system.getDefaultPeriodicBoxVectors()[k][k].value_in_unit(unit.nanometer) for k in range(3)]
    x, z = model.positions[:, 0], model.positions[:, 2]
    height = np.clip((z - bottom) / (top - bottom), 0, 1)
    # The conduction profile, and one roll's temperature pattern of amplitude ``perturbation`` (K) to grow or decay.
    integrator.setParticleTemperatures(list(t_hot + (t_cold - t_hot) * height + perturbation
                                            * np.sin(2 * np.pi * x / box[0]) * np.sin(np.pi * height)))
    capacity = parameters.heat_capacity
    liquid = ~(hot | cold)
    nx, nz = grid
    dt = integrator.getStepSize().value_in_unit(unit.picosecond)
    per_window = steps // windows // sample_every * sample_every
    rows = []
    for window in range(windows):
        sums, counts, theta_sums = np.zeros((3, nx, nz)), np.zeros((nx, nz)), np.zeros((nx, nz))
        heat_in = heat_out = kinetic = 0.0
        samples = 0
        for step in range(reset_every, per_window + 1, reset_every):
            integrator.step(reset_every)
            theta = np.asarray(integrator.getParticleTemperatures().value_in_unit(unit.kelvin))
            heat_in += capacity * float(np.sum(t_hot - theta[hot]))
            heat_out += capacity * float(np.sum(theta[cold] - t_cold))
            theta[hot], theta[cold] = t_hot, t_cold
            integrator.setParticleTemperatures(list(theta))
            if step % sample_every == 0:
                state = context.getState(getPositions=True, getVelocities=True, enforcePeriodicBox=True)
                r = state.getPositions(asNumpy=True).value_in_unit(unit.nanometer)[liquid]
                v = state.getVelocities(asNumpy=True).value_in_unit(unit.nanometer / unit.picosecond)[liquid]
                ix = np.clip((r[:, 0] / box[0] * nx).astype(int), 0, nx - 1)
                iz = np.clip(((r[:, 2] - bottom) / (top - bottom) * nz).astype(int), 0, nz - 1)
                for k in range(3):
                    np.add.at(sums[k], (ix, iz), v[:, k])
                np.add.at(counts, (ix, iz), 1)
                np.add.at(theta_sums, (ix, iz), theta[liquid])
                kinetic += float(np.sum(v * v)) / (3 * len(v))
                samples += 1
        mean_velocity = sums / np.maximum(counts, 1)
        # A cell's mean of N samples of pure thermal noise has the variance <v^2>/N per component.
        noise = math.sqrt(kinetic / samples * float(np.mean(1 / np.maximum(counts, 1))))
        flow = math.sqrt(float(np.mean(mean_velocity[0] ** 2 + mean_velocity[2] ** 2)) / 2)
        rows.append({"time": (window + 1) * per_window * dt, "flux": (heat_in + heat_out) / 2 / (per_window * dt),
                     "flow": flow, "noise": noise, "velocity": mean_velocity,
                     "theta": theta_sums / np.maximum(counts, 1)})
    return rows, top - bottom, box


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--differences", type=float, nargs="+", default=[8.0, 60.0],
                        help="dT between the walls in K (default 8 60; the first is the conduction reference)")
    parser.add_argument("--steps", type=int, default=40000, help="steps of dt* = 0.1 per run (default 40000)")
    parser.add_argument("--time-step", type=float, default=0.1, help="dt* (default 0.1)")
    parser.add_argument("--perturbation", type=float, default=2.0,
                        help="amplitude (K) of the roll pattern added to the conduction profile (default 2)")
    parser.add_argument("--windows", type=int, default=8, help="windows of each run, each reported (default 8)")
    parser.add_argument("--gravity", type=float, default=0.0074,
                        help="g in the model's reduced units, L/tau^2 (default 0.0074)")
    parser.add_argument("--atoms", type=float, default=15000, help="atoms per particle (default 15000)")
    parser.add_argument("--platform", default="CPU", choices=("Reference", "CPU"))
    parser.add_argument("--plot", metavar="STEM", help="draw the time-averaged fields of each run to STEM.png")
    arguments = parser.parse_args()

    parameters = coarse_grain(ARGON_EXPANDING, arguments.atoms, neighbors=20)
    u = parameters.units
    length = u.to_openmm(1, "length").value_in_unit(unit.nanometer)
    tau = u.to_openmm(1, "time").value_in_unit(unit.picosecond)
    gravity = arguments.gravity * length / tau**2      # nm/ps^2
    f = parameters.fluid.in_openmm()
    rho = f["mass_density"]                                              # amu/nm^3
    nu = f["shear_viscosity"] / rho                                      # nm^2/ps
    alpha, t0 = f["thermal_expansion"], parameters.temperature
    c_v = f["heat_capacity"] / f["molar_mass"]                           # kJ/mol/K per amu
    c_p = c_v + t0 * alpha**2 / (rho * f["compressibility"])
    diffusivity = f["thermal_conductivity"] / (rho * c_p)                # nm^2/ps
    print(f"{parameters.fluid.name}, {arguments.atoms:g} atoms per particle: L = {length:.3f} nm, tau = {tau:.3f} ps; "
          f"nu = {nu * tau / length**2:.4f}, D_T = {diffusivity * tau / length**2:.4f} L^2/tau; g = "
          f"{arguments.gravity} L/tau^2")
    print("  dT (K)  dT_ad (K)  Ra/Ra_c  window end (ns)  flux/dT (relative)  flow/noise  flow (m/s)")
    results = []
    reference = None
    for difference in arguments.differences:
        rows, depth, box = run(parameters, difference, gravity, arguments.steps, arguments.windows, arguments.platform,
                               5, (16, 8), arguments.time_step, arguments.perturbation)
        adiabatic = gravity * depth * alpha * t0 / c_p
        rayleigh = gravity * alpha * (difference - adiabatic) * depth**3 / (nu * diffusivity)
        reference = reference or rows[-1]["flux"] / difference
        for row in rows:
            print(f"  {difference:6.1f}  {adiabatic:8.2f}  {rayleigh / 1708:7.2f}  {row['time'] / 1000:12.2f}  "
                  f"{row['flux'] / difference / reference:14.3f}  {row['flow'] / row['noise']:14.2f}  "
                  f"{row['flow'] * 1000:9.3f}", flush=True)
        results.append((difference, rows[-1], depth, box))
    if arguments.plot:
        plot(results, arguments.plot)


def plot(results, stem):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, axes = plt.subplots(len(results), 1, figsize=(8, 2.6 * len(results)), squeeze=False)
    for axis, (difference, result, depth, box) in zip(axes[:, 0], results):
        velocity, theta = result["velocity"], result["theta"]
        nx, nz = theta.shape
        x = (np.arange(nx) + 0.5) / nx * box[0]
        z = (np.arange(nz) + 0.5) / nz * depth
        image = axis.pcolormesh(np.linspace(0, box[0], nx + 1), np.linspace(0, depth, nz + 1),
                                theta.T, cmap="coolwarm", shading="flat")
        axis.quiver(*np.meshgrid(x, z, indexing="ij"), velocity[0], velocity[2])
        axis.set_aspect("equal")
        axis.set_title(f"dT = {difference:g} K")
        axis.set_xlabel("x (nm)")
        axis.set_ylabel("z (nm)")
        figure.colorbar(image, ax=axis, label="<theta> (K)")
    figure.tight_layout()
    figure.savefig(f"{stem}.png", dpi=120)
    print(f"wrote {stem}.png")


if __name__ == "__main__":
    main()
