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
   The project's one physics core (core/include/gendpde/GenDPDEPhysicsCore.h)
   in double precision as the OpenMM host platforms compile it
   (GenDPDEPhysicsCoreDouble.h), its counter-based random streams, the
   tables of the density estimators and of the equations of state (their
   names and parameters) and the definition of the sweep's order. Every
   formula the pair style and the fix evaluate is one of the core's
   functions; nothing is written again.
------------------------------------------------------------------------- */

#ifndef LMP_GENDPDE_CORE_H
#define LMP_GENDPDE_CORE_H

#include "gendpde/CounterRandom.h"
#include "gendpde/GenDPDEDensityEstimators.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "gendpde/GenDPDEPhysicsCoreDouble.h"
#include "gendpde/GenDPDESweepDefinition.h"

#endif
