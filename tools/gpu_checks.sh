#!/usr/bin/env bash
# The CUDA platform's checks and benchmarks, for a machine with an NVIDIA GPU and a CUDA toolkit but no network
# (such as a lent H200), in two halves:
#
#   tools/gpu_checks.sh prepare        here, with network: the wheels the GPU machine lacks, into gpu-wheels/
#   tools/gpu_checks.sh run OUTDIR     there (gpu-wheels/ carried along): install OpenMM 8.6.1 with its CUDA platform
#                                      into a fresh venv, build and install this plugin with its C++ tests, run the
#                                      CUDA tests, a per-part profile of a step at N = 1e6 (GENDPDE_PROFILE), then
#                                      the benchmarks in mixed precision at N = 1e5 and 1e6; every output into
#                                      OUTDIR (build log, ctest log, profile, benchmark tables and JSON)
#
# The benchmarks are the package's own commands (docs/performance.md): benchmark-force (GenDPDEForce against the
# same potential as a CustomGBForce, V-A and V-B) and benchmark-integrator (every GenDPDEIntegrator mode, OpenMM's
# VerletIntegrator and DPDIntegrator), all on the same GPU and in one run, so that every ratio is side by side.
set -euo pipefail
cd "$(dirname "$0")/.."
openmm_version=$(sed -n 's/^openmm==\([0-9.]*\).*/\1/p' requirements.txt)
case "${1:-}" in
prepare)
    rm -rf gpu-wheels && mkdir gpu-wheels
    python=.venv/bin/python
    # Pure-Python or manylinux wheels for the GPU machine's python3 (the same 3.11 as here is assumed; check there).
    # (The package's commands import only numpy and tqdm at the top; the rest lazily.)
    $python -m pip download -q -d gpu-wheels "openmm==$openmm_version" \
        "$(grep '^swig==' requirements.txt)" "$(grep '^scikit-build-core==' requirements.txt)" \
        "$(grep '^numpy==' requirements.txt)" "$(grep '^tqdm==' requirements.txt)"
    $python -m pip download -q --no-deps -d gpu-wheels "openmm-cuda-13==$openmm_version"
    du -sh gpu-wheels
    ;;
run)
    out=${2:?"usage: tools/gpu_checks.sh run OUTDIR"}
    mkdir -p "$out"
    nvidia-smi > "$out/nvidia-smi.txt" 2>&1 || true
    venv=/tmp/gendpde-gpu-venv
    python3 -m venv --system-site-packages "$venv"
    "$venv/bin/python" -m pip install -q --no-index --find-links gpu-wheels "openmm==$openmm_version" swig \
        scikit-build-core numpy tqdm > "$out/pip.log" 2>&1
    "$venv/bin/python" -m pip install -q --no-index --no-deps gpu-wheels/openmm_cuda_13-*.whl >> "$out/pip.log" 2>&1
    # libOpenMMCUDA looks for the NVIDIA runtime wheels' libraries; the toolkit's serve instead.
    export LD_LIBRARY_PATH="/usr/local/cuda/lib64:${LD_LIBRARY_PATH:-}"
    "$venv/bin/python" -c "import openmm; print(openmm.Platform.getPluginLoadFailures()); \
print([openmm.Platform.getPlatform(i).getName() for i in range(openmm.Platform.getNumPlatforms())])" \
        > "$out/platforms.txt" 2>&1
    CMAKE_BUILD_PARALLEL_LEVEL=$(nproc) "$venv/bin/python" -m pip install --no-build-isolation --no-deps \
        -C build-dir=/tmp/gendpde-gpu-build -C cmake.define.GENDPDE_BUILD_TESTS=ON . > "$out/build.log" 2>&1
    ctest --test-dir /tmp/gendpde-gpu-build -R CUDA --output-on-failure > "$out/ctest-cuda.txt" 2>&1 || true
    # Where the device time goes (GENDPDE_PROFILE: each part synchronised and timed; the totals print at exit).
    "$venv/bin/python" tools/time_steps.py --state /tmp/gendpde-state-1000188.npz --particles 1000188 --platform CUDA \
        --precision mixed --what step --count 20 > "$out/profile-cuda-1000188.txt" 2>&1 || true
    GENDPDE_PROFILE=1 "$venv/bin/python" tools/time_steps.py --state /tmp/gendpde-state-1000188.npz --platform CUDA \
        --precision mixed --what step --count 20 >> "$out/profile-cuda-1000188.txt" 2>&1 || true
    for n in 108000 1000188; do
        "$venv/bin/python" -m openmmgendpde benchmark-force --platform CUDA --precision mixed --particles $n \
            --cutoffs 1.6839 --rounds 5 --json "$out/benchmark-force-cuda-$n.json" > "$out/benchmark-force-cuda-$n.txt" 2>&1 || true
        "$venv/bin/python" -m openmmgendpde benchmark-integrator --platform CUDA --precision mixed --particles $n \
            --rounds 5 --json "$out/benchmark-integrator-cuda-$n.json" > "$out/benchmark-integrator-cuda-$n.txt" 2>&1 || true
    done
    ;;
*)
    echo "usage: tools/gpu_checks.sh prepare | run OUTDIR" >&2
    exit 2
    ;;
esac
