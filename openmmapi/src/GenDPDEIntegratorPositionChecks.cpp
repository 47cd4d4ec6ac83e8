/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
/* GenDPDEIntegrator's checks of positions set from outside the dynamics (Context.setPositions(), setState(), a
 * checkpoint), on every platform alike (docs/integrator.md, "Positions"; docs/soft-matter.md, "Bonds and periodic
 * boundaries"): every coordinate finite, none too far outside a periodic box, and no bond of a Force without periodic
 * boundary conditions stretched across more than half the box (a molecule split by wrapping). */

#include "GenDPDEIntegrator.h"
#include "internal/BoxGeometry.h"
#include "internal/GenDPDEIntegratorUtilities.h"
#include "internal/MessageText.h"
#include "openmm/CustomAngleForce.h"
#include "openmm/CustomCompoundBondForce.h"
#include "openmm/CustomTorsionForce.h"
#include "openmm/Force.h"
#include "openmm/HarmonicAngleForce.h"
#include "openmm/OpenMMException.h"
#include "openmm/PeriodicTorsionForce.h"
#include "openmm/RBTorsionForce.h"
#include "openmm/internal/ContextImpl.h"
#include "openmm/internal/ForceImpl.h"
#include <algorithm>
#include <cmath>
#include <vector>

using namespace GenDPDEPlugin;
using namespace OpenMM;

namespace {

/** The particles of each angle and torsion of an OpenMM Force of those kinds, in the order its energy chains them
 * (r1 - r2, r3 - r2, ...); none for other Forces. */
std::vector<std::vector<int>> chainedTerms(const Force& force) {
    std::vector<std::vector<int>> terms;
    std::vector<double> parameters;
    int p[4];
    double a, b, c, d, e, f;
    int n;
    if (auto* angles = dynamic_cast<const HarmonicAngleForce*>(&force)) {
        for (int t = 0; t < angles->getNumAngles(); t++) {
            angles->getAngleParameters(t, p[0], p[1], p[2], a, b);
            terms.push_back({p[0], p[1], p[2]});
        }
    } else if (auto* angles = dynamic_cast<const CustomAngleForce*>(&force)) {
        for (int t = 0; t < angles->getNumAngles(); t++) {
            angles->getAngleParameters(t, p[0], p[1], p[2], parameters);
            terms.push_back({p[0], p[1], p[2]});
        }
    } else if (auto* torsions = dynamic_cast<const PeriodicTorsionForce*>(&force)) {
        for (int t = 0; t < torsions->getNumTorsions(); t++) {
            torsions->getTorsionParameters(t, p[0], p[1], p[2], p[3], n, a, b);
            terms.push_back({p[0], p[1], p[2], p[3]});
        }
    } else if (auto* torsions = dynamic_cast<const RBTorsionForce*>(&force)) {
        for (int t = 0; t < torsions->getNumTorsions(); t++) {
            torsions->getTorsionParameters(t, p[0], p[1], p[2], p[3], a, b, c, d, e, f);
            terms.push_back({p[0], p[1], p[2], p[3]});
        }
    } else if (auto* torsions = dynamic_cast<const CustomTorsionForce*>(&force)) {
        for (int t = 0; t < torsions->getNumTorsions(); t++) {
            torsions->getTorsionParameters(t, p[0], p[1], p[2], p[3], parameters);
            terms.push_back({p[0], p[1], p[2], p[3]});
        }
    } else if (auto* compound = dynamic_cast<const CustomCompoundBondForce*>(&force)) {
        std::vector<int> particles;
        for (int t = 0; t < compound->getNumBonds(); t++) {
            compound->getBondParameters(t, particles, parameters);
            terms.push_back(particles);
        }
    }
    return terms;
}

} // namespace

void GenDPDEIntegrator::collectNonPeriodicBonds(ContextImpl& contextRef) {
    // A Force without periodic boundary conditions measures r_j - r_i as the positions are; in a periodic System
    // that is right only while every molecule it bonds is whole. OpenMM's ForceImpls name the pairs they bond
    // (getBondedParticles(): bonds, a NonbondedForce's exceptions); angles and torsions add their chained pairs.
    nonPeriodicBonds.clear();
    const System& system = contextRef.getSystem();
    if (!system.usesPeriodicBoundaryConditions())
        return;
    const std::vector<ForceImpl*>& impls = contextRef.getForceImpls();
    for (size_t f = 0; f < impls.size(); f++) {
        const Force& force = impls[f]->getOwner();
        if (force.usesPeriodicBoundaryConditions())
            continue;
        for (const std::pair<int, int>& pair : impls[f]->getBondedParticles())
            nonPeriodicBonds.push_back({(int) f, pair.first, pair.second});
        for (const std::vector<int>& term : chainedTerms(force))
            for (size_t k = 1; k < term.size(); k++)
                nonPeriodicBonds.push_back({(int) f, term[k - 1], term[k]});
    }
}

void GenDPDEIntegrator::checkSetPositions() {
    std::vector<Vec3> positions;
    context->getPositions(positions);
    const bool periodic = context->getSystem().usesPeriodicBoundaryConditions();
    Vec3 box[3];
    context->getPeriodicBoxVectors(box[0], box[1], box[2]);
    refusedPositions.clear();
    for (size_t i = 0; i < positions.size() && refusedPositions.empty(); i++) {
        const Vec3& r = positions[i];
        if (!(std::isfinite(r[0]) && std::isfinite(r[1]) && std::isfinite(r[2]))) {
            MessageText message;
            message << "GenDPDEIntegrator: the position set for particle " << i << " is not finite (" << r[0] << ", "
                    << r[1] << ", " << r[2] << ")";
            refusedPositions = message.str();
        } else if (periodic) {
            const Vec3 s = BoxGeometry::fractionalCoordinates(r, box);
            const double lengths =
                    std::max(std::fabs(s[0] - 0.5), std::max(std::fabs(s[1] - 0.5), std::fabs(s[2] - 0.5))) - 0.5;
            if (lengths > maxBoxLengths) {
                MessageText message;
                message.precision(6);
                message << "GenDPDEIntegrator: the position of particle " << i << " (" << r[0] << ", " << r[1] << ", "
                        << r[2] << ") nm lies " << lengths << " box lengths outside the periodic box; a position may "
                        << "lie at most " << maxBoxLengths << " box lengths outside it (beyond that the platforms' "
                        << "periodic wrapping in double, mixed and single precision no longer agrees)";
                refusedPositions = message.str();
            }
        }
    }
    for (size_t b = 0; b < nonPeriodicBonds.size() && refusedPositions.empty(); b++) {
        const NonPeriodicBond& bond = nonPeriodicBonds[b];
        const Vec3 d = positions[bond.particle2] - positions[bond.particle1];
        const Vec3 s = BoxGeometry::fractionalCoordinates(d, box);
        if (std::max(std::fabs(s[0]), std::max(std::fabs(s[1]), std::fabs(s[2]))) > 0.5) {
            const Force& force = context->getSystem().getForce(bond.force);
            MessageText message;
            message.precision(6);
            message << "GenDPDEIntegrator: particles " << bond.particle1 << " and " << bond.particle2 << ", bonded by "
                    << force.getName() << " (force " << bond.force << ", which does not use periodic boundary "
                    << "conditions), are set " << std::sqrt(d.dot(d)) << " nm apart, more than half the periodic box "
                    << "across: their molecule is split by the box's boundary, and the force would pull them "
                    << "together across the box. Set positions that keep each molecule whole (unwrapped, as "
                    << "OpenMM's PDBFile and modeller give them), or call setUsesPeriodicBoundaryConditions(true) on "
                    << "the force";
            refusedPositions = message.str();
        }
    }
    if (!refusedPositions.empty())
        throw OpenMMException(refusedPositions
                              + ". The Context holds these positions; set valid ones before the "
                                "next step (step() refuses until then)");
}

void GenDPDEIntegrator::requireFinitePositions() const {
    std::vector<Vec3> positions;
    context->getPositions(positions);
    for (size_t i = 0; i < positions.size(); i++)
        if (!(std::isfinite(positions[i][0]) && std::isfinite(positions[i][1]) && std::isfinite(positions[i][2])))
            throw OpenMMException(
                    GenDPDEIntegratorUtilities::nonFinitePositionMessage(i, positions[i], context->getStepCount()));
}
