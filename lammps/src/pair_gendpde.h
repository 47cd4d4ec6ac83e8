/* -*- c++ -*- ----------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories
   Steve Plimpton, sjplimp@sandia.gov

   GENDPDE package (openmm-gendpde's LAMMPS package), a plugin for LAMMPS.
   Copyright (c) 2026 The openmm-gendpde developers. This file is
   distributed under the MIT License (the LICENSE file of openmm-gendpde),
   which is compatible with the GNU General Public License version 2 that
   LAMMPS is distributed under. See lammps/README of openmm-gendpde.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing authors: the openmm-gendpde developers
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   pair_style gendpde: GenDPDE's many-body conservative force (docs/theory.md
   sections 2-4, 11 and 12 of openmm-gendpde; doc/pair_gendpde.rst).

   pair_style gendpde R estimator f_cut [background p_b]
     R          pair range (distance units)
     estimator  va | vb | vc  (the density estimators V-A, V-B, V-C)
     f_cut      cutoff scaling: the estimators' reduced range is R/f_cut
                (in [1, 100], GenDPDEForce's range)
     p_b        background pressure (energy/volume units, >= 0)
   pair_coeff I I law parameters ...
     one law per type with its parameters, as GenDPDEForce::setEquationOfState
     takes them (the table of GenDPDEEquationsOfState.h); pressure-like
     parameters in energy/volume units. A pair of different types takes no
     coefficients.

   Two passes over a half neighbor list (newton on): the primitive densities
   n0_i (and V-C's first moments g_i) summed over pairs, ghosts' sums
   reverse-communicated to their owners; each owner's state from the physics
   core (gendpdeParticleState), its force coefficient (and V-C's moment force)
   forward-communicated to the ghosts; then the pair forces
   (gendpdePairForce). A law that depends on temperature reads and keeps each
   particle's thermal state in fix gendpde, by name (Fix::extract).
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(gendpde,PairGenDPDE);
// clang-format on
#else

#ifndef LMP_PAIR_GENDPDE_H
#define LMP_PAIR_GENDPDE_H

#include "pair.h"

namespace LAMMPS_NS {

class PairGenDPDE : public Pair {
 public:
  PairGenDPDE(class LAMMPS *);
  ~PairGenDPDE() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;
  void *extract(const char *, int &) override;

 private:
  // A type's law in the physics core's terms (gendpdeLocalEquationOfState).
  struct Law {
    int law = -1;    // GENDPDE_EOS_*; -1: not set
    // as pair_coeff gives them (the Tait four first if the law extends Tait)
    double given[12] = {0.0};
    // in the core's order, the background pressure included (pack)
    double parameter[12] = {0.0};
    int integer_power = -1;
  };
  double background = 0.0;
  void pack(Law &law) const;
  double cut_global = 0.0, fcut = 1.0;
  int estimator = 0;
  double k_per_density, volume_scale, derivative_scale, moment_scale, density_softening;
  double weight_scale, weight_derivative_scale;
  std::vector<Law> laws;    // by type, 1 ... ntypes
  // per atom (local and ghost): primitive density, V-C's moment g, force coefficient, V-C's
  // moment force q
  int nmax = 0;
  double *density = nullptr, **moment = nullptr, *coefficient = nullptr, **moment_force = nullptr;
  struct ClosePair {
    int i, j;                // local indices (i local, j local or ghost)
    double dx, dy, dz, r;    // d = x_i - x_j, r = |d| > 0, r^2 < R^2
  };
  std::vector<ClosePair> close_pairs;    // pass 1's pairs closer than R, read by pass 2
  bool moments() const;
  void grow();
  void particle_error(int status, int i, double volume);
  bool depends_on_temperature() const;
  int temperature_dependent = 0;    // depends_on_temperature() at init_style (extract)
  // the thermal state of fix gendpde (Fix::extract): per atom eps_i and the entropy sigma_i they
  // belong to (NaN: not known), C_V by type, the bath temperature, whether the mode is isothermal
  struct ThermalState {
    double *energy, *entropy, *heat_capacity;
    double temperature;
    int isothermal;
  };
  class Fix *thermal_fix();
  void read_thermal_state(class Fix *, ThermalState &);
};

}    // namespace LAMMPS_NS

#endif
#endif
