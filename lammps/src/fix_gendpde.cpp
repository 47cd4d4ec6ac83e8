/* ----------------------------------------------------------------------
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
   openmm-gendpde's LAMMPS package: fix gendpde (fix_gendpde.h).
------------------------------------------------------------------------- */

#include "fix_gendpde.h"

#include "atom.h"
#include "citeme.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "gendpde_core.h"
#include "group.h"
#include "input.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <mpi.h>

// A hint to load a particle's data a few pair updates before the sweep reads it: without it a
// 32,000-particle run on one rank took a median 5% more CPU time (perf stat, 200 steps, 6
// alternating pairs of runs: -1% to +9%). GCC, Clang and the compilers that define __GNUC__
// (Intel's) have __builtin_prefetch; elsewhere the hint is left out.
#if defined(__GNUC__) || defined(__clang__)
#define GENDPDE_PREFETCH(address) __builtin_prefetch(address)
#else
#define GENDPDE_PREFETCH(address) ((void) 0)
#endif

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace GenDPDEPlugin;
using namespace GenDPDEPlugin::Physics;

static const char cite_gendpde[] =
    "GenDPDE: doi:10.1039/c9cp04404c\n\n"
    "@Article{BonetAvalos19,\n"
    " author = {J. Bonet Avalos and M. L{\\'{\\i}}sal and J. P. Larentzos and A. D. Mackie and\n"
    "           J. K. Brennan},\n"
    " title = {Generalised Dissipative Particle Dynamics with Energy Conservation: Density- and\n"
    "          Temperature-Dependent Potentials},\n"
    " journal = {Phys.\\ Chem.\\ Chem.\\ Phys.},\n"
    " year = 2019,\n"
    " volume = 21,\n"
    " number = 45,\n"
    " pages = {24891--24911}\n"
    "}\n\n";

FixGenDPDE::FixGenDPDE(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  if (lmp->citeme) lmp->citeme->add(cite_gendpde);
  if (narg < 5)
    error->all(FLERR,
               "Illegal fix gendpde command: fix ID all gendpde mode seed keyword values ...");
  // Every atom: the sweep, the internal energies and the conserved energy are the whole system's
  // (atoms outside a group would feel the pair forces, stay frozen and take no part in the sweep).
  if (strcmp(group->names[igroup], "all") != 0)
    error->all(FLERR,
               "fix gendpde: group '{}' is not allowed: it must be all (the fix integrates every "
               "atom; its sweep and internal energies are the whole system's)",
               group->names[igroup]);
  check_restart_id();
  const std::string name = arg[3];
  if (name == "isoenergetic")
    mode = ISOENERGETIC;
  else if (name == "isothermal")
    mode = ISOTHERMAL;
  else if (name == "conservative")
    mode = CONSERVATIVE;
  else
    error->all(FLERR,
               "fix gendpde: mode '{}' is not allowed: it must be isoenergetic, isothermal or "
               "conservative",
               name);
  isothermal = mode == ISOTHERMAL ? 1 : 0;
  seed = utils::inumeric(FLERR, arg[4], false, lmp);
  if (seed < 0)
    error->all(FLERR, "fix gendpde: seed = {} is not allowed: it must be in [0, 2147483647]",
               arg[4]);

  const int ntypes = atom->ntypes;
  heat_capacity_of_type.assign(ntypes + 1, 0.0);
  heat_capacity_set.assign(ntypes + 1, false);
  friction_of_pair.assign((ntypes + 1) * (ntypes + 1), 0.0);
  conduction_of_pair.assign((ntypes + 1) * (ntypes + 1), 0.0);
  auto number = [&](int k, const char *what, bool positive) {
    const double value = utils::numeric(FLERR, arg[k], false, lmp);
    if (!(std::isfinite(value) && (positive ? value > 0.0 : value >= 0.0)))
      error->all(FLERR, "fix gendpde: {} = {} is not allowed: it must be {} and finite", what,
                 arg[k], positive ? "> 0" : ">= 0");
    return value;
  };
  int k = 5;
  while (k < narg) {
    const std::string keyword = arg[k];
    if (keyword == "heat_capacity" && k + 2 < narg) {
      int lo, hi;
      utils::bounds(FLERR, arg[k + 1], 1, ntypes, lo, hi, error);
      const double value = number(k + 2, "heat_capacity C_V", true);
      for (int t = lo; t <= hi; t++) {
        heat_capacity_of_type[t] = value;
        heat_capacity_set[t] = true;
      }
      k += 3;
    } else if ((keyword == "friction" || keyword == "conduction") && k + 3 < narg) {
      int ilo, ihi, jlo, jhi;
      utils::bounds(FLERR, arg[k + 1], 1, ntypes, ilo, ihi, error);
      utils::bounds(FLERR, arg[k + 2], 1, ntypes, jlo, jhi, error);
      const double value =
          number(k + 3, keyword == "friction" ? "friction gamma" : "conduction kappa", false);
      std::vector<double> &table = keyword == "friction" ? friction_of_pair : conduction_of_pair;
      for (int i = ilo; i <= ihi; i++)
        for (int j = jlo; j <= jhi; j++)
          table[i * (ntypes + 1) + j] = table[j * (ntypes + 1) + i] = value;
      k += 4;
    } else if (keyword == "temperature" && k + 1 < narg) {
      temperature = number(k + 1, "temperature T", true);
      has_temperature = true;
      k += 2;
    } else if (keyword == "initial" && k + 1 < narg) {
      if (strncmp(arg[k + 1], "v_", 2) == 0)
        initial_variable = arg[k + 1] + 2;
      else
        initial_temperature = number(k + 1, "initial temperature T", true);
      has_initial = true;
      k += 2;
    } else
      error->all(
          FLERR,
          "fix gendpde: keyword '{}' is not allowed (or lacks its values): heat_capacity I C, "
          "friction I J gamma, conduction I J kappa, temperature T, initial T",
          keyword);
  }
  if (mode == ISOTHERMAL && !has_temperature)
    error->all(FLERR, "fix gendpde: the isothermal mode needs the bath temperature: temperature T");
  if (mode == ISOENERGETIC)
    for (int t = 1; t <= ntypes; t++)
      if (!heat_capacity_set[t])
        error->all(FLERR,
                   "fix gendpde: type {} has no heat capacity: the isoenergetic mode needs "
                   "heat_capacity {} C",
                   t, t);

  time_integrate = 1;
  restart_global = 1;
  restart_peratom = 1;
  scalar_flag = 1;
  extscalar = 1;
  global_freq = 1;
  peratom_flag = 1;
  size_peratom_cols = 0;
  peratom_freq = 1;
  comm_forward = 5;
  comm_reverse = 5;
  // the sweep's order asks LAMMPS to build its lists at the steps it is built at (post_integrate)
  force_reneighbor = 1;
  next_reneighbor = -1;
  create_attribute = 1;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) {
    energy[i] = 0.0;
    entropy[i] = std::numeric_limits<double>::quiet_NaN();
    set_arrays(i);
  }
}

namespace {
// The fixes' per-atom restart data that read_restart has read and not yet given to a fix: LAMMPS
// keeps their IDs, styles and whether a fix took them in protected members of Modify, which a class
// derived from it may name (pointers to members of Modify; no object of this class is made).
struct RestartRecords : Modify {
  static char **Modify::*ids() { return &RestartRecords::id_restart_peratom; }
  static char **Modify::*styles() { return &RestartRecords::style_restart_peratom; }
  static int *Modify::*used() { return &RestartRecords::used_restart_peratom; }
};
}    // namespace

void FixGenDPDE::check_restart_id()
{
  // LAMMPS gives a fix the state a restart file holds only under the ID of the fix that wrote it:
  // under another ID the internal energies would be left unused and set again from initial (the
  // conserved energy jumps). Refused, naming the ID.
  if (modify->nfix_restart_peratom == 0) return;
  char **ids = modify->*RestartRecords::ids(), **styles = modify->*RestartRecords::styles();
  const int *used = modify->*RestartRecords::used();
  for (int k = 0; k < modify->nfix_restart_peratom; k++)
    if (!used[k] && strcmp(styles[k], style) == 0 && strcmp(ids[k], id) != 0)
      error->all(FLERR,
                 "fix gendpde: the restart file holds the state of fix {} (style {}), its "
                 "internal energies and sweep order, which LAMMPS gives only to a fix of that "
                 "ID: define fix {} ... gendpde instead of fix {} (under another ID the internal "
                 "energies would be set again from initial)",
                 ids[k], styles[k], ids[k], id);
}

FixGenDPDE::~FixGenDPDE()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(energy);
  memory->destroy(entropy);
  memory->destroy(build_x);
  memory->destroy(build_image);
}

int FixGenDPDE::setmask()
{
  return INITIAL_INTEGRATE | POST_INTEGRATE | FINAL_INTEGRATE | PRE_FORCE;
}

void FixGenDPDE::init()
{
  // The fix is the time integrator of its atoms: another fix that integrates any of them (fix nve,
  // nvt, npt, a second fix gendpde, ...) would move them twice per step, which LAMMPS only warns
  // about. In the modes with the sweep, a fix that changes the box's size or shape during a run (a
  // barostat, fix deform) is refused: the sweep's cells and ghost cutoff are those of the box at
  // the run's start (fix balance, which moves only the subdomains, runs).
  for (int k = 0; k < modify->nfix; k++) {
    const Fix *other = modify->fix[k];
    if (other == this) continue;
    if (other->time_integrate) {
      int local = 0, any = 0;
      for (int i = 0; i < atom->nlocal && !local; i++)
        if ((atom->mask[i] & groupbit) && (atom->mask[i] & other->groupbit)) local = 1;
      MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, world);
      if (any)
        error->all(FLERR,
                   "fix gendpde: fix {} (style {}) also integrates atoms of group {}, which would "
                   "move twice per step: fix gendpde must be their only time integrator (its modes "
                   "are its thermostats; unfix {})",
                   other->id, other->style, group->names[igroup], other->id);
    }
    if (mode != CONSERVATIVE && (other->box_change & (BOX_CHANGE_SIZE | BOX_CHANGE_SHAPE)))
      error->all(FLERR,
                 "fix gendpde: fix {} (style {}) changes the box during a run, which the {} mode "
                 "does not allow: the sweep's cells and ghost cutoff are those of the box at the "
                 "run's start (change the box between runs: change_box)",
                 other->id, other->style, mode == ISOTHERMAL ? "isothermal" : "isoenergetic");
  }
  dtv = update->dt;
  dtf = 0.5 * update->dt * force->ftm2v;
  // pair_style gendpde's range R and whether its laws depend on temperature, by name
  // (Pair::extract)
  Pair *pair = force->pair_match("^gendpde$", 0);
  has_pair = pair != nullptr;
  pair_range = 0.0;
  pair_thermal = 0;
  if (has_pair) {
    int dim_range = -1, dim_thermal = -1;
    const double *range = (double *) pair->extract("cut_global", dim_range);
    const int *thermal = (int *) pair->extract("temperature_dependent", dim_thermal);
    if (!range || !thermal || dim_range != 0 || dim_thermal != 0)
      error->all(FLERR, "fix gendpde: pair_style {} does not provide its range and laws",
                 force->pair_style);
    pair_range = *range;
    pair_thermal = *thermal;
  }
  if (mode != CONSERVATIVE && !has_pair)
    error->all(FLERR, "fix gendpde: the {} mode needs pair_style gendpde (its pair range R)",
               mode == ISOTHERMAL ? "isothermal" : "isoenergetic");
  if (pair_thermal)
    for (int t = 1; t <= atom->ntypes; t++)
      if (!heat_capacity_set[t])
        error->all(
            FLERR,
            "fix gendpde: type {} has no heat capacity, which its law needs: heat_capacity {} C", t,
            t);
  if (mode != CONSERVATIVE) {
    if (domain->triclinic) error->all(FLERR, "fix gendpde: the sweep needs an orthogonal box");
    if (!(domain->xperiodic && domain->yperiodic && domain->zperiodic))
      error->all(FLERR, "fix gendpde: the sweep needs a box periodic in x, y and z");
    if (!(force->newton_pair)) error->all(FLERR, "fix gendpde requires newton pair on");
  }
  make_pair_tables();    // (the masses, units and parameters a run reads)
}

void FixGenDPDE::setup_pre_force(int /*vflag*/)
{
  // Before the first force evaluation of a run: the internal energies C_V T of a fresh start (a
  // restart has them).
  if (!energies_set && has_initial) {
    // one temperature, or each particle's from an atom-style variable (e.g. an atomfile variable of
    // the temperatures an OpenMM run had: GenDPDEIntegrator.getParticleTemperatures)
    std::vector<double> theta(atom->nlocal, initial_temperature);
    if (!initial_variable.empty()) {
      const int index = input->variable->find(initial_variable.c_str());
      if (index < 0 || !input->variable->atomstyle(index))
        error->all(FLERR, "fix gendpde: initial v_{}: no atom-style variable of that name",
                   initial_variable);
      input->variable->compute_atom(index, igroup, theta.data(), 1, 0);
    }
    for (int i = 0; i < atom->nlocal; i++) {
      if ((atom->mask[i] & groupbit) && !(theta[i] > 0.0 && std::isfinite(theta[i])))
        error->one(FLERR,
                   "fix gendpde: initial temperature {} of atom {} is not allowed: it must be > 0",
                   theta[i], atom->tag[i]);
      energy[i] = heat_capacity_of_type[atom->type[i]] * theta[i];
      entropy[i] = std::numeric_limits<double>::quiet_NaN();
    }
    energies_set = 1;
  }
  const bool needs_energies = mode == ISOENERGETIC || (pair_thermal && mode == CONSERVATIVE);
  if (needs_energies && !energies_set)
    error->all(
        FLERR,
        "fix gendpde: the internal energies are not set: give initial T (or read a restart file)");
  if (mode != CONSERVATIVE) {
    // The sweep's candidates (pairs closer than 1.1 R at the order's build) and its ghosts hold
    // while no atom has moved more than 0.05 R since the build; the fix makes LAMMPS build its
    // lists then, so a skin of 0.1 R keeps LAMMPS's own lists (and its check, skin/2) complete.
    const double least = SweepDefinition::skinFraction * pair_range;
    if (!(neighbor->skin >= least))
      error->all(FLERR,
                 "fix gendpde: the neighbour skin {} is below {} = 0.1 R (R = {}), which the "
                 "sweep's order needs: neighbor {} bin",
                 neighbor->skin, least, pair_range, least);
    const double need = ghost_need();
    for (int d = 0; d < 3; d++)
      if (comm->cutghost[d] < need)
        error->all(
            FLERR,
            "fix gendpde: the ghost cutoff {} is below what the sweep needs, {} (1.5 sweep cells + "
            "the skin): comm_modify cutoff {}",
            comm->cutghost[d], need, need);
  }
  // the first sweep of the run builds the order (or the kept one again: sweep)
  setup_pending = true;
  build_pending = false;
}

double FixGenDPDE::ghost_need() const
{
  return SweepDefinition::ghostCutoff(domain->prd, pair_range, neighbor->skin);
}

void FixGenDPDE::make_pair_tables()
{
  // What the pair updates read by type and type pair, in the units of m v^2/2 (energies over
  // mvv2e): 1/m, C_V, kappa, and the noise amplitude, sqrt(2 k_B kappa) of the heat (isoenergetic)
  // or sqrt(2 gamma k_B T) of the bath (isothermal).
  const int ntypes = atom->ntypes;
  const double mvv2e = force->mvv2e, boltzmann = force->boltz / mvv2e;
  const bool isoenergetic = (mode == ISOENERGETIC);
  terms.dissipation = terms.conduction = 0;
  pair_tables.inverse_mass.assign(ntypes + 1, 0.0);
  pair_tables.heat_capacity.assign(ntypes + 1, 0.0);
  pair_tables.conduction.assign((ntypes + 1) * (ntypes + 1), 0.0);
  pair_tables.noise.assign((ntypes + 1) * (ntypes + 1), 0.0);
  for (int a = 1; a <= ntypes; a++) {
    pair_tables.inverse_mass[a] = atom->mass ? 1.0 / atom->mass[a] : 0.0;
    pair_tables.heat_capacity[a] = heat_capacity_of_type[a] / mvv2e;
    for (int b = 1; b <= ntypes; b++) {
      const int ab = a * (ntypes + 1) + b;
      pair_tables.conduction[ab] = conduction_of_pair[ab] / mvv2e;
      pair_tables.noise[ab] = isoenergetic
          ? gendpdeHeatNoise(pair_tables.conduction[ab], boltzmann)
          : gendpdeBathNoise(friction_of_pair[ab], boltzmann, temperature);
      terms.dissipation |= (mode != CONSERVATIVE && friction_of_pair[ab] > 0.0);
      terms.conduction |= (isoenergetic && conduction_of_pair[ab] > 0.0);
    }
  }
}

void FixGenDPDE::reset_dt()
{
  dtv = update->dt;
  dtf = 0.5 * update->dt * force->ftm2v;
}

void FixGenDPDE::initial_integrate(int /*vflag*/)
{
  // docs/theory.md section 6: the pair sweep at fixed positions on the full-step velocities, half
  // kick, drift.
  if (terms.dissipation || terms.conduction) sweep();
  kick();
  double **x = atom->x, **v = atom->v;
  const int *mask = atom->mask;
  const double limit = has_pair ? pair_range : std::numeric_limits<double>::infinity();
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double dx = dtv * v[i][0], dy = dtv * v[i][1], dz = dtv * v[i][2];
    // A particle that would cross its whole neighbourhood in one step is no longer being
    // integrated.
    if (!(dx * dx + dy * dy + dz * dz <= limit * limit))
      error->one(
          FLERR,
          "fix gendpde: atom {} would move {} in one step at step {} (more than R = {}): the run "
          "went bad; reduce the timestep",
          atom->tag[i], std::sqrt(dx * dx + dy * dy + dz * dz), update->ntimestep, limit);
    x[i][0] += dx;
    x[i][1] += dy;
    x[i][2] += dz;
  }
}

void FixGenDPDE::final_integrate()
{
  kick();
}

void FixGenDPDE::kick()
{
  // Half a step of the forces: v += (dt/2) F/m.
  double **v = atom->v, **f = atom->f;
  const double *rmass = atom->rmass, *mass = atom->mass;
  const int *type = atom->type, *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double dtfm = dtf / (rmass ? rmass[i] : mass[type[i]]);
    for (int d = 0; d < 3; d++) v[i][d] += dtfm * f[i][d];
  }
}

/* ---------------------------------------------------------------------- */

void FixGenDPDE::post_integrate()
{
  // The rule of the order's builds, after the drift (before LAMMPS decides whether to build its
  // lists): when it fires, LAMMPS builds them at this step and the next sweep builds the order from
  // these positions.
  if (!(terms.dissipation || terms.conduction) || setup_pending) return;
  if (rule_fires()) {
    build_pending = true;
    next_reneighbor = update->ntimestep;
  }
}

bool FixGenDPDE::rule_fires()
{
  // Whether the order must be built (GenDPDESweepDefinition.h): there is none, the box has changed,
  // or some atom has moved more than rebuildDisplacement2(R) from its position at the build (or has
  // none: it came later). A global OR over the ranks.
  int fires = has_build ? 0 : 1;
  for (int d = 0; d < 3; d++)
    if (domain->boxlo[d] != build_boxlo[d] || domain->boxhi[d] != build_boxhi[d]) fires = 1;
  const double limit = SweepDefinition::rebuildDisplacement2(pair_range);
  double **x = atom->x;
  const imageint *image = atom->image;
  const int *mask = atom->mask;
  const double *prd = domain->prd;
  for (int i = 0; i < atom->nlocal && !fires; i++) {
    if (!(mask[i] & groupbit)) continue;
    const int now[3] = {(int) (image[i] & IMGMASK) - IMGMAX,
                        (int) (image[i] >> IMGBITS & IMGMASK) - IMGMAX,
                        (int) (image[i] >> IMG2BITS) - IMGMAX};
    double moved2 = 0.0;
    for (int d = 0; d < 3; d++) {
      const double delta = x[i][d] + (now[d] - build_image[i][d]) * prd[d] - build_x[i][d];
      moved2 += delta * delta;
    }
    if (!(moved2 <= limit)) fires = 1;    // (NaN: no build position)
  }
  int any = 0;
  MPI_Allreduce(&fires, &any, 1, MPI_INT, MPI_MAX, world);
  return any != 0;
}

void FixGenDPDE::prepare_cells()
{
  // The sweep's cells (SweepDefinition, as GenDPDESweepOrder computes them: at least 1.1 R wide),
  // and this rank's blocks: those whose centre, boxlo + (2b + 1.5) w, is in the subdomain.
  const double reach = SweepDefinition::candidateRange(pair_range);
  for (int d = 0; d < 3; d++) {
    num_cells[d] = SweepDefinition::cellCount(domain->prd[d], reach, true);
    if (num_cells[d] < SweepDefinition::minCellsAcrossSubdomains)
      error->all(FLERR,
                 "fix gendpde: the box is {} wide along {}, less than {} candidate ranges 1.1 R = "
                 "{} (R = {}): too small for the sweep across subdomains",
                 domain->prd[d], "xyz"[d], SweepDefinition::minCellsAcrossSubdomains, reach,
                 pair_range);
    cell_width[d] = domain->prd[d] / num_cells[d];
    const double lo = domain->sublo[d], hi = domain->subhi[d], base = domain->boxlo[d],
                 w = cell_width[d];
    int first = (int) std::floor((lo - base) / (2.0 * w) - 0.75) - 1;
    while (!(base + (2 * first + 1.5) * w >= lo)) first++;
    int last = first;
    while (base + (2 * last + 1.5) * w < hi) last++;
    block_low[d] = first;
    block_count[d] = last - first;
    grid_low[d] = 2 * first;
    grid_count[d] = block_count[d] > 0 ? 2 * block_count[d] + 1 : 0;
  }
}

void FixGenDPDE::sweep()
{
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  const double mvv2e = force->mvv2e;
  if (sweep_energy.size() < (size_t) nall) {
    sweep_energy.resize(nall);
    modified.resize(nall);
    touched.resize(nall);
  }
  const double need = ghost_need();
  for (int d = 0; d < 3; d++)
    if (comm->cutghost[d] < need)
      error->all(FLERR,
                 "fix gendpde: the ghost cutoff {} is below what the sweep needs, {}: comm_modify "
                 "cutoff {}",
                 comm->cutghost[d], need, need);

  // The order: built at the first sweep of a run (from the positions of its last build if the run
  // continues one and the rule does not fire: the next run command, or a restart file) or after
  // the rule fired (LAMMPS then built its lists at the previous step); kept otherwise, its local
  // indices found again by atom ID when LAMMPS built its lists for reasons of its own.
  if (setup_pending) {
    build_order(!rule_fires());
    setup_pending = build_pending = false;
  } else if (build_pending) {
    if (neighbor->lastcall != update->ntimestep - 1)
      error->all(FLERR,
                 "fix gendpde: LAMMPS did not build its neighbour lists at step {} as the "
                 "sweep's order asked",
                 update->ntimestep - 1);
    build_order(false);
    build_pending = false;
  } else if (neighbor->lastcall != indexed_at) {
    // the subdomains changed (fix balance): the same order made again from the build's positions
    // for the new ones; else the same pairs found again
    bool moved = false;
    for (int d = 0; d < 3; d++)
      moved |= domain->sublo[d] != build_sublo[d] || domain->subhi[d] != build_subhi[d];
    int any = 0, local = moved ? 1 : 0;
    MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, world);
    if (any)
      build_order(true);
    else
      remap_order();
  }

  // Each owner's velocity and energy eps/mvv2e (the pair updates' units: kinetic energies m v^2/2),
  // to every ghost.
  const bool isoenergetic = (mode == ISOENERGETIC);
  for (int i = 0; i < nlocal; i++) sweep_energy[i] = isoenergetic ? energy[i] / mvv2e : 0.0;
  comm_phase = START;
  comm->forward_comm_fix(this, 4);
  std::fill(touched.begin(), touched.begin() + nall, 0);
  // Colour by colour: this rank's blocks of the colour, then the ghosts' new values to their owners
  // and back out.
  for (int colour = 0; colour < SweepDefinition::numColours; colour++) {
    std::fill(modified.begin(), modified.begin() + nall, 0);
    for (int rank = colour_start[colour]; rank < colour_start[colour + 1]; rank++)
      sweep_pairs(sweep_list.data() + block_rank_start[rank],
                  block_rank_start[rank + 1] - block_rank_start[rank], isoenergetic);
    comm_phase = COLOUR;
    comm->reverse_comm_fix(this, 5);
    comm->forward_comm_fix(this, 5);
  }
  if (isoenergetic)
    for (int i = 0; i < nlocal; i++)
      if (touched[i]) energy[i] = sweep_energy[i] * mvv2e;
}

void FixGenDPDE::build_order(bool from_stored)
{
  // The order from the positions of its build: the current ones (LAMMPS has just built its lists),
  // or (from_stored) those each atom keeps from the last build, which every ghost takes from its
  // owner shifted as LAMMPS shifts positions, so that the order is the one that build made.
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double **x = atom->x;
  const imageint *image = atom->image;
  if (sweep_x.size() < 3 * (size_t) nall) {
    sweep_x.resize(3 * (size_t) nall);
    extended_cell.resize(3 * (size_t) nall);
  }
  if (from_stored) {
    const double *prd = domain->prd;
    for (int i = 0; i < nlocal; i++) {
      const int now[3] = {(int) (image[i] & IMGMASK) - IMGMAX,
                          (int) (image[i] >> IMGBITS & IMGMASK) - IMGMAX,
                          (int) (image[i] >> IMG2BITS) - IMGMAX};
      for (int d = 0; d < 3; d++) {
        const int shift = build_image[i][d] - now[d];
        // (an atom outside the fix's group may have none: it takes no part)
        if (!std::isfinite(build_x[i][d]))
          sweep_x[3 * i + d] = x[i][d];
        else
          sweep_x[3 * i + d] = shift == 0 ? build_x[i][d] : build_x[i][d] + shift * prd[d];
      }
    }
    comm_phase = POSITIONS;
    comm->forward_comm_fix(this, 3);
  } else {
    for (int i = 0; i < nall; i++)
      for (int d = 0; d < 3; d++) sweep_x[3 * i + d] = x[i][d];
    for (int i = 0; i < nlocal; i++) {
      const int now[3] = {(int) (image[i] & IMGMASK) - IMGMAX,
                          (int) (image[i] >> IMGBITS & IMGMASK) - IMGMAX,
                          (int) (image[i] >> IMG2BITS) - IMGMAX};
      for (int d = 0; d < 3; d++) {
        build_x[i][d] = x[i][d];
        build_image[i][d] = now[d];
      }
    }
    for (int d = 0; d < 3; d++) {
      build_boxlo[d] = domain->boxlo[d];
      build_boxhi[d] = domain->boxhi[d];
    }
  }
  has_build = 1;
  for (int d = 0; d < 3; d++) {
    build_sublo[d] = domain->sublo[d];
    build_subhi[d] = domain->subhi[d];
  }
  check_atom_ids();
  prepare_cells();
  rank_blocks();
  // Each owner's cell from its wrapped position (as OpenMM computes it), to every ghost; then each
  // particle's cell in this rank's frame: its owner's cell plus the multiple of n that puts it where
  // it is.
  for (int i = 0; i < nlocal; i++)
    for (int d = 0; d < 3; d++)
      extended_cell[3 * i + d] = SweepDefinition::periodicCell(
          (sweep_x[3 * i + d] - domain->boxlo[d]) / domain->prd[d], num_cells[d]);
  comm_phase = CELLS;
  comm->forward_comm_fix(this, 3);
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) {
      const int owner = extended_cell[3 * i + d];
      const double approximate =
          std::floor((sweep_x[3 * i + d] - domain->boxlo[d]) / cell_width[d]);
      const double images = std::nearbyint((approximate - owner) / num_cells[d]);
      extended_cell[3 * i + d] = owner + num_cells[d] * (int) images;
    }
  find_candidates();
  order_blocks();
  indexed_at = neighbor->lastcall;
}

void FixGenDPDE::remap_order()
{
  // LAMMPS built its lists at a step the rule did not choose (neigh_modify settings of its own, a
  // restart file written): the order stays, its particles are found again by atom ID, each at its
  // image nearest its block's centre (each is within 1.5 cells + 0.05 R of it, inside the ghost
  // cutoff; its other images are at least 2.5 cells farther).
  const int nall = atom->nlocal + atom->nghost;
  const tagint *tag = atom->tag;
  double **x = atom->x;
  std::vector<int> &by_tag = bin_next;    // (scratch) local indices sorted by atom ID
  by_tag.resize(nall);
  for (int i = 0; i < nall; i++) by_tag[i] = i;
  std::sort(by_tag.begin(), by_tag.end(), [&](int a, int b) {
    return tag[a] < tag[b];
  });
  const int num_blocks = colour_start.back();
  auto nearest = [&](std::uint32_t index, const double *centre) {
    const tagint id = (tagint) index + 1;
    auto first = std::lower_bound(by_tag.begin(), by_tag.end(), id, [&](int a, tagint value) {
      return tag[a] < value;
    });
    int best = -1;
    double best2 = 0.0;
    for (auto it = first; it != by_tag.end() && tag[*it] == id; ++it) {
      double r2 = 0.0;
      for (int d = 0; d < 3; d++) r2 += (x[*it][d] - centre[d]) * (x[*it][d] - centre[d]);
      if (best < 0 || r2 < best2) {
        best = *it;
        best2 = r2;
      }
    }
    if (best < 0)
      error->one(FLERR,
                 "fix gendpde: atom {} of the sweep's order is not on this rank or its ghosts at "
                 "step {}",
                 id, update->ntimestep);
    return best;
  };
  for (int r = 0; r < num_blocks; r++)
    for (int k = block_rank_start[r]; k < block_rank_start[r + 1]; k++) {
      SweepPair &pair = sweep_list[k];
      pair.li = nearest(pair.i, &block_centre[3 * r]);
      pair.lj = nearest(pair.j, &block_centre[3 * r]);
    }
  indexed_at = neighbor->lastcall;
}

void FixGenDPDE::check_atom_ids()
{
  // A pair's random numbers are keyed on its particles' indices, atom ID - 1, as 32-bit numbers (as
  // OpenMM's particle indices): a larger ID (possible with -DLAMMPS_BIGBIG) would share the streams
  // of another particle. Refused here, at each build of the order (atoms may have come).
  const std::int64_t max_id = std::int64_t(1) << 32;
  for (int i = 0; i < atom->nlocal; i++)
    if ((std::int64_t) atom->tag[i] > max_id)
      error->one(FLERR,
                 "fix gendpde: atom ID {} is not allowed: the sweep's random streams take atom IDs "
                 "1 ... 4294967296 (2^32, a 32-bit particle index ID - 1); renumber the atoms "
                 "(reset_atom_ids)",
                 atom->tag[i]);
}

void FixGenDPDE::find_candidates()
{
  // The candidates of this rank's blocks: the pairs closer than candidateRange(R) = 1.1 R at the
  // build's positions among the particles (local or ghost) in the cells those blocks cover, binned
  // in bins at least 1.1 R wide.
  //
  // Not a neighbour list requested from LAMMPS: a half list with ghosts (newton off, ghost = 1)
  // would give the same candidates but costs more. LAMMPS builds neighbours for every ghost out to
  // the ghost cutoff (1.5 sweep cells + skin on every side), while the sweep needs the pairs of the
  // particles in the cells of this rank's blocks only (about one cell more than the subdomain).
  const int nall = atom->nlocal + atom->nghost;
  const double *p = sweep_x.data();
  const tagint *tag = atom->tag;
  const int *mask = atom->mask;
  const double reach = SweepDefinition::candidateRange(pair_range), reach2 = reach * reach;
  double low[3], high[3];
  int bins[3];
  const double margin = 1e-9 * pair_range;
  for (int d = 0; d < 3; d++) {
    low[d] = domain->boxlo[d] + grid_low[d] * cell_width[d] - margin;
    high[d] = domain->boxlo[d] + (grid_low[d] + grid_count[d]) * cell_width[d] + margin;
    bins[d] = std::max(1, (int) ((high[d] - low[d]) / (reach + 2 * margin)));
  }
  bin_head.assign((size_t) bins[0] * bins[1] * bins[2], -1);
  bin_next.assign(nall, -1);
  auto bin_of = [&](int i, int *b) {
    for (int d = 0; d < 3; d++) {
      const int cell = extended_cell[3 * i + d] - grid_low[d];
      if (cell < 0 || cell >= grid_count[d]) return false;
      // (clamped: a position rounded just outside its cell stays in a bin next to its cell's)
      b[d] = std::max(
          0,
          std::min(bins[d] - 1,
                   (int) std::floor((p[3 * i + d] - low[d]) / (high[d] - low[d]) * bins[d])));
    }
    return true;
  };
  for (int i = nall - 1; i >= 0; i--) {
    int b[3];
    if (!(mask[i] & groupbit) || grid_count[0] == 0 || !bin_of(i, b)) continue;
    const size_t bin = ((size_t) b[2] * bins[1] + b[1]) * bins[0] + b[0];
    bin_next[i] = bin_head[bin];
    bin_head[bin] = i;
  }
  candidates.clear();
  for (int bz = 0; bz < bins[2]; bz++)
    for (int by = 0; by < bins[1]; by++)
      for (int bx = 0; bx < bins[0]; bx++) {
        const int home = (bz * bins[1] + by) * bins[0] + bx;
        for (int a = bin_head[home]; a >= 0; a = bin_next[a])
          for (int oz = -1; oz <= 1; oz++)
            for (int oy = -1; oy <= 1; oy++)
              for (int ox = -1; ox <= 1; ox++) {
                const int cx = bx + ox, cy = by + oy, cz = bz + oz;
                if (cx < 0 || cy < 0 || cz < 0 || cx >= bins[0] || cy >= bins[1] || cz >= bins[2])
                  continue;
                const int other = (cz * bins[1] + cy) * bins[0] + cx;
                if (other < home) continue;
                for (int b = (other == home ? bin_next[a] : bin_head[other]); b >= 0;
                     b = bin_next[b]) {
                  const double dx = p[3 * a] - p[3 * b], dy = p[3 * a + 1] - p[3 * b + 1],
                               dz = p[3 * a + 2] - p[3 * b + 2];
                  if (!(dx * dx + dy * dy + dz * dz < reach2)) continue;
                  const int group = block_rank_of(a, b);
                  if (group < 0) continue;
                  // (atom IDs 1 ... 2^32: check_atom_ids)
                  const auto ta = (std::uint32_t) (tag[a] - 1), tb = (std::uint32_t) (tag[b] - 1);
                  candidates.push_back(ta < tb ? SweepPair{ta, tb, a, b, group}
                                               : SweepPair{tb, ta, b, a, group});
                }
              }
      }
  // By block, then in (i, j) order.
  std::sort(candidates.begin(), candidates.end(), [](const SweepPair &p, const SweepPair &q) {
    return p.group < q.group || (p.group == q.group && pair_key(p) < pair_key(q));
  });
}

int FixGenDPDE::block_rank_of(int a, int b) const
{
  // The rank of the block of a pair's home cell (the lower of its two cells along each direction),
  // or -1 if that block is not this rank's.
  int block = 0;
  for (int d = 2; d >= 0; d--) {
    const int home = std::min(extended_cell[3 * a + d], extended_cell[3 * b + d]) - grid_low[d];
    const int bd = home >= 0 ? home >> 1 : -1;
    if (bd < 0 || bd >= block_count[d]) return -1;
    block = block * block_count[d] + bd;
  }
  return rank_of_block[block];
}

void FixGenDPDE::rank_blocks()
{
  // The ranks of this rank's blocks: colour by colour, by index within a colour (any order within a
  // colour gives the same result: its blocks share no particle); and their centres.
  const int num_blocks = block_count[0] * block_count[1] * block_count[2];
  rank_of_block.assign(num_blocks, 0);
  block_centre.assign(3 * (size_t) num_blocks, 0.0);
  colour_start.assign(SweepDefinition::numColours + 1, 0);
  int rank = 0;
  for (int colour = 0; colour < SweepDefinition::numColours; colour++) {
    colour_start[colour] = rank;
    for (int b = 0; b < num_blocks; b++) {
      const int index[3] = {block_low[0] + b % block_count[0],
                            block_low[1] + (b / block_count[0]) % block_count[1],
                            block_low[2] + b / (block_count[0] * block_count[1])};
      if (SweepDefinition::blockColour(index[0], index[1], index[2]) != colour) continue;
      for (int d = 0; d < 3; d++)
        block_centre[3 * rank + d] = domain->boxlo[d] + (2 * index[d] + 1.5) * cell_width[d];
      rank_of_block[b] = rank++;
    }
  }
  colour_start[SweepDefinition::numColours] = rank;
}

void FixGenDPDE::order_blocks()
{
  // The order within each block (SweepDefinition::orderBlock): its candidates in (i, j) order,
  // each at the lowest level none of its particles' earlier pairs has; the sequence level 0, level
  // 1, ..., each level in (i, j) order.
  const int num_blocks = colour_start.back();
  const int count = candidates.size(), nall = atom->nlocal + atom->nghost;
  block_rank_start.assign(num_blocks + 1, 0);
  for (const SweepPair &p : candidates) block_rank_start[p.group + 1]++;
  for (int r = 0; r < num_blocks; r++) block_rank_start[r + 1] += block_rank_start[r];
  sweep_list.resize(count);
  slot_of.assign(nall, -1);
  for (int r = 0; r < num_blocks; r++) {
    const int start = block_rank_start[r], size = block_rank_start[r + 1] - start;
    const SweepPair *pairs = candidates.data() + start;
    place.resize(size);
    SweepDefinition::orderBlock(
        size,
        [&](int k, int end) {
          return end == 0 ? pairs[k].li : pairs[k].lj;
        },
        slot_of.data(), block_scratch, place.data());
    for (int k = 0; k < size; k++) sweep_list[start + place[k]] = pairs[k];
  }
}

void FixGenDPDE::sweep_pairs(const SweepPair *pairs, int count, bool isoenergetic)
{
  // The pair updates (docs/theory.md sections 5-7): the core's pair step, as on every OpenMM
  // platform, with the run's terms (any pair of types with friction, with conduction), as
  // GenDPDEIntegrator decides them, for each candidate closer than R at this step's positions.
  double **x = atom->x, **v = atom->v;
  const tagint *tag = atom->tag;
  const double *rmass = atom->rmass;
  const int *type = atom->type;
  const int ntypes = atom->ntypes;
  const double range = pair_range, range2 = range * range, mvv2e = force->mvv2e,
               boltzmann = force->boltz / mvv2e;
  const double dt = update->dt, sqrt_dt = std::sqrt(dt);
  const std::uint64_t step = (std::uint64_t) (update->ntimestep - 1);
  const double *inverse_mass_of_type = pair_tables.inverse_mass.data(),
               *capacity = pair_tables.heat_capacity.data();
  const double *kappa_of = pair_tables.conduction.data(), *noise_of = pair_tables.noise.data();
  double *energy = sweep_energy.data();
  for (int k = 0; k < count; k++) {
    if (k + 8 < count) {
      // the particles of a pair a few updates ahead, which are anywhere in memory
      const SweepPair &ahead = pairs[k + 8];
      GENDPDE_PREFETCH(x[ahead.li]);
      GENDPDE_PREFETCH(x[ahead.lj]);
      GENDPDE_PREFETCH(v[ahead.li]);
      GENDPDE_PREFETCH(v[ahead.lj]);
      GENDPDE_PREFETCH(&energy[ahead.li]);
      GENDPDE_PREFETCH(&energy[ahead.lj]);
    }
    const SweepPair &pair = pairs[k];
    const int i = pair.li, j = pair.lj;
    const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
    const double r2 = dx * dx + dy * dy + dz * dz;
    if (!(r2 < range2)) continue;
    const double r = std::sqrt(r2);
    const double inverse_mass_i = rmass ? 1.0 / rmass[i] : inverse_mass_of_type[type[i]];
    const double inverse_mass_j = rmass ? 1.0 / rmass[j] : inverse_mass_of_type[type[j]];
    const int ab = type[i] * (ntypes + 1) + type[j];
    CounterRandom::PairStream random((std::uint32_t) seed, step, pair.i, pair.j);
    const int failed =
        gendpdeSweepPair(terms.dissipation, terms.conduction, isoenergetic ? 1 : 0, dx, dy, dz, r,
                         range, inverse_mass_i, inverse_mass_j, v[i], v[j],
                         isoenergetic ? &energy[i] : nullptr, isoenergetic ? &energy[j] : nullptr,
                         capacity[type[i]], capacity[type[j]], friction_of_pair[ab], kappa_of[ab],
                         noise_of[ab], noise_of[ab], boltzmann, dt, sqrt_dt, &random);
    if (failed) {
      const int bad = energy[i] > 0.0 ? j : i;
      error->one(
          FLERR,
          "fix gendpde: atom {}'s internal energy became {} at step {} (it must stay > 0): reduce "
          "the timestep or raise the heat capacity",
          tag[bad], energy[bad] * mvv2e, update->ntimestep);
    }
    modified[i] = modified[j] = touched[i] = touched[j] = 1;
  }
}

/* ---------------------------------------------------------------------- */

// The exchanges of the sweep. At its start (START) every ghost gets its owner's velocity and energy.
// After each colour (COLOUR) only what the colour changed travels: a flag per particle, then its
// velocity and energy if it was updated (on its rank, or received), so the reverse exchange carries
// the ghosts a block updated to their owners and the forward one the owners' new values out to
// every ghost. At a build every ghost gets its owner's cell (CELLS) and, when the order is made
// again from the positions of its build, that position shifted as LAMMPS shifts the ghost's
// (POSITIONS).

int FixGenDPDE::pack_state(int i, double *buf) const
{
  int m = 0;
  if (comm_phase == CELLS) {
    for (int d = 0; d < 3; d++) buf[m++] = extended_cell[3 * i + d];
    return m;
  }
  if (comm_phase == COLOUR) {
    buf[m++] = modified[i];
    if (!modified[i]) return m;
  }
  const double *vi = atom->v[i];
  buf[m++] = vi[0];
  buf[m++] = vi[1];
  buf[m++] = vi[2];
  buf[m++] = sweep_energy[i];
  return m;
}

int FixGenDPDE::unpack_state(int i, const double *buf)
{
  // What pack_state wrote, set (not added) on particle i: after a colour one block at most updated
  // a particle, so it gets exactly the bits the updating rank computed; it is then marked changed,
  // to be sent on in a later swap.
  int m = 0;
  if (comm_phase == CELLS) {
    for (int d = 0; d < 3; d++) extended_cell[3 * i + d] = (int) buf[m++];
    return m;
  }
  if (comm_phase == POSITIONS) {
    for (int d = 0; d < 3; d++) sweep_x[3 * i + d] = buf[m++];
    return m;
  }
  if (comm_phase == COLOUR) {
    if (buf[m++] == 0.0) return m;
    modified[i] = touched[i] = 1;
  }
  double *vi = atom->v[i];
  vi[0] = buf[m++];
  vi[1] = buf[m++];
  vi[2] = buf[m++];
  sweep_energy[i] = buf[m++];
  return m;
}

int FixGenDPDE::pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  int m = 0;
  if (comm_phase == POSITIONS) {
    // as AtomVec::pack_comm shifts positions (an orthogonal box: init)
    double shift[3] = {0.0, 0.0, 0.0};
    if (pbc_flag)
      for (int d = 0; d < 3; d++) shift[d] = pbc[d] * domain->prd[d];
    for (int k = 0; k < n; k++)
      for (int d = 0; d < 3; d++) buf[m++] = sweep_x[3 * list[k] + d] + shift[d];
    return m;
  }
  for (int k = 0; k < n; k++) m += pack_state(list[k], buf + m);
  return m;
}

void FixGenDPDE::unpack_forward_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) m += unpack_state(i, buf + m);
}

int FixGenDPDE::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) m += pack_state(i, buf + m);
  return m;
}

void FixGenDPDE::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int k = 0; k < n; k++) m += unpack_state(list[k], buf + m);
}

/* ---------------------------------------------------------------------- */

double FixGenDPDE::compute_scalar()
{
  // The sum of the internal energies (energy units): etotal + this is the energy an isoenergetic
  // run conserves.
  double local = 0.0, total = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & groupbit) local += energy[i];
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, world);
  return total;
}

void FixGenDPDE::grow_arrays(int nmax)
{
  memory->grow(energy, nmax, "fix_gendpde:energy");
  memory->grow(entropy, nmax, "fix_gendpde:entropy");
  memory->grow(build_x, nmax, 3, "fix_gendpde:build_x");
  memory->grow(build_image, nmax, 3, "fix_gendpde:build_image");
  vector_atom = energy;
}

void FixGenDPDE::copy_arrays(int i, int j, int /*delflag*/)
{
  energy[j] = energy[i];
  entropy[j] = entropy[i];
  for (int d = 0; d < 3; d++) {
    build_x[j][d] = build_x[i][d];
    build_image[j][d] = build_image[i][d];
  }
}

void FixGenDPDE::set_arrays(int i)
{
  // an atom that came after the order's build (create_atoms, fix deposit, ...): no position at the
  // build, so the next rule check builds the order
  for (int d = 0; d < 3; d++) {
    build_x[i][d] = std::numeric_limits<double>::quiet_NaN();
    build_image[i][d] = 0;
  }
}

// Per atom: eps_i, sigma_i, the position at the order's build and the image flags then (as
// doubles: exact).
int FixGenDPDE::pack_exchange(int i, double *buf)
{
  int m = 0;
  buf[m++] = energy[i];
  buf[m++] = entropy[i];
  for (int d = 0; d < 3; d++) buf[m++] = build_x[i][d];
  for (int d = 0; d < 3; d++) buf[m++] = build_image[i][d];
  return m;
}

int FixGenDPDE::unpack_exchange(int nlocal, double *buf)
{
  int m = 0;
  energy[nlocal] = buf[m++];
  entropy[nlocal] = buf[m++];
  for (int d = 0; d < 3; d++) build_x[nlocal][d] = buf[m++];
  for (int d = 0; d < 3; d++) build_image[nlocal][d] = (int) buf[m++];
  return m;
}

int FixGenDPDE::pack_restart(int i, double *buf)
{
  buf[0] = 9;    // (the count first: other fixes' unpack_restart skip it so)
  return 1 + pack_exchange(i, buf + 1);
}

void FixGenDPDE::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  const int count = static_cast<int>(extra[nlocal][m]);
  if (count >= 9)
    unpack_exchange(nlocal, &extra[nlocal][m + 1]);
  else {
    // a restart file of an earlier version: eps_i and sigma_i only (the order is built anew)
    energy[nlocal] = extra[nlocal][m + 1];
    entropy[nlocal] = extra[nlocal][m + 2];
    set_arrays(nlocal);
  }
}

int FixGenDPDE::size_restart(int /*nlocal*/)
{
  return 9;
}

int FixGenDPDE::maxsize_restart()
{
  return 9;
}

void FixGenDPDE::write_restart(FILE *fp)
{
  // energies_set + 2 has_build, then (if has_build) the box of the order's build
  if (comm->me == 0) {
    double values[7] = {(double) (energies_set + 2 * has_build)};
    for (int d = 0; d < 3; d++) {
      values[1 + d] = build_boxlo[d];
      values[4 + d] = build_boxhi[d];
    }
    const int count = has_build ? 7 : 1;
    const int size = count * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(values, sizeof(double), count, fp);
  }
}

void FixGenDPDE::restart(char *buf)
{
  const double *values = (const double *) buf;
  const int flags = (int) values[0];
  energies_set = flags & 1;
  has_build = (flags >> 1) & 1;
  if (has_build)
    for (int d = 0; d < 3; d++) {
      build_boxlo[d] = values[1 + d];
      build_boxhi[d] = values[4 + d];
    }
}

/* ----------------------------------------------------------------------
   the thermal state, by name, for pair_style gendpde (which does not
   include this header): per atom (dim 1, local atoms) internal_energy eps_i
   and the entropy sigma_i at the density eps_i belongs to (NaN where not
   known), both read and updated by the pair style; per type (dim 1, index
   1 ... ntypes) heat_capacity C_V; bath_temperature (dim 0, double);
   isothermal (dim 0, int: 1 in the isothermal mode)
------------------------------------------------------------------------- */

void *FixGenDPDE::extract(const char *name, int &dim)
{
  dim = 1;
  if (strcmp(name, "internal_energy") == 0) return (void *) energy;
  if (strcmp(name, "entropy") == 0) return (void *) entropy;
  if (strcmp(name, "heat_capacity") == 0) return (void *) heat_capacity_of_type.data();
  dim = 0;
  if (strcmp(name, "bath_temperature") == 0) return (void *) &temperature;
  if (strcmp(name, "isothermal") == 0) return (void *) &isothermal;
  return nullptr;
}

double FixGenDPDE::memory_usage()
{
  return (double) atom->nmax * (5 * sizeof(double) + 3 * sizeof(int)) +
      sweep_energy.size() * (sizeof(double) + 2) +
      (sweep_x.size() + block_centre.size()) * sizeof(double) + extended_cell.size() * sizeof(int) +
      sweep_list.capacity() * sizeof(SweepPair) + candidates.capacity() * sizeof(SweepPair);
}
