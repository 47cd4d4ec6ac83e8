/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_FORCE_H_
#define GENDPDE_FORCE_H_

#include "openmm/Context.h"
#include "openmm/Force.h"
#include <map>
#include <string>
#include <vector>

namespace GenDPDEPlugin {

class GenDPDEForceImpl;
struct GenDPDEObservables;

/**
 * The many-body conservative force of generalised energy-conserving dissipative particle dynamics (GenDPDE).
 *
 * Every particle i of the System carries a local density. The primitive density is
 * n0_i = sum_{j != i} w(r_ij) with the normalised weight w(r) = 15/(2 pi R^3) (1 - r/R)^2 of range R (the cutoff
 * distance). A volume estimator turns it into a particle volume V_i and density n_i = 1/V_i:
 *
 *  - VA (traditional): V_i = 1/n0_i. An isolated particle (n0_i = 0) has no volume and is reported as an error.
 *    With VA, particles clump in pairs so that n_i settles near the free-energy minimum instead of the imposed
 *    density (the pairing instability).
 *  - VB (partition of unity): V_i = 4 pi Rt^3 int_0^1 y^2 (1-y)^2/(y^2 + k_i) dy with Rt = R/f_cut and
 *    k_i = (2 pi/15) Rt^3 n0_i. It is finite for an isolated particle ((4 pi/3) Rt^3), tends to VA at high density
 *    and removes the pairing instability. f_cut >= 1 (the cutoff scaling) tunes the mean density.
 *  - VC (V-B with a surface correction): V_i = V_B(n0_i) (1 + 3 x_i^2/(1 + x_i^2)), x_i = max(0, a_i^2 - 0.4)/0.3,
 *    where a_i measures how one-sided the neighbourhood is: a_i^2 = c^2 |g_i|^2/(n0_i^2 + eps^2) with
 *    g_i = sum_j (r_ij/R)(1 - r_ij/R)^2 e_ij, c = 30/(pi R^3) (a_i = 1 at a flat free surface), eps = 3/(4 pi R^3).
 *    V-B is blind to a neighbourhood empty on one side; V-C gives such particles the larger volume the exact
 *    partition of unity gives them, so that free surfaces and droplets hold instead of foaming, and is V-B itself
 *    for the particles of a bulk liquid (below the threshold). docs/interfaces.md.
 *
 * Each particle has the Tait pressure pi(n) = pi0 + B_T [(n/n0)^gamma_T - 1] and free energy
 * f(n) = (B_T - pi0)/n + B_T/((gamma_T - 1) n0) (n/n0)^(gamma_T - 1), and the potential energy is
 * U = sum_i f(n_i). The force is its exact gradient,
 * F_i = sum_j [pi_i dV_i/dn0_i + pi_j dV_j/dn0_j] w'(r_ij) e_ij (with VC also a term from the moments,
 * H(r_ij)(q_i - q_j), docs/theory.md section 4), which is pairwise antisymmetric and conserves momentum. Coincident
 * particles count in the density but exert no force on each other.
 *
 * Particle types (docs/types.md). Every particle has a type, an integer (0 unless setParticleType() says otherwise),
 * and each type may have its own Tait parameters (addTypeParameters()); a type without them uses
 * setTaitParameters(). Particle i then has the equation of state of its type, f_i(n_i), while its density counts
 * every neighbour whatever its type: the volumes V_i partition the space the particles fill, so the mixture's
 * volume is the sum of its particles' volumes and each particle's pressure follows from its own.
 *
 * Temperature (docs/theory.md section 11). A type may instead have a local equation of state that depends on the
 * particle's own temperature theta_i (setEquationOfState(), addTypeEquationOfState()): a Tait law with thermal
 * expansion, or van der Waals. The particles' temperatures then come from the GenDPDEIntegrator, the conservative
 * motion keeps each particle's entropy, and U counts the thermal energy a compression has done since the integrator
 * last updated eps_i, so that K + U + sum_i eps_i stays the conserved total and the force stays -dU/dr.
 *
 * All parameters can be set before the Context is created. The estimator, the cutoff scaling and the Tait
 * parameters (per type too) can also be changed afterwards with updateParametersInContext(); the cutoff distance,
 * the nonbonded method and the particle types cannot. The per-particle observables (densities, volumes, pressures, virial tensors) and
 * the virial are computed from the Context's current positions on request, by the platform's kernels.
 *
 * The defaults are the liquid-argon model of Colella et al. (J. Chem. Theory Comput. 2025) in OpenMM units
 * (one particle = 5 argon atoms): n0 = 1/L^3 = 4.27484 nm^-3, pi0 = 0.116056 u/L^3, B_T = u/(6 L^3) with
 * u = 94.5476 kJ/mol and L = 0.61616 nm, gamma_T = 6; estimator VB, f_cut = 1, periodic boundaries.
 */
class GenDPDEForce : public OpenMM::Force {
public:
    /** How pair distances are computed. */
    enum NonbondedMethod {
        /** No periodic boundaries; pairs farther apart than the cutoff do not interact. */
        CutoffNonPeriodic = 0,
        /** Periodic boundaries; the cutoff must not exceed half the smallest box width. */
        CutoffPeriodic = 1
    };
    /** How the primitive density n0_i becomes a particle volume V_i. */
    enum DensityEstimator {
        /** Traditional estimator V = 1/n0. */
        VA = 0,
        /** Partition-of-unity estimator; removes the pairing instability. */
        VB = 1,
        /**
         * V-B with a surface correction from the first moment of the neighbourhood: V-B in bulk liquids, and free
         * surfaces and droplets hold instead of foaming (docs/interfaces.md).
         */
        VC = 2
    };
    /**
     * The local equation of state of a particle type (docs/theory.md section 11). Every law is one free energy per
     * particle f(theta, n) = e(n) - theta sigma(n) + C_V theta (1 - ln(theta/theta0)), with C_V the particle's heat
     * capacity on the GenDPDEIntegrator, so that pi = n^2 df/dn = pi_0(n) + theta pi_theta(n), and the conservative
     * motion is isentropic: a compressed particle heats up as dtheta/dn = theta pi_theta/(n^2 C_V). A law that depends
     * on temperature needs a GenDPDEIntegrator (it holds theta_i); every platform runs it.
     */
    enum EquationOfState {
        /** pi(n) from the Tait parameters alone (no parameters of its own): no temperature dependence. */
        Tait = 0,
        /**
         * The Tait law with a thermal pressure, pi = pi_Tait(n) + beta (theta - theta0). Parameters {beta, theta0}:
         * beta = (dpi/dtheta)_n in kJ/mol/nm^3/K, finite (alpha/kappa_T of the fluid at the reference state),
         * theta0 > 0 in K, the temperature at which pi is the Tait law's.
         */
        TaitThermalExpansion = 1,
        /**
         * van der Waals, pi = k theta n/(1 - b n) - a n^2, for 0 < n < 1/b (a particle outside stops the simulation
         * with an error naming it and the step). Parameters {a, b, k}: a >= 0 in kJ/mol nm^3, b > 0 in nm^3,
         * k > 0 in kJ/(mol K) (k_B for a particle that is one molecule).
         */
        VanDerWaals = 2
    };
    /**
     * Create a GenDPDEForce.
     *
     * @param cutoff    the range R of the density weight (in nm), finite and > 0
     */
    explicit GenDPDEForce(double cutoff);
    /** Get the cutoff distance R (in nm). */
    double getCutoffDistance() const;
    /** Set the cutoff distance R (in nm), finite and > 0. Takes effect when a Context is created. */
    void setCutoffDistance(double distance);
    /** Get the method used for periodic boundaries. */
    NonbondedMethod getNonbondedMethod() const;
    /** Set the method used for periodic boundaries. Takes effect when a Context is created. */
    void setNonbondedMethod(NonbondedMethod method);
    /** Get the density estimator (VA, VB or VC). */
    DensityEstimator getDensityEstimator() const;
    /** Set the density estimator (VA, VB or VC). */
    void setDensityEstimator(DensityEstimator estimator);
    /** Get the cutoff scaling f_cut of the VB estimator (dimensionless). */
    double getCutoffScaling() const;
    /** Set the cutoff scaling f_cut >= 1 of the VB and VC estimators (dimensionless; Rt = R/f_cut). Ignored by VA. */
    void setCutoffScaling(double scaling);
    /**
     * Set the parameters of the Tait equation of state.
     *
     * @param referenceDensity     n0 (in nm^-3), > 0
     * @param referencePressure    pi0 (in kJ/mol/nm^3), any finite value
     * @param bulkModulus          B_T = 1/(gamma_T kappa_T0) (in kJ/mol/nm^3), > 0
     * @param exponent             gamma_T (dimensionless), > 1
     */
    void setTaitParameters(double referenceDensity, double referencePressure, double bulkModulus, double exponent);
    /**
     * Get the parameters of the Tait equation of state.
     *
     * @param[out] referenceDensity     n0 (in nm^-3)
     * @param[out] referencePressure    pi0 (in kJ/mol/nm^3)
     * @param[out] bulkModulus          B_T (in kJ/mol/nm^3)
     * @param[out] exponent             gamma_T (dimensionless)
     */
    void getTaitParameters(double& referenceDensity, double& referencePressure, double& bulkModulus,
                           double& exponent) const;
    /** Get the Tait reference density n0 (in nm^-3). */
    double getReferenceDensity() const;
    /** Get the Tait reference pressure pi0 (in kJ/mol/nm^3). */
    double getReferencePressure() const;
    /** Get the Tait bulk modulus B_T (in kJ/mol/nm^3). */
    double getBulkModulus() const;
    /** Get the Tait exponent gamma_T (dimensionless). */
    double getTaitExponent() const;
    /**
     * Set the background pressure p_b (in kJ/mol/nm^3), finite and >= 0; default 0 (docs/theory.md section 12). Every
     * particle's pressure becomes pi_i + p_b (its free energy f_i - p_b V_i, whatever its law) and the energy gains
     * p_b V_box, so that U = sum_i f_i + p_b (V_box - sum_i V_i): the system's pressure is unchanged where the volumes
     * add up to the box (sum_i V_i = V_box, a partition of unity), and a structure whose volumes add up to less is
     * penalised. It keeps the particle pressures positive in a liquid whose own pressure is low against n k_B T
     * (water at 0.1 MPa with 4 molecules per particle), where a negative pi_i lets the structure absorb a
     * compression. getParticlePressures() includes p_b; getVirial() and getParticleVirials() include the box term
     * (-3 p_b V_box, shared equally by the particles). Needs periodic boundaries (CutoffPeriodic) when p_b > 0.
     * Takes effect when a Context is created or at updateParametersInContext().
     */
    void setBackgroundPressure(double pressure);
    /** Get the background pressure p_b (in kJ/mol/nm^3). */
    double getBackgroundPressure() const;
    /**
     * Set the type of a particle: any integer (particles never given one have type 0). Read when a Context is
     * created; the particle index is checked against the System then.
     *
     * @param index   the particle, >= 0
     * @param type    its type
     */
    void setParticleType(int index, int type);
    /** Get the type of a particle (0 if none was set). */
    int getParticleType(int index) const;
    /** The particles whose type was set, as particle -> type (every other particle has type 0). */
    const std::map<int, int>& getParticleTypes() const;
    /**
     * Give a type its own Tait parameters (see setTaitParameters for units and ranges). Each type may appear in one
     * entry; types without an entry use the force's own parameters. The type must be one that some particle has
     * when a Context is created.
     *
     * @return the index of the entry
     */
    int addTypeParameters(int type, double referenceDensity, double referencePressure, double bulkModulus,
                          double exponent);
    /** The number of entries added with addTypeParameters(). */
    int getNumTypeParameters() const;
    /** Get an entry of addTypeParameters(): its type and Tait parameters (n0 in nm^-3, pi0 and B_T in kJ/mol/nm^3). */
    void getTypeParameters(int index, int& type, double& referenceDensity, double& referencePressure,
                           double& bulkModulus, double& exponent) const;
    /** Change an entry of addTypeParameters() (same units and checks). */
    void setTypeParameters(int index, int type, double referenceDensity, double referencePressure, double bulkModulus,
                           double exponent);
    /**
     * Set the local equation of state of every type without an entry of addTypeEquationOfState(): the law and its
     * parameters (see EquationOfState for their number, units and ranges). The Tait parameters of the law are the
     * type's (addTypeParameters()) or the force's (setTaitParameters()). Default: Tait, no parameters.
     */
    void setEquationOfState(EquationOfState law, const std::vector<double>& parameters);
    /** Get the local equation of state of the types without an entry: the law and its parameters. */
    void getEquationOfState(EquationOfState& law, std::vector<double>& parameters) const;
    /**
     * Give a type its own local equation of state (see setEquationOfState()). Each type may appear in one entry; the
     * type must be one that some particle has when a Context is created.
     *
     * @return the index of the entry
     */
    int addTypeEquationOfState(int type, EquationOfState law, const std::vector<double>& parameters);
    /** The number of entries added with addTypeEquationOfState(). */
    int getNumTypeEquationsOfState() const;
    /** Get an entry of addTypeEquationOfState(): its type, law and parameters. */
    void getTypeEquationOfState(int index, int& type, EquationOfState& law, std::vector<double>& parameters) const;
    /** Change an entry of addTypeEquationOfState() (same checks). */
    void setTypeEquationOfState(int index, int type, EquationOfState law, const std::vector<double>& parameters);
    /**
     * Whether some law of this force depends on temperature (any law but Tait, as the default or in an entry): the
     * force then needs a GenDPDEIntegrator, which holds the particles' temperatures.
     */
    bool dependsOnTemperature() const;
    /** Returns true if the force uses periodic boundaries (nonbonded method CutoffPeriodic). */
    bool usesPeriodicBoundaryConditions() const override;
    /**
     * Copy the estimator, the cutoff scaling, the background pressure, the Tait parameters (the force's and each
     * type's) and the equations of state into a Context that already exists, without reinitialising it. The cutoff
     * distance, the nonbonded method and the particle types cannot be changed this way.
     */
    void updateParametersInContext(OpenMM::Context& context);
    /** The primitive density n0_i of every particle (in nm^-3) at the Context's current positions. */
    std::vector<double> getPrimitiveDensities(OpenMM::Context& context) const;
    /** The density n_i = 1/V_i of every particle (in nm^-3) at the Context's current positions. */
    std::vector<double> getParticleDensities(OpenMM::Context& context) const;
    /** The volume V_i of every particle (in nm^3) at the Context's current positions. */
    std::vector<double> getParticleVolumes(OpenMM::Context& context) const;
    /**
     * The pressure pi_i of every particle (in kJ/mol/nm^3) at the Context's current positions: its law's, plus the
     * background pressure.
     */
    std::vector<double> getParticlePressures(OpenMM::Context& context) const;
    /**
     * The conservative virial W = sum_{i<j} r_ij . F_ij (in kJ/mol) at the Context's current positions, plus the
     * background pressure's box term -3 p_b V_box, so that the pressure is P = (2K + W)/(3 V_box). It equals
     * -3 V_box dU/dV_box under uniform scaling.
     */
    double getVirial(OpenMM::Context& context) const;
    /**
     * The virial tensor of every particle (in kJ/mol) at the Context's current positions: nine numbers per particle,
     * row-major, W_i[3a + b] = sum_j (1/2) F_ij,a r_ij,b with F_ij the force on i from its pair with j and
     * r_ij = r_i - r_j, so that each pair's tensor is shared equally by its two particles (and the background
     * pressure's -p_b V_box on the diagonal equally by all particles). They add up to the
     * system's virial tensor W_ab = -dU/d epsilon_ab (the energy's response to the strain r -> (1 + epsilon) r of
     * positions and box), whose trace is getVirial(); the pressure tensor of the system is
     * P_ab = (sum_i m_i v_i,a v_i,b + W_ab)/V_box. Computed on request only, by the platform's own kernels.
     */
    std::vector<double> getParticleVirials(OpenMM::Context& context) const;

protected:
    OpenMM::ForceImpl* createImpl() const override;

private:
    GenDPDEForceImpl& getImpl(OpenMM::Context& context) const;
    const GenDPDEObservables& observablesInContext(OpenMM::Context& context, bool particleVirials = false) const;
    double cutoff, cutoffScaling, backgroundPressure;
    double referenceDensity, referencePressure, bulkModulus, exponent;
    NonbondedMethod nonbondedMethod;
    DensityEstimator estimator;
    std::map<int, int> particleTypes;
    struct TypeEntry {
        int type;
        double referenceDensity, referencePressure, bulkModulus, exponent;
    };
    std::vector<TypeEntry> typeParameters;
    struct LawEntry {
        int type;
        EquationOfState law;
        std::vector<double> parameters;
    };
    LawEntry defaultLaw; // type ignored
    std::vector<LawEntry> typeLaws;
    /** Refuse a law or parameters outside the allowed ranges; entry names what is checked. */
    static void checkLaw(const std::string& entry, EquationOfState law, const std::vector<double>& parameters);
    void checkTypeLaw(int index, int type, EquationOfState law, const std::vector<double>& parameters) const;
    void checkTypeEntry(int index, int type, double referenceDensity, double referencePressure, double bulkModulus,
                        double exponent) const;
};

} // namespace GenDPDEPlugin

#endif /*GENDPDE_FORCE_H_*/
