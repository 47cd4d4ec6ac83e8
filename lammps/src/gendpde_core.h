/* -------------------------------------------------------------------------- *
 * openmm-gendpde's LAMMPS package: the project's one physics core            *
 * (core/include/gendpde/GenDPDEPhysicsCore.h) in double precision as   *
 * the OpenMM host platforms compile it (GenDPDEPhysicsCoreDouble.h), its     *
 * counter-based random streams, the table of the equations of state (their *
 * names and parameters) and the definition of the sweep's order.            *
 * Every formula the pair style and the fix evaluate is one of the core's     *
 * functions; nothing is written again.                                       *
 * -------------------------------------------------------------------------- */

#ifndef LMP_GENDPDE_CORE_H
#define LMP_GENDPDE_CORE_H

#include "gendpde/CounterRandom.h"
#include "gendpde/GenDPDEDensityEstimators.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include "gendpde/GenDPDEPhysicsCoreDouble.h"
#include "gendpde/GenDPDESweepDefinition.h"

#endif
