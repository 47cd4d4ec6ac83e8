/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_FORCE_ERRORS_H_
#define GENDPDE_FORCE_ERRORS_H_

/* The errors a GenDPDEForce evaluation reports, in the same words on every platform. */

#include "GenDPDEForce.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDETypes.h"
#include "openmm/OpenMMException.h"
#include "openmm/Vec3.h"
#include "internal/MessageText.h"
#include <string>

namespace GenDPDEPlugin {
namespace GenDPDEForceErrors {

inline std::string nonFinitePosition(int particle, const OpenMM::Vec3& r, long long step) {
    MessageText message;
    message << "GenDPDEForce: the position of particle " << particle << " is not finite (" << r[0] << ", " << r[1]
            << ", " << r[2] << ") at step " << step;
    return message.str();
}

inline std::string noNeighbor(int particle, double cutoff, long long step) {
    MessageText message;
    message.precision(12);
    message << "GenDPDEForce: particle " << particle << " has no neighbor within the cutoff (" << cutoff
            << " nm) at step " << step << ", so its VA volume 1/n0 is undefined. "
            << "Use the VB estimator, a larger cutoff or a denser system";
    return message.str();
}

/**
 * The equation of state of a particle (law: its type's, Physics::LocalEquationOfState) overflows at density n
 * (nm^-3); a law that extends Tait says how many times its n0 that is.
 */
inline std::string equationOfStateOverflow(int particle, double density, const Physics::LocalEquationOfState& law,
                                           long long step) {
    const EquationsOfState::Law& description = EquationsOfState::laws[law.law];
    MessageText message;
    message.precision(6);
    message << "GenDPDEForce: the " << description.description << " equation of state of particle " << particle
            << " overflows at its density " << density << " nm^-3";
    if (description.extendsTait)
        message << " (" << density / law.parameter[0] << " n0)";
    message << " at step " << step << ": the simulation has become unstable (reduce the step size) or the parameters "
            << "of the law are extreme";
    return message.str();
}

/**
 * A particle's density n (nm^-3) is outside the domain of its law (law: its type's; the table's domain, up to
 * gendpdeLawDensityLimit), e.g. 0 < n < 1/b for a law with an excluded volume b (nm^3).
 */
inline std::string outsideDomain(int particle, double density, const Physics::LocalEquationOfState& law,
                                 long long step) {
    const EquationsOfState::Law& description = EquationsOfState::laws[law.law];
    MessageText message;
    message.precision(6);
    message << "GenDPDEForce: particle " << particle << " has the density " << density << " nm^-3 at step " << step
            << ", outside the domain of its " << description.description << " equation of state (" << description.domain
            << " = " << Physics::gendpdeLawDensityLimit(law.law, law.parameter.data())
            << " nm^-3): the simulation has become unstable (reduce the step size) or the particles are packed "
            << "beyond what the law allows";
    return message.str();
}

/**
 * A step's motion changed a particle's temperature from thetaBefore to thetaAfter (K), more than a factor
 * GENDPDE_STEP_TEMPERATURE_FACTOR, at the density n (nm^-3) it reached (docs/theory.md section 11).
 */
inline std::string temperatureJump(int particle, double thetaBefore, double thetaAfter, double density,
                                   long long step) {
    MessageText message;
    message.precision(6);
    message << "GenDPDEForce: the temperature of particle " << particle << " went from " << thetaBefore << " K to "
            << thetaAfter << " K in one step (by its compression or expansion alone, to the density " << density
            << " nm^-3), more than a factor " << GENDPDE_STEP_TEMPERATURE_FACTOR << ", at step " << step << ": its "
            << "equation of state is not being integrated; the simulation has become unstable (reduce the step size)";
    return message.str();
}

/**
 * updateParametersInContext() may not change the cutoff, the nonbonded method or the particle types of a Context's
 * force (types: those the Context was created with).
 */
inline void checkUnchangeableParameters(const GenDPDEForce& force, double cutoff, bool periodic,
                                        const ParticleTypeIndex& types) {
    if (!(ParticleTypeIndex(force.getParticleTypes(), types.getParticleTypeIndices().size(), "GenDPDEForce") == types))
        throw OpenMM::OpenMMException("GenDPDEForce: updateParametersInContext() cannot change the particle types; "
                                      "call Context.reinitialize() (or create a new Context) after changing them");
    if (force.getCutoffDistance() != cutoff)
        throw OpenMM::OpenMMException("GenDPDEForce: updateParametersInContext() cannot change the cutoff distance; "
                                      "call Context.reinitialize() (or create a new Context) after changing it");
    if (force.usesPeriodicBoundaryConditions() != periodic)
        throw OpenMM::OpenMMException("GenDPDEForce: updateParametersInContext() cannot change the nonbonded method; "
                                      "call Context.reinitialize() (or create a new Context) after changing it");
}

} // namespace GenDPDEForceErrors
} // namespace GenDPDEPlugin

#endif /*GENDPDE_FORCE_ERRORS_H_*/
