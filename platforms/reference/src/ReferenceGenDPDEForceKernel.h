#ifndef REFERENCE_GENDPDE_FORCE_KERNEL_H_
#define REFERENCE_GENDPDE_FORCE_KERNEL_H_

#include "GenDPDEKernels.h"
#include "NeighborList.h"
#include "internal/GenDPDEPhysics.h"
#include "internal/GenDPDETypes.h"
#include "openmm/Vec3.h"
#include <memory>
#include <vector>

namespace GenDPDEPlugin {

/**
 * Reference (double precision, single thread) evaluation of GenDPDEForce, docs/theory.md sections 2-4:
 * one sweep over the pairs for the primitive densities, one pass over the particles for volumes, pressures and
 * free energies, and one sweep over the pairs for the forces and the virial.
 */
class ReferenceCalcGenDPDEForceKernel : public CalcGenDPDEForceKernel {
public:
    ReferenceCalcGenDPDEForceKernel(std::string name, const OpenMM::Platform& platform) :
            CalcGenDPDEForceKernel(name, platform) {
    }
    void initialize(const OpenMM::System& system, const GenDPDEForce& force) override;
    double execute(OpenMM::ContextImpl& context, bool includeForces, bool includeEnergy) override;
    void copyParametersToContext(OpenMM::ContextImpl& context, const GenDPDEForce& force) override;
    const GenDPDEObservables& getObservables(OpenMM::ContextImpl& context) override;
    /** The neighbor list; its pairs are those of the most recent evaluation. */
    const NeighborList& getNeighborList() const {
        return *neighborList;
    }
protected:
    /** What evaluateParticle() needs per evaluation: the Tait equation of state of each type and the V-B estimator. */
    struct ParticleModel {
        explicit ParticleModel(const ReferenceCalcGenDPDEForceKernel& kernel) :
                volumeVB(kernel.cutoff/kernel.cutoffScaling),
                volumeVC(kernel.cutoff, kernel.cutoff/kernel.cutoffScaling) {
            for (const TaitParameters& p : kernel.taitByType)
                tait.emplace_back(p.referenceDensity, p.referencePressure, p.bulkModulus, p.exponent);
        }
        std::vector<Physics::TaitEquationOfState> tait;   // by type index
        Physics::VolumeEstimatorVB volumeVB;
        Physics::VolumeEstimatorVC volumeVC;
    };
    enum ParticleStatus {Valid, NoNeighbor, Overflow};
    /** What evaluateParticle() finds for one particle. */
    struct ParticleState {
        double volume;             // V (nm^3)
        double pressure;           // pi (kJ/mol/nm^3)
        double forceCoefficient;   // pi dV/dn0 (kJ/mol nm^3)
        double momentCoefficient;  // pi dV/dG (kJ/mol), VC only (else 0)
        double freeEnergy;         // f (kJ/mol)
    };
    /** Take the parameters that updateParametersInContext() may change; reject changes of the others. */
    void readParameters(const GenDPDEForce& force);
    /** Throw if firstBadParticle >= 0 (a non-finite position) or the cutoff exceeds half the box. */
    void checkConfiguration(OpenMM::ContextImpl& context, int firstBadParticle) const;
    /** The first particle in [begin, end) whose position is not finite, or -1. */
    static int firstNonFinitePosition(const std::vector<OpenMM::Vec3>& positions, int begin, int end);
    /**
     * The state of a particle of primitive density n0 (nm^-3), squared first moment G (VC only, else ignored) and
     * type index type; valid only if the status is Valid.
     */
    ParticleStatus evaluateParticle(double n0, double G, int type, const ParticleModel& model,
                                    ParticleState& state) const;
    /** Whether the estimator needs the first moments of the neighbourhoods (VC). */
    bool usesMoments() const {
        return estimator == GenDPDEForce::VC;
    }
    /** The density 1/V of particle i from its primitive density and moment of the last evaluation (nm^-3). */
    double particleDensity(int i) const;
    /** Store particle i's state in the per-particle arrays. */
    void storeParticle(int i, const ParticleState& state) {
        volume[i] = state.volume;
        pressure[i] = state.pressure;
        forceCoefficient[i] = state.forceCoefficient;
        if (usesMoments())
            momentForce[i] = moment[i]*(2.0*state.momentCoefficient);
    }
    /** The error for particle i, naming it, its density and the step. */
    [[noreturn]] void throwParticleError(ParticleStatus status, int i, OpenMM::ContextImpl& context) const;
    /** Pair sweep and particle pass: fills the per-particle arrays and returns U = sum_i f(n_i) (kJ/mol). */
    virtual double computeDensitiesAndEnergy(OpenMM::ContextImpl& context);
    /** Pair sweep for F_i (added to *forces unless null); returns the virial W (kJ/mol). */
    virtual double computePairForces(OpenMM::ContextImpl& context, std::vector<OpenMM::Vec3>* forces);
    double cutoff, cutoffScaling;
    std::unique_ptr<ParticleTypeIndex> types;   // the particle types, fixed when the Context is created
    std::vector<TaitParameters> taitByType;    // by type index
    GenDPDEForce::DensityEstimator estimator;
    bool periodic;
    std::unique_ptr<NeighborList> neighborList;
    // Per particle, at the positions of the last evaluation.
    std::vector<double> primitiveDensity, volume, pressure;
    std::vector<double> forceCoefficient;   // pi_i dV_i/dn0_i (kJ/mol nm^3)
    std::vector<double> particleVirial;     // sum over the pairs (i, j > i) of r_ij . F_ij (kJ/mol)
    std::vector<OpenMM::Vec3> moment;        // VC: g_i = sum_j phi(r_ij) e_ij (dimensionless)
    std::vector<OpenMM::Vec3> momentForce;   // VC: q_i = 2 pi_i dV_i/dG_i g_i (kJ/mol)
    // Observables and the configuration they belong to.
    GenDPDEObservables observables;
    std::vector<OpenMM::Vec3> observedPositions;
    OpenMM::Vec3 observedBox[3];
    bool observablesValid = false;
};

} // namespace GenDPDEPlugin

#endif /*REFERENCE_GENDPDE_FORCE_KERNEL_H_*/
