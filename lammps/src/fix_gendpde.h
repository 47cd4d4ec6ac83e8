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
   fix gendpde: GenDPDE's integrator (docs/theory.md sections 5-7 of
   openmm-gendpde; doc/fix_gendpde.rst): per step the Shardlow-like sweep
   of the pair terms at fixed positions, then velocity Verlet, as
   GenDPDEIntegrator steps, with each particle's internal energy.

   fix ID all gendpde mode seed keyword values ...   (group all: the fix is
                                                     every atom's only integrator)
     mode   isoenergetic | isothermal | conservative
     seed   random seed, 0 ... 2147483647
     heat_capacity I C       C_V of type(s) I (energy/temperature)
     friction I J gamma      gamma of type pair(s) I J (mass/time)
     conduction I J kappa    kappa of type pair(s) I J (energy temperature/time)
     temperature T           bath temperature of the isothermal mode
     initial T | v_name      internal energies C_V T at the first run (not
                             after a restart, which needs the writing
                             fix's ID); v_name: an atom-style
                             variable of each particle's T

   The sweep runs across subdomains in the order every OpenMM platform of
   openmm-gendpde follows (GenDPDESweepDefinition.h), made once per build
   from the candidate pairs (closer than 1.1 R at the build's positions):
   cells at least 1.1 R wide, 2x2x2 blocks in eight colours, within a
   block greedy levels of its candidates in (i, j) order. The order is
   built at the first step of a run and when the box has changed or an
   atom has moved more than 0.05 R since the build (the fix then makes
   LAMMPS build its lists at that step: neighbor skin >= 0.1 R); each step
   updates, in that order, the candidates closer than R. A rank updates
   the blocks whose centre is in its subdomain (every particle of such a
   block is within 1.5 cells of it: ghosts), and after each colour the
   ghosts' new velocities and energies go to their owners and back out to
   every ghost. Blocks of one colour share no particle and each pair's
   random numbers are keyed on its particles' IDs and the step, so the
   sweep does not depend on the number of ranks.

   pair_style gendpde reads the thermal state by name (extract):
   internal_energy, entropy (per atom), heat_capacity (per type),
   bath_temperature, isothermal.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(gendpde,FixGenDPDE);
// clang-format on
#else

#ifndef LMP_FIX_GENDPDE_H
#define LMP_FIX_GENDPDE_H

#include "fix.h"
#include "gendpde/GenDPDESweepDefinition.h"

namespace LAMMPS_NS {

class FixGenDPDE : public Fix {
 public:
  enum Mode { ISOENERGETIC = 0, ISOTHERMAL = 1, CONSERVATIVE = 2 };
  FixGenDPDE(class LAMMPS *, int, char **);
  ~FixGenDPDE() override;
  int setmask() override;
  void init() override;
  void setup_pre_force(int) override;
  void initial_integrate(int) override;
  void post_integrate() override;
  void final_integrate() override;
  void reset_dt() override;
  double compute_scalar() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
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
  void *extract(const char *, int &) override;

 private:
  Mode mode;
  int seed;
  double temperature = 0.0, initial_temperature = 0.0;
  bool has_temperature = false, has_initial = false;
  std::string initial_variable;    // initial v_name
  int energies_set = 0;            // saved in restart files
  double dtv, dtf;
  // by type (ntypes + 1) and by type pair ((ntypes + 1)^2)
  std::vector<double> heat_capacity_of_type, friction_of_pair, conduction_of_pair;
  std::vector<bool> heat_capacity_set;
  double *energy = nullptr, *entropy = nullptr;    // per atom (ghosts: scratch of the sweep)
  int isothermal = 0;                              // mode == ISOTHERMAL (extract)
  // pair_style gendpde's (Pair::extract): whether it is defined, its range R, whether a law
  // depends on temperature
  bool has_pair = false;
  double pair_range = 0.0;
  int pair_thermal = 0;

  // The sweep (see the header comment). Its order of pair updates is made once per build
  // (GenDPDESweepDefinition.h): at the first step of a run, and when the box has changed or some
  // atom has moved more than rebuildDisplacement2(R) from its position at the build (the rule,
  // checked after each drift; the fix then makes LAMMPS build its lists at that step).
  struct SweepPair {
    std::uint32_t i, j;    // atom ID - 1 of the two particles, i < j: the stream's indices
    int li, lj;            // their local indices (local or ghost)
    int group;    // the rank of its block on this rank (the number of blocks: none of this rank's)
  };
  static std::uint64_t pair_key(const SweepPair &p) { return (std::uint64_t) p.i << 32 | p.j; }
  int num_cells[3];
  double cell_width[3];
  int block_low[3], block_count[3];    // this rank's blocks
  int grid_low[3], grid_count[3];      // the extended cells they cover
  std::vector<double> sweep_energy;    // eps / mvv2e, local and ghost
  std::vector<double> sweep_x;         // the build's positions, local and ghost (at a build)
  std::vector<int> extended_cell;      // each particle's cell in this rank's frame (at a build)
  std::vector<char> modified, touched;
  // Per atom (travelling with it, in restart files): its position at the order's build (wrapped as
  // LAMMPS had it then; NaN: none) and its image flags then.
  double **build_x = nullptr;
  int **build_image = nullptr;
  // The build's box, and whether there is an order (saved in restart files: a continued run rebuilds
  // the same order from the positions at its build).
  int has_build = 0;
  double build_boxlo[3] = {0.0, 0.0, 0.0}, build_boxhi[3] = {0.0, 0.0, 0.0};
  double build_sublo[3] = {0.0, 0.0, 0.0}, build_subhi[3] = {0.0, 0.0, 0.0};    // the blocks'
  bool setup_pending = false;    // the first sweep of a run: build, or rebuild the kept order
  bool build_pending = false;    // the rule fired after the last drift
  bigint indexed_at = -1;        // neighbor->lastcall when the order's local indices were set
  std::vector<SweepPair> candidates;    // (scratch of a build)
  std::vector<int> bin_head, bin_next;
  // The order: this rank's blocks by rank (colour by colour), each block's pairs in sweep order
  std::vector<int> rank_of_block, block_rank_start, colour_start;
  std::vector<double> block_centre;     // by block rank (3 each)
  std::vector<SweepPair> sweep_list;    // the pairs in sweep order
  std::vector<int> slot_of, place;      // (scratch of order_blocks)
  GenDPDEPlugin::SweepDefinition::BlockScratch block_scratch;
  struct PairTables {
    std::vector<double> inverse_mass, heat_capacity, conduction, noise;    // by type, type pair
  } pair_tables;
  // The run's pair terms, as GenDPDEIntegrator decides them (GenDPDEStepTerms): whether any pair of
  // types has friction, heat conduction (isoenergetic); the sweep runs if either does.
  struct {
    int dissipation = 0, conduction = 0;
  } terms;
  // what the sweep's exchanges carry (pack_state)
  enum CommPhase { START = 0, COLOUR = 1, CELLS = 2, POSITIONS = 3 };
  int comm_phase = START;
  void check_restart_id();
  void kick();
  void make_pair_tables();
  int pack_state(int i, double *buf) const;
  int unpack_state(int i, const double *buf);
  void sweep();
  bool rule_fires();
  void build_order(bool from_stored);
  void remap_order();
  void prepare_cells();
  void rank_blocks();
  void check_atom_ids();
  void find_candidates();
  int block_rank_of(int a, int b) const;
  void order_blocks();
  void sweep_pairs(const SweepPair *pairs, int count, bool isoenergetic);
  double ghost_need() const;
};

}    // namespace LAMMPS_NS

#endif
#endif
