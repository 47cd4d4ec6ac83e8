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

/* -------------------------------------------------------------------
   openmm-gendpde's LAMMPS package: fix gendpde, GenDPDE's integrator
   (docs/theory.md sections 5-7; docs/lammps.md): per step the Shardlow sweep
   of the pair terms at fixed positions, then velocity Verlet, as
   GenDPDEIntegrator steps, with each particle's internal energy.

   fix ID group gendpde mode seed keyword values ...
     mode   isoenergetic | isothermal | conservative
     seed   random seed, 0 ... 2147483647
     heat_capacity I C        C_V of type(s) I (energy/temperature)
     friction I J gamma       gamma of type pair(s) I J (mass/time)
     conduction I J kappa     kappa of type pair(s) I J (energy temperature/time)
     temperature T            bath temperature of the isothermal mode
     initial T | v_name       internal energies C_V T at the first run (not after a restart); v_name: an
                              atom-style variable of each particle's T (e.g. an atomfile variable)

   The sweep runs across subdomains in the order every OpenMM platform
   follows (GenDPDESweepOrder.h): cells at least R wide, 2x2x2 blocks in
   eight colours; a rank updates the blocks whose centre is in its subdomain
   (every particle of such a block is within 1.5 cells of it: ghosts), and
   after each colour the ghosts' new velocities and energies go to their
   owners and back out to every ghost. Blocks of one colour share no particle
   and each pair's random numbers are keyed on its particles' tags and the
   step, so the sweep does not depend on the number of ranks.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(gendpde,FixGenDPDE);
// clang-format on
#else

#ifndef LMP_FIX_GENDPDE_H
#define LMP_FIX_GENDPDE_H

#include "fix.h"
#include "lmptype.h"
#include <cstdint>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairGenDPDE;

class FixGenDPDE : public Fix {
 public:
  enum Mode { ISOENERGETIC = 0, ISOTHERMAL = 1, CONSERVATIVE = 2 };
  FixGenDPDE(class LAMMPS *, int, char **);
  ~FixGenDPDE() override;
  int setmask() override;
  void init() override;
  void setup_pre_force(int) override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void reset_dt() override;
  double compute_scalar() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  // The thermal state, for pair gendpde (local atoms).
  Mode getMode() const { return mode; }
  double getTemperature() const { return temperature; }
  double heatCapacity(int type) const { return heatCapacityOfType[type]; }
  double *internalEnergies() { return energy; }
  /** sigma at the density each internal energy belongs to; NaN where it is not known. */
  double *storedEntropies() { return entropy; }

 private:
  Mode mode;
  int seed;
  double temperature = 0.0, initialTemperature = 0.0;
  bool hasTemperature = false, hasInitial = false;
  std::string initialVariable;    // initial v_name
  int energiesSet = 0;            // saved in restart files
  double dtv, dtf;
  std::vector<double> heatCapacityOfType, frictionOfPair,
      conductionOfPair;    // by type, type pair (ntypes+1)^2
  std::vector<bool> heatCapacitySet;
  double *energy = nullptr, *entropy = nullptr;    // per atom (ghosts: scratch of the sweep)
  PairGenDPDE *pair = nullptr;

  // The sweep (see the header comment).
  struct SweepPair {
    int i, j;    // tag - 1 of the two particles, i < j (the particle indices of the random stream)
    int li, lj;    // their local indices (local or ghost)
    int group;    // the rank of the block it was in when found (the number of blocks: none of this rank's)
  };
  static std::uint64_t pairKey(const SweepPair &p)
  {
    return (std::uint64_t) (std::uint32_t) p.i << 32 | (std::uint32_t) p.j;
  }
  int numCells[3];
  double cellWidth[3];
  int blockLow[3], blockCount[3];     // this rank's blocks
  int gridLow[3], gridCount[3];       // the extended cells they cover
  std::vector<double> sweepEnergy;    // eps / mvv2e, local and ghost
  std::vector<int> extendedCell;      // each particle's cell in this rank's frame
  std::vector<char> modified, touched;
  // Candidates: the pairs closer than R + skin among the particles near this rank's blocks, by the block they were
  // in, then by (i, j); found again when LAMMPS has built its neighbour lists again (every particle has then moved
  // less than skin/2).
  std::vector<SweepPair> candidates;
  bigint candidatesBuiltAt = -1;
  std::vector<int> binHead, binNext;
  std::vector<double>
      builtPositions;    // the local particles' positions when the candidates were found
  // Each step: the pairs closer than R of each block (by block rank: colour by colour), in sweep order
  std::vector<int> rankOfBlock, blockRankStart, colourStart, pairBlockRank, blockPairs, blockFirst,
      blockOrder;
  std::vector<int> movedIn;
  std::vector<SweepPair> sweepList;    // the pairs in sweep order
  struct PairTables {
    std::vector<double> inverseMass, heatCapacity, conduction, noise;    // by type, type pair
  } pairTables;
  // The run's pair terms, as GenDPDEIntegrator decides them (GenDPDEStepTerms): whether any pair of types has
  // friction, heat conduction (isoenergetic); the sweep runs if either does.
  struct {
    int dissipation = 0, conduction = 0;
  } terms;
  int commPhase =
      0;    // 0: velocities, energies and cells (start of the sweep); 1: velocities and energies
  void kick();
  void makePairTables();
  int packState(int i, double *buf) const;
  int unpackState(int i, const double *buf);
  void sweep();
  void prepareCells();
  void rankBlocks();
  void findCandidates();
  int blockRankOf(int a, int b) const;
  void orderPairs();
  void sweepPairs(const SweepPair *pairs, int count, bool isoenergetic);
  double ghostNeed() const;
};

}    // namespace LAMMPS_NS

#endif
#endif
