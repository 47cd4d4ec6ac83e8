# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The pointwise physics of GenDPDE (docs/theory.md sections 2-4 and 11), exactly as the kernels evaluate it.

Plain floats in any consistent units (OpenMM units where a law's parameters are checked, as GenDPDEForce checks them):

- ``particleVolumeVA(n0) -> (V, dV/dn0)``
- ``particleVolumeVB(n0, Rt) -> (V, dV/dn0)`` with Rt = R/f_cut; accurate to ~1e-15 relative for every n0 >= 0
- ``particleVolume(estimator, n0, G, R, f_cut) -> (V, dV/dn0, dV/dG)`` for any estimator (GenDPDEForce.VA, VB, VC;
  G the squared moment |g|^2, read by VC)
- ``volumeIntegralsVB(k) -> (I, J)``: V = 4 pi Rt^3 I(k), dV/dn0 = -(8 pi^2/15) Rt^6 J(k), k = (2 pi/15) Rt^3 n0
- ``densityWeight(r, R) -> (w, dw/dr)``
- ``taitEquationOfState(n, n0, pi0, B_T, gamma_T) -> (pi, f)``
- ``localEquationOfState(law, parameters, n0, pi0, B_T, gamma_T, p_b, n) -> (status, e, sigma, pi_0, pi_theta)`` for
  any law (a GenDPDEForce.EquationOfState value: GenDPDEForce.Tait, ...; its parameters as setEquationOfState
  takes them), with pi = pi_0 + theta pi_theta and f = e - theta sigma + C theta (1 - ln(theta/theta0))
- ``particleState(estimator, R, f_cut, n0, G, law, parameters, n0_T, pi0, B_T, gamma_T, p_b, isothermal, T, eps,
  sigma_stored, entropyKnown, C_V) -> (status, V, pi, u, pi dV/dn0, 2 pi dV/dG, C theta, sigma)``: everything a
  particle contributes to the force, for any estimator and law (its thermal state read only by a law that depends on
  temperature)

``status`` is 0 for a valid state, else why not: ``PARTICLE_NO_NEIGHBOR``, ``PARTICLE_OVERFLOW``,
``PARTICLE_OUTSIDE_DOMAIN``, ``PARTICLE_TEMPERATURE_JUMP``.
"""

from .gendpde import (
                      PARTICLE_NO_NEIGHBOR,
                      PARTICLE_OUTSIDE_DOMAIN,
                      PARTICLE_OVERFLOW,
                      PARTICLE_TEMPERATURE_JUMP,
                      PARTICLE_VALID,
                      densityWeight,
                      localEquationOfState,
                      particleState,
                      particleVolume,
                      particleVolumeVA,
                      particleVolumeVB,
                      taitEquationOfState,
                      volumeIntegralsVB,
)

__all__ = ["densityWeight", "localEquationOfState", "particleState", "particleVolume", "particleVolumeVA",
           "particleVolumeVB", "taitEquationOfState", "volumeIntegralsVB", "PARTICLE_VALID", "PARTICLE_NO_NEIGHBOR",
           "PARTICLE_OVERFLOW", "PARTICLE_OUTSIDE_DOMAIN", "PARTICLE_TEMPERATURE_JUMP"]
