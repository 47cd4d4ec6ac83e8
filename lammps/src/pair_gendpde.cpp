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
   openmm-gendpde's LAMMPS package: pair_style gendpde (pair_gendpde.h).
------------------------------------------------------------------------- */

#include "pair_gendpde.h"

#include "atom.h"
#include "citeme.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "gendpde_core.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;
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

static const char cite_gendpde_vb[] =
    "GenDPDE density estimator V-B: doi:10.1021/acs.jctc.5c01646\n\n"
    "@Article{Colella25,\n"
    " author = {G. Colella and J. P. Larentzos and F. Bresme and J. Bonet Avalos},\n"
    " title = {Density- and Temperature-Dependent Potentials: Redefinition of the Local Density "
    "to\n"
    "          Improve the Simulation of Liquids within Generalized Dissipative Particle "
    "Dynamics},\n"
    " journal = {J.~Chem.\\ Theory Comput.},\n"
    " year = 2025,\n"
    " doi = {10.1021/acs.jctc.5c01646}\n"
    "}\n\n";

static_assert(EquationsOfState::coreStride() <= 12 && EquationsOfState::maxParameters + 4 <= 12,
              "PairGenDPDE::Law holds at most 12 parameters");

PairGenDPDE::PairGenDPDE(LAMMPS *lmp) : Pair(lmp)
{
  if (lmp->citeme) lmp->citeme->add(cite_gendpde);
  single_enable = 0;
  restartinfo = 0;
  one_coeff = 0;
  manybody_flag = 1;
  comm_forward = 4;
  comm_reverse = 4;
}

PairGenDPDE::~PairGenDPDE()
{
  memory->destroy(density);
  memory->destroy(moment);
  memory->destroy(coefficient);
  memory->destroy(moment_force);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
}

bool PairGenDPDE::moments() const
{
  return gendpdeEstimatorNeedsMoments(estimator) != 0;
}

bool PairGenDPDE::depends_on_temperature() const
{
  for (size_t t = 1; t < laws.size(); t++)
    if (laws[t].law >= 0 && gendpdeLawDependsOnTemperature(laws[t].law)) return true;
  return false;
}

void PairGenDPDE::settings(int narg, char **arg)
{
  if (!(narg == 3 || (narg == 5 && strcmp(arg[3], "background") == 0)))
    error->all(FLERR,
               "Illegal pair_style gendpde command: expected pair_style gendpde R va|vb|vc f_cut "
               "[background p_b]");
  cut_global = utils::numeric(FLERR, arg[0], false, lmp);
  if (!(cut_global > 0.0))
    error->all(FLERR, "pair_style gendpde: pair range R = {} is not allowed: it must be > 0",
               arg[0]);
  // the estimators of GenDPDEForce (the table of GenDPDEDensityEstimators.h), in lower case
  const std::string name = arg[1];
  const DensityEstimators::Estimator *found = DensityEstimators::findByName(name);
  if (found == nullptr)
    error->all(FLERR, "pair_style gendpde: density estimator '{}' is not allowed: it must be {}",
               name, DensityEstimators::listOfEstimators(true));
  estimator = found->coreId;
  // the partition of unity (V-B, and V-C: V-B with a surface correction) is Colella et al.'s
  if (lmp->citeme && estimator != GENDPDE_ESTIMATOR_VA) lmp->citeme->add(cite_gendpde_vb);
  // f_cut is dimensionless: GenDPDEForce's range (ParameterRanges.h) holds in any units
  fcut = utils::numeric(FLERR, arg[2], false, lmp);
  const EquationsOfState::Parameter scaling{"f_cut", "cutoff scaling f_cut",
                                            ParameterChecks::Ranges::cutoffScaling};
  std::string rule;
  if (!EquationsOfState::allowedInAnyUnits(scaling, fcut, rule))
    error->all(FLERR, "pair_style gendpde: {} = {} is not allowed: it must be {} (GenDPDEForce's)",
               scaling.description, arg[2], rule);
  background = narg == 5 ? utils::numeric(FLERR, arg[4], false, lmp) : 0.0;
  if (!(background >= 0.0 && std::isfinite(background)))
    error->all(FLERR,
               "pair_style gendpde: background pressure p_b = {} is not allowed: it must be >= 0 "
               "and finite",
               arg[4]);
  for (Law &law : laws) pack(law);
  gendpdeEstimatorConstants(cut_global, cut_global / fcut, &k_per_density, &volume_scale,
                            &derivative_scale, &moment_scale, &density_softening);
  gendpdeDensityWeightScales(cut_global, &weight_scale, &weight_derivative_scale);
}

void PairGenDPDE::coeff(int narg, char **arg)
{
  if (!allocated) {
    allocated = 1;
    const int n = atom->ntypes;
    memory->create(setflag, n + 1, n + 1, "pair:setflag");
    memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
    for (int i = 1; i <= n; i++)
      for (int j = i; j <= n; j++) setflag[i][j] = 0;
    laws.assign(n + 1, Law());
  }
  if (narg < 3)
    error->all(FLERR, "Incorrect args for pair coefficients: pair_coeff I I law parameters ...");
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);

  // The law and its parameters as GenDPDEForce takes them (the table of GenDPDEEquationsOfState.h:
  // a law that extends Tait takes n0, pi0, B_T, gamma_T first), laid out as the physics core reads
  // them. The table's ranges are in OpenMM's units; only their signs hold in any LAMMPS units, and
  // those are checked.
  const std::string name = arg[2];
  const EquationsOfState::Law *found = nullptr;
  for (const EquationsOfState::Law &candidate : EquationsOfState::laws)
    if (name == candidate.name) found = &candidate;
  if (found == nullptr)
    error->all(FLERR,
               "pair_coeff gendpde: law '{}' is not allowed: it must be one of GenDPDEForce's, {}",
               name, EquationsOfState::listOfLaws());
  const int num_given = EquationsOfState::numGivenParameters(*found);
  if (narg != 3 + num_given) {
    std::string names;
    for (int k = 0; k < num_given; k++)
      names += (k > 0 ? ", " : "") + std::string(EquationsOfState::givenParameter(*found, k).name);
    error->all(FLERR, "pair_coeff gendpde: law {} takes {} parameters ({}); got {}", name,
               num_given, names, narg - 3);
  }
  // Each parameter by the rule of its range that holds in any units (GenDPDEForce's ranges are in
  // OpenMM's).
  Law law;
  law.law = found->coreId;
  for (int k = 0; k < num_given; k++) {
    const EquationsOfState::Parameter &parameter = EquationsOfState::givenParameter(*found, k);
    const double value = utils::numeric(FLERR, arg[3 + k], false, lmp);
    std::string rule;
    if (!EquationsOfState::allowedInAnyUnits(parameter, value, rule))
      error->all(FLERR, "pair_coeff gendpde: {} {} = {} is not allowed: it must be {}", name,
                 parameter.description, value, rule);
    law.given[k] = value;
  }
  pack(law);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    if (i >= jlo && i <= jhi) {
      laws[i] = law;
      setflag[i][i] = 1;
      count++;
    }
  if (count == 0)
    error->all(FLERR,
               "pair_coeff gendpde: coefficients are per type (pair_coeff I I or * *); {} {} names "
               "no type",
               arg[0], arg[1]);
}

static_assert(EquationsOfState::maxParameters + 4 <= 12 && EquationsOfState::coreStride() <= 12,
              "PairGenDPDE::Law holds 12 given and 12 core parameters");

void PairGenDPDE::pack(Law &law) const
{
  // The core's parameters with the background pressure, packed as GenDPDEForce packs them
  // (packCoreParameters).
  if (law.law >= 0)
    law.integer_power = EquationsOfState::packCoreParameters(EquationsOfState::laws[law.law],
                                                             law.given, background, law.parameter);
}

void PairGenDPDE::init_style()
{
  if (force->newton_pair == 0) error->all(FLERR, "pair_style gendpde requires newton pair on");
  if (atom->tag_enable == 0) error->all(FLERR, "pair_style gendpde requires atom IDs");
  // Bonded pairs count in the density like any other pair, as in OpenMM's GenDPDEForce (which has no
  // exclusions) and in fix gendpde's sweep, which finds its pairs itself: a special_bonds weight other
  // than 1 would make LAMMPS leave them out of the neighbour list (weight 0) or mark them.
  if (atom->molecular != Atom::ATOMIC)
    for (int k = 1; k <= 3; k++)
      if (force->special_lj[k] != 1.0)
        error->all(
            FLERR,
            "pair_style gendpde: special_bonds lj {} {} {} is not allowed: bonded pairs count "
            "in the density like any other pair (as in OpenMM's GenDPDEForce and in fix "
            "gendpde's sweep); use special_bonds lj/coul 1.0 1.0 1.0",
            force->special_lj[1], force->special_lj[2], force->special_lj[3]);
  temperature_dependent = depends_on_temperature() ? 1 : 0;
  if (temperature_dependent && thermal_fix() == nullptr)
    error->all(FLERR,
               "pair_style gendpde: a law that depends on temperature needs fix gendpde (the "
               "thermal state)");
  neighbor->request(this, instance_me);
}

double PairGenDPDE::init_one(int i, int j)
{
  if (setflag[i][i] == 0 || setflag[j][j] == 0)
    error->all(FLERR, "pair_style gendpde: type {} has no law (pair_coeff {} {} ...)",
               setflag[i][i] ? j : i, setflag[i][i] ? j : i, setflag[i][i] ? j : i);
  return cut_global;
}

Fix *PairGenDPDE::thermal_fix()
{
  const int index = modify->find_fix_by_style("^gendpde$");
  return index < 0 ? nullptr : modify->fix[index];
}

/* ----------------------------------------------------------------------
   the thermal state fix gendpde keeps, read by name through Fix::extract
   (fix_gendpde.h lists the names): neither style includes the other
------------------------------------------------------------------------- */

void PairGenDPDE::read_thermal_state(Fix *fix, ThermalState &state)
{
  int dim_energy = -1, dim_entropy = -1, dim_capacity = -1, dim_temperature = -1,
      dim_isothermal = -1;
  state.energy = (double *) fix->extract("internal_energy", dim_energy);
  state.entropy = (double *) fix->extract("entropy", dim_entropy);
  state.heat_capacity = (double *) fix->extract("heat_capacity", dim_capacity);
  const double *temperature = (double *) fix->extract("bath_temperature", dim_temperature);
  const int *isothermal = (int *) fix->extract("isothermal", dim_isothermal);
  if (!state.energy || !state.entropy || !state.heat_capacity || !temperature || !isothermal ||
      dim_energy != 1 || dim_entropy != 1 || dim_capacity != 1 || dim_temperature != 0 ||
      dim_isothermal != 0)
    error->all(FLERR, "pair_style gendpde: fix {} (style {}) does not provide the thermal state",
               fix->id, fix->style);
  state.temperature = *temperature;
  state.isothermal = *isothermal;
}

void PairGenDPDE::grow()
{
  if (atom->nmax <= nmax) return;
  nmax = atom->nmax;
  memory->destroy(density);
  memory->destroy(coefficient);
  memory->create(density, nmax, "pair:gendpde:density");
  memory->create(coefficient, nmax, "pair:gendpde:coefficient");
  if (moments()) {
    memory->destroy(moment);
    memory->destroy(moment_force);
    memory->create(moment, nmax, 3, "pair:gendpde:moment");
    memory->create(moment_force, nmax, 3, "pair:gendpde:moment_force");
  }
}

void PairGenDPDE::particle_error(int status, int i, double volume)
{
  const tagint tag = atom->tag[i];
  const bigint step = update->ntimestep;
  if (status == GENDPDE_PARTICLE_NO_NEIGHBOR)
    error->one(FLERR,
               "pair gendpde: atom {} has no neighbour within R = {} at step {}: V-A's volume 1/n0 "
               "is undefined",
               tag, cut_global, step);
  if (status == GENDPDE_PARTICLE_OUTSIDE_DOMAIN)
    error->one(
        FLERR,
        "pair gendpde: atom {} has density {} outside its law's domain (0 < n < 1/b) at step {}",
        tag, 1.0 / volume, step);
  if (status == GENDPDE_PARTICLE_TEMPERATURE_JUMP)
    error->one(FLERR,
               "pair gendpde: atom {} changed its temperature by more than a factor {} in one step "
               "at step {} "
               "(density {}): the run is no longer integrated; reduce the timestep",
               tag, GENDPDE_STEP_TEMPERATURE_FACTOR, step, 1.0 / volume);
  error->one(FLERR,
             "pair gendpde: atom {}'s equation of state is not finite at density {} at step {}",
             tag, 1.0 / volume, step);
}

void PairGenDPDE::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  grow();
  double **x = atom->x, **f = atom->f;
  const int *type = atom->type;
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  const int inum = list->inum;
  const int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  const double cut = cut_global, cut2 = cut * cut, inv_cut = 1.0 / cut;
  const bool vc = moments();

  // Pass 1 (docs/theory.md sections 2-3): n0_i = sum_j w(r_ij) and V-C's g_i = sum_j (phi/r) d_ij
  // over the pairs; the pairs closer than R kept with their geometry for pass 2 (the list's others,
  // up to R + skin, are not).
  close_pairs.clear();    // (keeps its capacity: no step allocates once the list has grown)
  for (int i = 0; i < nall; i++) {
    density[i] = 0.0;
    if (vc) moment[i][0] = moment[i][1] = moment[i][2] = 0.0;
  }
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int *jlist = firstneigh[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (!(r2 < cut2)) continue;
      const double r = std::sqrt(r2);
      if (r2 > 0.0) close_pairs.push_back({i, j, dx, dy, dz, r});
      if (r < cut) {
        const double w = gendpdeDensityWeight(r, inv_cut, weight_scale);
        density[i] += w;
        density[j] += w;
        if (vc && r > 0.0) {
          const double s = gendpdeMomentWeightOverDistance(r, inv_cut);
          moment[i][0] += dx * s;
          moment[i][1] += dy * s;
          moment[i][2] += dz * s;
          moment[j][0] -= dx * s;
          moment[j][1] -= dy * s;
          moment[j][2] -= dz * s;
        }
      }
    }
  }
  comm->reverse_comm_pair(this);

  // Each owner's state (sections 3-4, 11): its volume, pressure, term of U, force coefficient,
  // V-C's moment force.
  Fix *fix = temperature_dependent ? thermal_fix() : nullptr;
  ThermalState state = {nullptr, nullptr, nullptr, 0.0, 0};
  if (fix) read_thermal_state(fix, state);
  double *stored_energy = state.energy;
  double *stored_entropy = state.entropy;
  const bool isothermal = fix && state.isothermal;
  const bool keep = fix && !isothermal;
  const bool check_step = update->setupflag == 0;
  for (int i = 0; i < nlocal; i++) {
    const Law &law = laws[type[i]];
    const double G = vc
        ? moment[i][0] * moment[i][0] + moment[i][1] * moment[i][1] + moment[i][2] * moment[i][2]
        : 0.0;
    const bool thermal = fix && gendpdeLawDependsOnTemperature(law.law);
    const double stored = thermal ? stored_energy[i] : 0.0;
    const bool entropy_known = thermal && !std::isnan(stored_entropy[i]);
    double volume, pressure, energy, force_coefficient, moment_force_scale, thermal_energy,
        density_entropy;
    const int status = gendpdeParticleState(
        estimator, density[i], G, k_per_density, volume_scale, derivative_scale, moment_scale,
        density_softening, volumePolynomials(), VolumeVBQuadrature::nodeSquared,
        VolumeVBQuadrature::mirrorNodeSquared, VolumeVBQuadrature::coefficient, law.law,
        law.parameter, law.integer_power, isothermal ? 1 : 0, fix ? state.temperature : 0.0, stored,
        entropy_known ? stored_entropy[i] : 0.0, entropy_known ? 1 : 0,
        (check_step && entropy_known) ? 1 : 0, thermal ? state.heat_capacity[type[i]] : 1.0,
        &volume, &pressure, &energy, &force_coefficient, &moment_force_scale, &thermal_energy,
        &density_entropy);
    if (status != GENDPDE_PARTICLE_VALID) particle_error(status, i, volume);
    coefficient[i] = force_coefficient;
    if (vc)
      for (int k = 0; k < 3; k++) moment_force[i][k] = moment_force_scale * moment[i][k];
    if (thermal) {
      // The integrator keeps the thermal state each evaluation finds (Isoenergetic, Conservative);
      // the Isothermal mode does not update eps_i, so the densities it belongs to are forgotten
      // (GenDPDEIntegratorUtilities).
      if (keep) {
        stored_energy[i] = thermal_energy;
        stored_entropy[i] = density_entropy;
      } else
        stored_entropy[i] = std::numeric_limits<double>::quiet_NaN();
    }
    if (eflag_global) eng_vdwl += energy;
    if (eflag_atom) eatom[i] += energy;
  }
  comm->forward_comm_pair(this);

  // Pass 2 (section 4): the pair forces, central (c_i + c_j) w'(r)/r d plus V-C's moment term.
  const double zero[3] = {0.0, 0.0, 0.0};
  for (const ClosePair &pair : close_pairs) {
    const int i = pair.i, j = pair.j;
    const double dx = pair.dx, dy = pair.dy, dz = pair.dz, r = pair.r;
    const bool inside = r < cut;
    const double *qi = vc ? moment_force[i] : zero, *qj = vc ? moment_force[j] : zero;
    double force[3];
    gendpdePairForce(
        dx, dy, dz, r, coefficient[i] + coefficient[j],
        inside ? gendpdeDensityWeightDerivative(r, inv_cut, weight_derivative_scale) : 0.0, inv_cut,
        (vc && inside) ? 1 : 0, qi[0], qi[1], qi[2], qj[0], qj[1], qj[2], force);
    f[i][0] += force[0];
    f[i][1] += force[1];
    f[i][2] += force[2];
    f[j][0] -= force[0];
    f[j][1] -= force[1];
    f[j][2] -= force[2];
    if (evflag) ev_tally_xyz(i, j, nlocal, 1, 0.0, 0.0, force[0], force[1], force[2], dx, dy, dz);
  }
  const bool virial = vflag_global || vflag_fdotr;
  if (vflag_fdotr) virial_fdotr_compute();    // (which clears vflag_fdotr)
  if (background != 0.0) {
    // docs/theory.md section 12: U gains p_b V_box and the virial's trace -3 p_b V_box (the core's
    // box term), shared equally by the particles (as GenDPDEForce shares them)
    const double volume = domain->xprd * domain->yprd * domain->zprd,
                 natoms = (double) atom->natoms;
    const double share = gendpdeBackgroundEnergy(background, volume) / natoms;
    const double virial_share = gendpdeBackgroundVirial(background, volume) / (3.0 * natoms);
    if (eflag_global) eng_vdwl += share * nlocal;
    if (virial)
      for (int k = 0; k < 3; k++) this->virial[k] += virial_share * nlocal;
    for (int i = 0; i < nlocal; i++) {
      if (eflag_atom) eatom[i] += share;
      if (vflag_atom)
        for (int k = 0; k < 3; k++) vatom[i][k] += virial_share;
    }
  }
}

int PairGenDPDE::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    buf[m++] = density[i];
    if (moments())
      for (int k = 0; k < 3; k++) buf[m++] = moment[i][k];
  }
  return m;
}

void PairGenDPDE::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    density[j] += buf[m++];
    if (moments())
      for (int k = 0; k < 3; k++) moment[j][k] += buf[m++];
  }
}

int PairGenDPDE::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  int m = 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    buf[m++] = coefficient[j];
    if (moments())
      for (int k = 0; k < 3; k++) buf[m++] = moment_force[j][k];
  }
  return m;
}

void PairGenDPDE::unpack_forward_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    coefficient[i] = buf[m++];
    if (moments())
      for (int k = 0; k < 3; k++) moment_force[i][k] = buf[m++];
  }
}

double PairGenDPDE::memory_usage()
{
  return (double) nmax * sizeof(double) * (moments() ? 8 : 2) +
      close_pairs.capacity() * sizeof(ClosePair);
}

void *PairGenDPDE::extract(const char *name, int &dim)
{
  dim = 0;
  if (strcmp(name, "cut_global") == 0) return (void *) &cut_global;
  // whether some type's law depends on temperature (fix gendpde then keeps the thermal state)
  if (strcmp(name, "temperature_dependent") == 0) return (void *) &temperature_dependent;
  return nullptr;
}
