#ifndef GENDPDE_PHYSICS_CORE_H_
#define GENDPDE_PHYSICS_CORE_H_

/* -------------------------------------------------------------------------- *
 * The scalar core of GenDPDE's physics (docs/theory.md sections 3-7), written *
 * once in the common subset of C++ and of OpenMM's Common kernel dialect     *
 * (OpenCL C, CUDA): plain functions of scalars, results through pointers, no *
 * std::, no references, no includes.                                         *
 *                                                                            *
 * GenDPDEPhysics.h includes it for the host platforms (GENDPDE_REAL double,  *
 * inside namespace GenDPDEPlugin::Physics); the GPU platforms embed this     *
 * file in their device programs (GENDPDE_REAL real for the force, mixed for  *
 * the integrator). The includer defines GENDPDE_REAL, and on the device      *
 * GENDPDE_CORE (inline DEVICE) and GENDPDE_GLOBAL (GLOBAL).                  *
 * -------------------------------------------------------------------------- */

#ifndef GENDPDE_CORE
#define GENDPDE_CORE inline
#endif
#ifndef GENDPDE_GLOBAL
#define GENDPDE_GLOBAL
#endif

/** x^p for an integer p >= 0, by binary powering (exact to a few ulp, several times cheaper than pow). */
GENDPDE_CORE GENDPDE_REAL gendpdeIntegerPower(GENDPDE_REAL x, int p) {
    GENDPDE_REAL result = 1;
    while (p > 0) {
        if (p & 1)
            result *= x;
        x *= x;
        p >>= 1;
    }
    return result;
}

/**
 * The Tait equation of state and the free energy per particle at density n (section 4):
 *   pi(n) = pi0 + B_T [ (n/n0)^gamma_T - 1 ],   f(n) = (B_T - pi0)/n + B_T/((gamma_T - 1) n0) (n/n0)^(gamma_T - 1).
 * integerPower is gamma_T - 1 when gamma_T is an integer in [2, 33] (then by multiplications), else -1 (pow).
 */
GENDPDE_CORE void gendpdeTait(GENDPDE_REAL density, GENDPDE_REAL referenceDensity, GENDPDE_REAL referencePressure,
                              GENDPDE_REAL bulkModulus, GENDPDE_REAL exponent, int integerPower,
                              GENDPDE_REAL* pressure, GENDPDE_REAL* freeEnergy) {
    const GENDPDE_REAL x = density/referenceDensity;
    const GENDPDE_REAL xPowGammaMinusOne = (integerPower >= 0 ? gendpdeIntegerPower(x, integerPower)
                                                              : pow(x, exponent - 1));
    *pressure = referencePressure + bulkModulus*(xPowGammaMinusOne*x - 1);
    *freeEnergy = (bulkModulus - referencePressure)/density
                + bulkModulus/((exponent - 1)*referenceDensity)*xPowGammaMinusOne;
}

/**
 * The V-B integrals I(k), J(k) (section 3) below the polynomial range, 0 < k < 1/16: the closed forms, with
 * ln((k+1)/k) as log1p(k) - log(k) so that no intermediate overflows for subnormal k.
 */
GENDPDE_CORE void gendpdeVolumeIntegralsClosedForm(GENDPDE_REAL k, GENDPDE_REAL* I, GENDPDE_REAL* J) {
    const GENDPDE_REAL s = sqrt(k);
    const GENDPDE_REAL arctangent = atan(1/s);
    const GENDPDE_REAL logarithm = log1p(k) - log(k);
    *I = (GENDPDE_REAL) 1/3 - k - (1 - k)*s*arctangent + k*logarithm;
    *J = (GENDPDE_REAL) 1.5 - logarithm + (1 - 3*k)/(2*s)*arctangent;
}

/**
 * The V-B integrals above the polynomial range, k >= 16: Gauss-Legendre quadrature of the integrands in mirror pairs
 * of nodes y, 1 - y (squares nodeSquared, mirrorNodeSquared; one coefficient per pair; VolumeVBTables.h).
 */
GENDPDE_CORE void gendpdeVolumeIntegralsQuadrature(GENDPDE_REAL k, GENDPDE_GLOBAL const GENDPDE_REAL* nodeSquared,
        GENDPDE_GLOBAL const GENDPDE_REAL* mirrorNodeSquared, GENDPDE_GLOBAL const GENDPDE_REAL* coefficient,
        int numPairs, GENDPDE_REAL* I, GENDPDE_REAL* J) {
    GENDPDE_REAL sumI = 0, sumJ = 0;
    for (int m = 0; m < numPairs; m++) {
        const GENDPDE_REAL a = 1/(nodeSquared[m] + k);
        const GENDPDE_REAL b = 1/(mirrorNodeSquared[m] + k);
        sumI += coefficient[m]*(a + b);
        sumJ += coefficient[m]*(a*a + b*b);
    }
    *I = sumI;
    *J = sumJ;
}

/**
 * The surface factor of V-C (docs/interfaces.md): V = V_B (1 + alpha x^2/(1 + x^2)) with x = max(0, a^2 - t)/w,
 * alpha = 3, threshold t = 0.4, width w = 0.3, where a^2 measures how one-sided a particle's neighbourhood is
 * (1 at a flat free surface). *factor receives 1 + alpha x^2/(1 + x^2), *slope its derivative with respect to a^2
 * (both continuous at the threshold, where the factor is 1 and its slope 0).
 */
GENDPDE_CORE void gendpdeSurfaceFactor(GENDPDE_REAL a2, GENDPDE_REAL* factor, GENDPDE_REAL* slope) {
    const GENDPDE_REAL alpha = 3, threshold = (GENDPDE_REAL) 0.4, inverseWidth = 1/(GENDPDE_REAL) 0.3;
    if (!(a2 > threshold)) {
        *factor = 1;
        *slope = 0;
        return;
    }
    const GENDPDE_REAL x = (a2 - threshold)*inverseWidth, denominator = 1/(1 + x*x);
    *factor = 1 + alpha*x*x*denominator;
    *slope = alpha*2*x*denominator*denominator*inverseWidth;
}

/**
 * What a pair update needs from the internal energies eps_i, eps_j and heat capacities C_i, C_j (sections 5 and 7),
 * with beta = 1/theta = C/eps: k_B Theta_ij with 1/Theta_ij = (beta_i + beta_j)/2, beta_i - beta_j, and the Ito
 * factor of the friction k_B (beta_i^2/C_i + beta_j^2/C_j)/(beta_i + beta_j)^2 = k_B (beta_i/eps_i + beta_j/eps_j)
 * /(beta_i + beta_j)^2 (GenDPDEPhysics.h, PairTemperatures, says why). beta = 1/theta stays within the range of the
 * temperatures, so no intermediate overflows for any allowed eps and C_V.
 */
GENDPDE_CORE void gendpdePairTemperatures(GENDPDE_REAL energyI, GENDPDE_REAL energyJ, GENDPDE_REAL heatCapacityI,
                                          GENDPDE_REAL heatCapacityJ, GENDPDE_REAL boltzmann,
                                          GENDPDE_REAL* pairThermalEnergy, GENDPDE_REAL* inverseTemperatureDifference,
                                          GENDPDE_REAL* frictionFactor) {
    const GENDPDE_REAL betaI = heatCapacityI/energyI, betaJ = heatCapacityJ/energyJ;
    const GENDPDE_REAL inverseSum = 1/(betaI + betaJ);
    *pairThermalEnergy = 2*boltzmann*inverseSum;
    *inverseTemperatureDifference = betaI - betaJ;
    *frictionFactor = boltzmann*(betaI/energyI + betaJ/energyJ)*inverseSum*inverseSum;
}

/**
 * The dissipative and random impulse P of one pair along e (section 6), in two stages: an explicit half (half the
 * friction, half the random impulse) and an implicit half solved exactly for the final relative velocity (a
 * Crank-Nicolson step of u = e.(v_i - v_j), whose stationary variance stays exact for any dt). u0 is u before the
 * update, inverseReducedMass 1/m_i + 1/m_j, friction the coefficient of the drift -friction omega_R^2 u,
 * noiseAmplitude the sigma of the random impulse sigma omega_R dW, xi a standard normal variate. P e goes to i and
 * -P e to j; *kineticChange receives the change of the pair's kinetic energy, P (u0 + P (1/m_i + 1/m_j)/2).
 */
GENDPDE_CORE GENDPDE_REAL gendpdePairImpulse(GENDPDE_REAL u0, GENDPDE_REAL omegaR, GENDPDE_REAL friction,
        GENDPDE_REAL noiseAmplitude, GENDPDE_REAL stepSize, GENDPDE_REAL sqrtStepSize, GENDPDE_REAL inverseReducedMass,
        GENDPDE_REAL xi, GENDPDE_REAL* kineticChange) {
    const GENDPDE_REAL frictionHalf = (GENDPDE_REAL) 0.5*friction*omegaR*omegaR*stepSize;
    const GENDPDE_REAL implicitFactor = 1/(1 + inverseReducedMass*frictionHalf);
    const GENDPDE_REAL randomHalf = (GENDPDE_REAL) 0.5*noiseAmplitude*omegaR*sqrtStepSize*xi;
    const GENDPDE_REAL explicitHalf = randomHalf - frictionHalf*u0;
    const GENDPDE_REAL u1 = u0 + inverseReducedMass*explicitHalf;
    const GENDPDE_REAL implicitHalf = (randomHalf - frictionHalf*u1)*implicitFactor;
    const GENDPDE_REAL impulse = explicitHalf + implicitHalf;
    *kineticChange = impulse*(u0 + (GENDPDE_REAL) 0.5*inverseReducedMass*impulse);
    return impulse;
}

/**
 * The heat that flows from j to i in one step (section 5): kappa omega_q (1/theta_i - 1/theta_j) dt
 * + alpha omega_R sqrt(dt) xi_q, with omega_q = omega_R^2 and randomAmplitude alpha = sqrt(2 k_B kappa).
 */
GENDPDE_CORE GENDPDE_REAL gendpdeConductiveHeat(GENDPDE_REAL omegaR, GENDPDE_REAL heatConduction,
        GENDPDE_REAL randomAmplitude, GENDPDE_REAL inverseTemperatureDifference, GENDPDE_REAL stepSize,
        GENDPDE_REAL sqrtStepSize, GENDPDE_REAL xiQ) {
    return heatConduction*omegaR*omegaR*inverseTemperatureDifference*stepSize
         + randomAmplitude*omegaR*sqrtStepSize*xiQ;
}

#endif /*GENDPDE_PHYSICS_CORE_H_*/
