/* -------------------------------------------------------------------------- *
 * openmm-gendpde's LAMMPS package: the project's one physics core            *
 * (openmmapi/include/internal/GenDPDEPhysicsCore.h) in double precision as   *
 * the OpenMM host platforms compile it (GenDPDEPhysicsCoreDouble.h), its     *
 * counter-based random streams, the table of the equations of state (their *
 * names and parameters) and the definition of the sweep's order.            *
 * Every formula the pair style and the fix evaluate is one of the core's     *
 * functions; nothing is written again.                                       *
 * -------------------------------------------------------------------------- */

#ifndef LMP_GENDPDE_CORE_H
#define LMP_GENDPDE_CORE_H

#include "internal/CounterRandom.h"
#include "internal/GenDPDEEquationsOfState.h"
#include "internal/GenDPDEPhysicsCoreDouble.h"
#include "internal/GenDPDESweepDefinition.h"

#endif
