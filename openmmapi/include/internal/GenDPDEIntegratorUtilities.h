/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_INTEGRATOR_UTILITIES_H_
#define GENDPDE_INTEGRATOR_UTILITIES_H_

#include "GenDPDEIntegrator.h"
#include "openmm/System.h"
#include "openmm/internal/ContextImpl.h"
#include <map>
#include <string>

namespace GenDPDEPlugin {

class GenDPDEPairSource;
class IntegrateGenDPDEStepKernel;
struct GenDPDEThermalState;

/**
 * Which terms one step of a GenDPDEIntegrator contains, decided once from its mode and parameters for the API's
 * checks and every platform's kernel (a term that is switched off costs nothing).
 */
struct GenDPDEStepTerms {
    bool pairSweep;          // any pair term: the sweep runs
    bool dissipation;        // dissipative and random pair forces (friction > 0)
    bool conduction;         // heat conduction and its noise (Isoenergetic, heat conduction > 0)
    bool internalEnergies;   // the pair updates exchange energy with eps_i (Isoenergetic); otherwise with a bath
    /**
     * The largest displacement of a particle in one step (nm) that is not taken as a blown-up simulation: the pair
     * range R (the density weight and the pair terms vary on that scale, so a particle that crosses its whole
     * neighborhood in one step is no longer integrated; a stable liquid moves ~1e-3 R per step), or infinity if
     * the range is unknown (then only non-finite values are caught).
     */
    double maxDisplacement;
};

/** Decisions about a GenDPDEIntegrator's step that the API class and every platform share (docs/theory.md 5-6). */
class GenDPDEIntegratorUtilities {
public:
    /** The terms of the next step, for the pair range of the bound Context (0 if unknown). */
    static GenDPDEStepTerms stepTerms(const GenDPDEIntegrator& integrator, double pairRange);
    /**
     * The range R of the pair terms (nm): the integrator's cutoff if set, else that of the System's GenDPDEForces
     * (which must agree), else 0 (unknown; a step that needs the pair sweep then fails).
     */
    static double pairRange(const OpenMM::System& system, const GenDPDEIntegrator& integrator);
    /**
     * The pairs a step may reuse instead of searching them again: the pair source (GenDPDEKernels.h) of a
     * GenDPDEForce that has the pair range as its cutoff, the System's boundary conditions, and a force group among
     * the integration groups (so that GenDPDEIntegrator::step, which evaluates those groups right before the
     * kernel's execute(), has just found its pairs at the current positions). Null if there is none.
     */
    static GenDPDEPairSource* findPairSource(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator,
                                             double pairRange);
    /**
     * The particle types a Context's integrator uses (docs/types.md, "One type per particle"): a particle's type is
     * one setting, made on the GenDPDEForce (the integrator then takes the force's types, as it takes the pair
     * range), on the integrator (a GenDPDEForce that sets no types treats every particle alike), or on both alike.
     * Throws, naming the particle and both types, if the integrator's types and a GenDPDEForce's, or two
     * GenDPDEForces', differ for a particle.
     */
    static std::map<int, int> particleTypes(const OpenMM::System& system, const GenDPDEIntegrator& integrator);
    /**
     * Refuse, when a Context is created, what a temperature-dependent law (GenDPDEForce::dependsOnTemperature) cannot
     * run with: more than one such GenDPDEForce, or one outside the integration force groups (the integrator keeps
     * the thermal state its evaluation right before each step finds). Returns the index of such a force in the System,
     * or -1 if it has none.
     */
    static int checkThermalForces(const OpenMM::System& system, const GenDPDEIntegrator& integrator);
    /**
     * For the kernel of a GenDPDEForce whose laws depend on temperature: the thermal state the Context's
     * GenDPDEIntegrator holds. Throws if the Context's integrator is not a GenDPDEIntegrator, or if the particles'
     * temperatures are not set (Isoenergetic, Conservative) or the bath temperature is not (Isothermal).
     */
    static GenDPDEThermalState thermalState(OpenMM::ContextImpl& context);
    /**
     * The checks of thermalState(), then the Context's GenDPDEIntegrator (through integrator) and its kernel, whose
     * device thermal state a GPU platform's force kernel reads (IntegrateGenDPDEStepKernel::getDeviceThermalState).
     */
    static IntegrateGenDPDEStepKernel& thermalStateHolder(OpenMM::ContextImpl& context,
                                                          const GenDPDEIntegrator*& integrator);
    /**
     * Right after the integration force groups were evaluated at the current positions: the integrator kernel keeps
     * the thermal state the GenDPDEForce whose laws depend on temperature found (Isoenergetic, Conservative), or
     * forgets the densities its eps_i belong to (Isothermal: eps_i is not updated there). Nothing without such a force.
     */
    static void keepThermalState(OpenMM::ContextImpl& context, const GenDPDEIntegrator& integrator,
                                 IntegrateGenDPDEStepKernel& kernel);
    /**
     * Whether the evaluation under way is a step's, whose particles' temperatures the step's motion may change by at
     * most GENDPDE_STEP_TEMPERATURE_FACTOR (GenDPDEThermalState::checkStep).
     */
    static bool checksStepTemperatures(const GenDPDEIntegrator& integrator) {
        return integrator.checkingStepTemperatures;
    }
    /**
     * What follows the failure that stops a run (GenDPDEIntegrator::stopRun), and every later refusal: the way on
     * (docs/integrator.md, "When a run goes bad").
     */
    static constexpr const char* stoppedRunAdvice =
            ". This Context takes no step from this state, and makes no checkpoint or State of it: load a checkpoint "
            "or State saved before the failure (Context.loadCheckpoint() or setState(); Simulation.loadCheckpoint() "
            "or loadState()) and, if the run became unstable, reduce the step size";
    /** The errors a step reports (every platform uses the same words). */
    static std::string nonFinitePositionMessage(int particle, const OpenMM::Vec3& position, long long step);
    static std::string nonFiniteForceMessage(int particle, const OpenMM::Vec3& force, long long step);
    static std::string unstableStepMessage(int particle, double distance, double maxDisplacement, long long step);
    static std::string nonPositiveEnergyMessage(int particle, double energy, long long step);
    /**
     * Why a step is refused for a particle (velocity v, force F, 1/m, step dt): its force is not finite, or it
     * would move |(v + dt F/m) dt| > maxDisplacement.
     */
    static std::string unstableParticleMessage(int particle, const OpenMM::Vec3& velocity, const OpenMM::Vec3& force,
                                               double inverseMass, double stepSize, double maxDisplacement,
                                               long long step);
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_INTEGRATOR_UTILITIES_H_*/
