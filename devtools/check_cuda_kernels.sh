#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# Compile the device kernels (platforms/common/src/kernels) as CUDA, as OpenMM's CUDA platform would at run time,
# on a machine without a GPU: OpenMM's CUDA prelude (common.cu and vectorOps.cu from an OpenMM source checkout of
# the supported version) + the defines and typedefs of each precision + the kernels, through nvcc --ptx for sm_90.
# Prints the number of kernels in each program; any compile error is printed and fails the script.
#   devtools/check_cuda_kernels.sh OPENMM_SOURCE_DIR
set -euo pipefail
openmm=${1:?"usage: devtools/check_cuda_kernels.sh OPENMM_SOURCE_DIR (a checkout of openmm/openmm)"}
root="$(cd "$(dirname "$0")/.." && pwd)"
kernels="$root/platforms/common/src/kernels"
core="$root/core/include/gendpde/GenDPDEPhysicsCore.h"
sweep_pair="$root/core/include/gendpde/GenDPDESweepPair.h"
nvcc=${NVCC:-/usr/local/cuda/bin/nvcc}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prelude="$openmm/platforms/cuda/src/kernels/common.cu $openmm/platforms/cuda/src/kernels/vectorOps.cu"
# The status words' layout as the integrator kernel defines it (CommonGenDPDEStatus.h, one source), and the stride
# of the laws' parameters as the force kernel defines it (the table of the laws).
cat > "$work/status.cpp" <<'SOURCE'
#include "CommonGenDPDEStatus.h"
#include "gendpde/GenDPDEEquationsOfState.h"
#include <cstdio>
int main() {
    for (const auto& define : GenDPDEPlugin::DeviceStatus::defines())
        std::printf("#define %s %s\n", define.first.c_str(), define.second.c_str());
    std::printf("#define LAW_PARAMETER_STRIDE %d\n", GenDPDEPlugin::EquationsOfState::coreStride());
}
SOURCE
g++ -std=c++17 -I"$root/platforms/common/src" -I"$root/core/include" -o "$work/status" "$work/status.cpp"
"$work/status" > "$work/status.h"
for precision in single mixed double; do
    case $precision in
        single) real=float; mixed=float; flag=""; words=4;;
        mixed) real=float; mixed=double; flag="#define USE_MIXED_PRECISION 1"; words=8;;
        double) real=double; mixed=double; flag="#define USE_DOUBLE_PRECISION 1"; words=8;;
    esac
    {
        echo "$flag"
        printf '#define %s %s\n' NUM_ATOMS 1000 PADDED_NUM_ATOMS 1024 SCAN_GROUP_SIZE 256 BOUNDS_GROUP_SIZE 128 \
            USE_PERIODIC 1 GENDPDE_DOUBLE_RANDOM 1 SWEEP_MAX_PARTICLES 192 SWEEP_BLOCKS_PER_GROUP 4 \
            SWEEP_BLOCK_THREADS 32 SWEEP_LEVEL_WORDS $words
        cat "$work/status.h"
        for n in 2 3 4; do
            echo "#define make_real$n make_$real$n"
            echo "#define make_mixed$n make_$mixed$n"
        done
        for n in "" 2 3 4; do
            echo "typedef $real$n real$n;"
            echo "typedef $mixed$n mixed$n;"
        done
        echo "typedef unsigned int tileflags;"
        cat $prelude
    } > "$work/prelude.cu"
    # As CommonGenDPDEKernelSources::physicsCore: the shared core in real (force) or mixed (integrator) precision,
    # with the V-B table sizes of core/include/gendpde/VolumeVBTables.h.
    core_in() {
        printf '#define GENDPDE_REAL %s\n#define GENDPDE_ENERGY mixed\n#define GENDPDE_CORE inline DEVICE\n#define GENDPDE_GLOBAL GLOBAL\n' "$1"
        printf '#define GENDPDE_ISFINITE(x) isfinite(x)\n#define GENDPDE_FREXP(x, e) frexp(x, e)\n'
        printf '#define GENDPDE_VB_FIRST_OCTAVE -4\n'
        printf '#define GENDPDE_VB_LAST_OCTAVE 3\n#define GENDPDE_VB_QUADRATURE_PAIRS 12\n'
        cat "$core"
    }
    { cat "$work/prelude.cu"; core_in real; cat "$kernels/gendpdeCells.cc" "$kernels/gendpdeForce.cc"; } > "$work/force.cu"
    { cat "$work/prelude.cu"; core_in mixed; cat "$kernels/gendpdeCells.cc" "$kernels/gendpdeRandom.cc" \
        "$kernels/gendpdeStatus.cc" "$kernels/gendpdeIntegrator.cc"; } > "$work/integrator.cu"
    { cat "$work/prelude.cu"; core_in mixed; cat "$kernels/gendpdeCells.cc" "$kernels/gendpdeRandom.cc" \
        "$kernels/gendpdeStatus.cc" "$sweep_pair" "$kernels/gendpdeSweep.cc"; } > "$work/sweep.cu"
    for program in force integrator sweep; do
        "$nvcc" --ptx -arch=sm_90 -o "$work/$program.ptx" "$work/$program.cu"
        echo "$precision $program: $(grep -c '\.entry' "$work/$program.ptx") kernels"
        # Registers, shared memory, stack and spills of each kernel (ptxas, as the driver would assemble them).
        "$(dirname "$nvcc")/ptxas" -arch=sm_90 -v -o "$work/$program.cubin" "$work/$program.ptx" 2>&1 | awk '
            /Compiling entry function/ { match($0, /\x27[A-Za-z]*\x27/); name = substr($0, RSTART + 1, RLENGTH - 2) }
            /Function properties for/ { entry = index($0, "for " name) > 0 }
            /bytes stack frame/ && entry { sub(/^ *ptxas info *: */, ""); frame = $0 }
            /Used [0-9]* registers/ && name != "" { sub(/^.*Used/, "Used"); printf "    %s: %s; %s\n", name, $0, frame; name = "" }'
    done
done
