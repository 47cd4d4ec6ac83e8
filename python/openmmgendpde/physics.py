"""The pointwise physics of GenDPDE (docs/theory.md sections 2-4), exactly as the kernels evaluate it.

Plain floats in any consistent units:

- ``particleVolumeVA(n0) -> (V, dV/dn0)``
- ``particleVolumeVB(n0, Rt) -> (V, dV/dn0)`` with Rt = R/f_cut; accurate to ~1e-15 relative for every n0 >= 0
- ``volumeIntegralsVB(k) -> (I, J)``: V = 4 pi Rt^3 I(k), dV/dn0 = -(8 pi^2/15) Rt^6 J(k), k = (2 pi/15) Rt^3 n0
- ``densityWeight(r, R) -> (w, dw/dr)``
- ``taitEquationOfState(n, n0, pi0, B_T, gamma_T) -> (pi, f)``
"""

from .gendpde import densityWeight, particleVolumeVA, particleVolumeVB, taitEquationOfState, volumeIntegralsVB

__all__ = ["densityWeight", "particleVolumeVA", "particleVolumeVB", "taitEquationOfState", "volumeIntegralsVB"]
