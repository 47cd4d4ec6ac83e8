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
   openmm-gendpde's LAMMPS package as a plugin (plugin load gendpdeplugin.so):
   registers pair_style gendpde and fix gendpde.
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "version.h"

#include "fix_gendpde.h"
#include "pair_gendpde.h"

using namespace LAMMPS_NS;

static Pair *pair_creator(LAMMPS *lmp)
{
  return new PairGenDPDE(lmp);
}

static Fix *fix_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new FixGenDPDE(lmp, argc, argv);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  lammpsplugin_regfunc register_plugin = (lammpsplugin_regfunc) regfunc;
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.style = "pair";
  plugin.name = "gendpde";
  plugin.info = "GenDPDE many-body force (V-A, V-B, V-C; Tait and temperature-dependent laws), "
                "openmm-gendpde";
  plugin.author = "openmm-gendpde";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &pair_creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "gendpde";
  plugin.info = "GenDPDE integrator: Shardlow sweep across subdomains, three modes, openmm-gendpde";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &fix_creator;
  (*register_plugin)(&plugin, lmp);
}
