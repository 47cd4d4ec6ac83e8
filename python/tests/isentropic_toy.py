# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""A numerical check of docs/theory.md section 11 (issue 23's design): the Shardlow sweep of sections 5-6, unchanged,
combined with an isentropic conservative motion for f(theta, n) = e(n) - theta sigma(n) + C theta (1 - ln theta/theta0)
samples delta(H - E) prod_i exp(s_i/k_B) exp(sigma(n_i)/C), not delta(H - E) prod_i exp(s_i/k_B).

A toy with one degree of freedom in the positions, written out here in plain Python (a prototype, not the plugin):
two particles of mass 1 on a ring of length L, relative coordinate x, density n = 1 + exp(-x^2/(2 l^2)) for both (an
inf-range weight so that the pair always interacts), van der Waals e(n) = -a n, sigma(n) = k ln(1/(b n) - 1), heat
capacity C = 4 k_B (k_B = 1). A step: the pair update of the sweep (GenDPDEPairSweep.h's sweepIsoenergetic: the
two-stage impulse of gendpdePairImpulse with the Ito factor of gendpdePairTemperatures, half the kinetic change to
each internal energy, conduction; weight omega_R = 1), then velocity Verlet whose drift changes each eps = C theta
at fixed entropy (gendpdeIsentropicThermalEnergy) and whose forces use pi(theta_i, n).

Integrating p and the eps out of each law on the energy shell gives the law of x in closed form, with
Q(x) = E - 2 e(n(x)) and c = C/k_B:
    claimed (section 11):  P(x) ~ Q^(2c + 3/2) exp(2 sigma(n) (1/k_B + 1/C)),
    naive:                 P(x) ~ Q^(2c + 3/2) exp(2 sigma(n)/k_B).
sample() returns the histogram of |x| with its errors (samples every 50 steps, blocks of 100 samples) and both laws;
test_isentropic_equilibrium.py (validation tier) judges it by chi^2 per bin. Run alone it prints the table:
python3 python/tests/isentropic_toy.py [--steps 4000000] [--seed 1]
"""

import argparse
import math
import random

L, ELL, A, B, K, C, KB = 4.0, 0.7, 0.5, 0.3, 1.0, 4.0, 1.0
GAMMA, KAPPA, DT = 1.0, 0.3, 0.01
#: the reduced mass of the pair (masses 1 and 1): the relative motion's kinetic energy is MU v^2/2
MU = 0.5


def density(x):
    return 1.0 + math.exp(-x * x / (2 * ELL * ELL))


def density_slope(x):
    return -x / (ELL * ELL) * math.exp(-x * x / (2 * ELL * ELL))


def energy(n):
    return -A * n


def entropy(n):
    return K * math.log(1.0 / (B * n) - 1.0)


def pressure(theta, n):
    return -A * n * n + theta * K * n / (1.0 - B * n)


def force(x, eps):
    """-dH/dx at fixed entropies: sum_i (pi_i/n^2) dn/dx, both particles at the same n."""
    n = density(x)
    return -sum(pressure(e / C, n) for e in eps) / (n * n) * density_slope(x)


def wrap(x):
    return (x + L / 2) % L - L / 2


def pair_update(x, velocity, eps, rng):
    """One pair of the sweep (inverse masses 1 and 1, 1/MU = 2): momentum, heating, conduction."""
    sign = 1.0 if x >= 0 else -1.0
    beta = [C / e for e in eps]
    inverse_sum = 1.0 / (beta[0] + beta[1])
    pair_thermal_energy = 2 * KB * inverse_sum
    friction_factor = KB * (beta[0] / eps[0] + beta[1] / eps[1]) * inverse_sum * inverse_sum
    friction = GAMMA * (1.0 + friction_factor)
    noise = math.sqrt(2 * GAMMA * pair_thermal_energy)
    inverse_reduced_mass = 1.0 / MU
    u0 = sign * velocity
    friction_half = 0.5 * friction * DT
    implicit_factor = 1.0 / (1.0 + inverse_reduced_mass * friction_half)
    random_half = 0.5 * noise * math.sqrt(DT) * rng.gauss(0.0, 1.0)
    explicit_half = random_half - friction_half * u0
    u1 = u0 + inverse_reduced_mass * explicit_half
    impulse = explicit_half + (random_half - friction_half * u1) * implicit_factor
    kinetic_change = impulse * (u0 + 0.5 * inverse_reduced_mass * impulse)
    velocity = sign * (u0 + inverse_reduced_mass * impulse)
    eps = [eps[0] - 0.5 * kinetic_change, eps[1] - 0.5 * kinetic_change]
    heat = KAPPA * (beta[0] - beta[1]) * DT + math.sqrt(2 * KB * KAPPA) * math.sqrt(DT) * rng.gauss(0.0, 1.0)
    return velocity, [eps[0] + heat, eps[1] - heat]


BINS = 20


def sample(steps, seed=1):
    """Run the toy ``steps`` steps; return (energy at the start, mean energy, spread, means, errors, claimed, naive):
    the fraction of samples in each of BINS bins of |x| in [0, L/2] with its standard error over blocks of 100
    samples, and each law's fraction (the claimed law of section 11 and the naive one)."""
    rng = random.Random(seed)
    x, velocity, eps = 0.3, 0.0, [4.0, 4.0]     # velocity = dx/dt
    total = 0.5 * MU * velocity ** 2 + 2 * energy(density(x)) + sum(eps)
    counts, blocks, block = [0] * BINS, [], [0] * BINS
    energies = []
    f = force(x, eps)
    for step in range(steps):
        velocity, eps = pair_update(x, velocity, eps, rng)
        velocity += 0.5 * DT * f / MU
        n_old = density(x)
        x = wrap(x + DT * velocity)
        n_new = density(x)
        change = entropy(n_new) - entropy(n_old)
        eps = [e * math.exp(-change / C) for e in eps]
        f = force(x, eps)
        velocity += 0.5 * DT * f / MU
        if step % 50 == 0 and step > 10000:
            k = min(int(abs(x) / (L / 2) * BINS), BINS - 1)
            counts[k] += 1
            block[k] += 1
            energies.append(0.5 * MU * velocity ** 2 + 2 * energy(density(x)) + sum(eps))
            if sum(block) == 100:
                blocks.append(block)
                block = [0] * BINS
    samples = sum(counts)
    energy_mean = sum(energies) / len(energies)

    def law(extra):
        weights = []
        for k in range(BINS):
            # the bin's integral by the midpoint rule on 20 sub-points
            total_weight = 0.0
            for m in range(20):
                r = (k + (m + 0.5) / 20) * (L / 2) / BINS
                n = density(r)
                q = energy_mean - 2 * energy(n)
                total_weight += q ** (2 * C / KB + 1.5) * math.exp(2 * entropy(n) * (1 / KB + extra))
            weights.append(total_weight)
        norm = sum(weights)
        return [w / norm for w in weights]

    means = [c / samples for c in counts]
    errors = []
    for k in range(BINS):
        values = [b[k] / 100 for b in blocks]
        mean = sum(values) / len(values)
        variance = sum((v - mean) ** 2 for v in values) / (len(values) - 1)
        errors.append(math.sqrt(variance / len(values)) or 1e-12)
    return total, energy_mean, max(energies) - min(energies), means, errors, law(1 / C), law(0.0)


def chi2_per_bin(means, errors, law_values):
    return sum(((m - v) / e) ** 2 for m, e, v in zip(means, errors, law_values)) / len(means)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--steps", type=int, default=4000000)
    parser.add_argument("--seed", type=int, default=1)
    arguments = parser.parse_args()
    total, energy_mean, spread, means, errors, claimed, naive = sample(arguments.steps, arguments.seed)
    print(f"E: start {total:.6f}, mean {energy_mean:.6f}, spread {spread:.2e} (the conservative part's O(dt^2) error)")
    print("| |x| bin | measured | claimed | naive |")
    print("|---|---|---|---|")
    for k in range(BINS):
        print(f"| {k * L / 2 / BINS:.2f}-{(k + 1) * L / 2 / BINS:.2f} | {means[k]:.4f} +- {errors[k]:.4f} | "
              f"{claimed[k]:.4f} | {naive[k]:.4f} |")
    for name, law_values in (("claimed", claimed), ("naive", naive)):
        print(f"chi^2 per bin against the {name} law: {chi2_per_bin(means, errors, law_values):.2f}")


if __name__ == "__main__":
    main()
