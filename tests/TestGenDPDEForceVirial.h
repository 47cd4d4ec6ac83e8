/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEForce tests (included by TestGenDPDEForce.h): the scalar virial and the virial tensors (docs/theory.md
 * section 4) against the energy's response to scaling and to strain. */

namespace ForceTests {

/** U at the scene's positions and box scaled uniformly by lambda (r -> lambda r), in a periodic Context. */
double scaledEnergy(Context& context, const Scene& scene, double lambda) {
    context.setPeriodicBoxVectors(scene.box[0] * lambda, scene.box[1] * lambda, scene.box[2] * lambda);
    std::vector<Vec3> scaled = scene.positions;
    for (Vec3& r : scaled)
        r *= lambda;
    return energyAt(context, scaled);
}

/**
 * The virial equals sum_i r_i . F_i for open boundaries, and -dU/d(lambda) under uniform scaling r -> lambda r of
 * positions and box (= -3 V dU/dV) for periodic ones; the finite difference uses lambda = 1 +- 1e-6, whose
 * truncation error is ~1e-12 relative, and the rounding error eps |U| / 1e-6 is ~1e-9 of |W|.
 */
void testVirial() {
    for (GenDPDEForce::DensityEstimator estimator : testEstimators()) {
        Scene open = makeLatticeLiquid(6, referenceDensity, 0.2, estimator, false, 31);
        VerletIntegrator integrator(0.001);
        Context context(open.system, integrator, *platform);
        context.setPositions(open.positions);
        State state = context.getState(State::Forces);
        double sum = 0;
        for (size_t i = 0; i < open.positions.size(); i++)
            sum += open.positions[i].dot(state.getForces()[i]);
        // Float forces: the State's forces are rounded to float each, and the terms r_i . F_i (of either sign, their
        // magnitudes summing to ~100 |W|) carry that: 1e-5.
        assertRelative(sum, open.force->getVirial(context), precisionTolerance(1e-10, 1e-5), "open virial");

        for (double density : {referenceDensity, 3.0 * referenceDensity}) {
            Scene periodic = makeLatticeLiquid(6, density, 0.2, estimator, true, 32);
            VerletIntegrator integrator2(0.001);
            Context context2(periodic.system, integrator2, *platform);
            context2.setPositions(periodic.positions);
            double virial = periodic.force->getVirial(context2);
            // Float forces: the energy's ~1e-7 relative rounding over 2 epsilon needs epsilon = 1e-3 (rounding
            // ~1e-4 of U/W, truncation ~1e-6): 1e-3.
            const double epsilon = precisionTolerance(1e-6, 1e-3);
            double derivative =
                    (scaledEnergy(context2, periodic, 1 + epsilon) - scaledEnergy(context2, periodic, 1 - epsilon))
                    / (2 * epsilon);
            assertRelative(-derivative, virial, precisionTolerance(1e-7, 1e-3), "virial = -3V dU/dV");
        }
    }
}

/** U at positions (and, if periodic, box vectors) mapped by the strain r_a -> r_a + epsilon r_b. */
double strainedEnergy(Context& context, const Scene& scene, int a, int b, double epsilon) {
    auto strain = [&](Vec3 v) {
        v[a] += epsilon * v[b];
        return v;
    };
    if (scene.force->usesPeriodicBoundaryConditions())
        context.setPeriodicBoxVectors(strain(scene.box[0]), strain(scene.box[1]), strain(scene.box[2]));
    std::vector<Vec3> strained = scene.positions;
    for (Vec3& r : strained)
        r = strain(r);
    return energyAt(context, strained);
}

/**
 * The particles' virial tensors (getParticleVirials) add up to a tensor W whose trace is the scalar virial and which
 * is symmetric (U is invariant under rotations; the V-C pair forces are not central, so symmetry holds for the sum,
 * not pair by pair), and whose elements are the energy's response to strain, W_ab = -dU/d epsilon_ab for
 * r_a -> r_a + epsilon r_b: every element for open boundaries (positions only); for periodic boxes the strains that
 * keep OpenMM's reduced box form, the upper triangle and the diagonal of a triclinic box (the lower triangle follows by
 * symmetry), the diagonal of a rectangular one (a shear would make it triclinic, which the GPU platforms allow only
 * for a System created triclinic).
 * Central differences with epsilon = 1e-6: truncation ~1e-12 relative, rounding eps |U|/1e-6 ~ 1e-9 of |W|, so 1e-6
 * of the largest element. The sums agree to 1e-12 of the sum of the particles' |trace|, or 1e-5 with float forces
 * (each element a sum of ~17 pair terms rounded to 2^-24); the finite differences need double precision
 * (testFiniteDifferences says why).
 */
void checkVirialTensor(Scene& scene, const std::string& label) {
    VerletIntegrator integrator(0.001);
    Context context(scene.system, integrator, *platform);
    context.setPositions(scene.positions);
    const std::vector<double> particles = scene.force->getParticleVirials(context);
    double W[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, traceScale = 0.0, largest = 0.0;
    for (size_t i = 0; i < particles.size() / 9; i++) {
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                W[a][b] += particles[9 * i + 3 * a + b];
        traceScale += std::abs(particles[9 * i] + particles[9 * i + 4] + particles[9 * i + 8]);
    }
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            largest = std::max(largest, std::abs(W[a][b]));
    const double sumTolerance = precisionTolerance(1e-12, 1e-5) * traceScale;
    assertClose(scene.force->getVirial(context), W[0][0] + W[1][1] + W[2][2], sumTolerance, label + ": trace W");
    for (int a = 0; a < 3; a++)
        for (int b = a + 1; b < 3; b++)
            assertClose(W[a][b], W[b][a], sumTolerance,
                        label + ": W symmetric, " + std::to_string(a) + std::to_string(b));
    if (floatForces())
        return;
    const double epsilon = 1e-6;
    const bool periodic = scene.force->usesPeriodicBoundaryConditions();
    const bool rectangular = scene.box[1][0] == 0.0 && scene.box[2][0] == 0.0 && scene.box[2][1] == 0.0;
    for (int a = 0; a < 3; a++)
        for (int b = (periodic ? a : 0); b < (periodic && rectangular ? a + 1 : 3); b++) {
            const double derivative =
                    (strainedEnergy(context, scene, a, b, epsilon) - strainedEnergy(context, scene, a, b, -epsilon))
                    / (2 * epsilon);
            assertClose(-derivative, W[a][b], 1e-6 * largest,
                        label + ": W_" + std::to_string(a) + std::to_string(b) + " = -dU/d epsilon");
        }
}

/** checkVirialTensor for every estimator: a bulk liquid, a triclinic box, a slab in vacuum and an open cluster. */
void testVirialTensor() {
    for (GenDPDEForce::DensityEstimator estimator : testEstimators()) {
        const std::string label = estimatorLabel(estimator);
        Scene bulk = makeLatticeLiquid(6, referenceDensity, 0.2, estimator, true, 131);
        checkVirialTensor(bulk, label + " bulk");
        Scene triclinic = makeLatticeLiquid(6, referenceDensity, 0.2, estimator, true, 132);
        const double edge = triclinic.box[0][0];
        setBox(triclinic, Vec3(edge, 0, 0), Vec3(0.3 * edge, edge, 0), Vec3(-0.4 * edge, 0.2 * edge, edge));
        checkVirialTensor(triclinic, label + " triclinic");
        Scene slab = makeSlab(6, 0.82 * referenceDensity, 0.2, estimator, 133);
        checkVirialTensor(slab, label + " slab");
        Scene cluster = makeLatticeLiquid(6, referenceDensity, 0.2, estimator, false, 134);
        checkVirialTensor(cluster, label + " open cluster");
    }
}

} // namespace ForceTests
