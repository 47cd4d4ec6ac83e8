#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
# The CUDA platform's checks and benchmarks on a lent GPU machine without network: the H200 of the device tool,
# whose python3 (3.12, /opt/torch/.venv) holds numpy, scipy, tqdm, scikit-build-core, cmake, ninja and NVIDIA's
# CUDA 13 runtime wheels, with nvcc 13 and g++, but no OpenMM.
#
#   devtools/gpu_checks.sh prepare          here: cp312 wheels of only what that image lacks (openmm, openmm-cuda-13,
#                                        swig) into .gpu-wheels/ (git-ignored), checked against the 64 MiB carry
#   devtools/gpu_checks.sh run OUTDIR       there: the stages below, each under a time limit, the most important first,
#                                        the whole run under 8 minutes; OUTDIR/summary.txt (each stage's status, its
#                                        figures, and every failure's last lines) and OUTDIR/logs.tar.gz (every log):
#                                        two files, as the device tool brings back at most eight
#   devtools/gpu_checks.sh dry-run OUTDIR   here: the same run with cp311 wheels, a python that holds what the image
#                                        holds (made once in /tmp from PyPI), OpenCL (PoCL) in place of CUDA and
#                                        small systems: every step but the GPU itself
#
# The device call (device tool, after `prepare`):
#   run(command="bash devtools/gpu_checks.sh run $OUT", carry=[".gpu-wheels"], timeout_s=560)
#
# Stages (run): env (the GPU, the image's tools and libraries), install (the wheels, with --no-index, into a prefix
# on PYTHONPATH, so that the image's packages stay visible; libOpenMMCUDA finds cuFFT and NVRTC in the CUDA toolkit
# or the image's NVIDIA wheels), build (this plugin and its C++ tests against that OpenMM), then the figures of issue
# 52 first: throughput at N = 1,000,188 (liquid argon, V-B, R* = 1.6839, Isoenergetic steps, mixed precision, then
# the per-part profile, GENDPDE_PROFILE, summed up by devtools/profile_summary.py: launches, host transfers and order
# builds per step, the critical path in levels, the sweep's time per level), throughput at N = 108,000 (mixed, with
# its profile, then single and double), the device memory per particle (devtools/device_memory.py: nvidia-smi's
# count, two sizes), the package's benchmarks at N = 108,000 (benchmark-integrator: every mode against
# VerletIntegrator, the Isothermal step against DPDIntegrator; benchmark-force: against CustomGBForce), then the
# correctness checks: tests (ctest -R CUDA: the shared tests in each precision, the comparison with Reference, the
# sweep), python-tests (pytest's GPU tier of test_gpu_platforms.py and test_sweep_order.py for the platform, with
# the image's pytest) and, time permitting, the benchmarks at N = 1,000,188. Before the figures, launch-modes: the
# step's stages in shared launches against a launch per stage at N = 108,000 (devtools/sweep_launch_modes.py: the
# same trajectory bit for bit, and both times); if that fails or hangs, the later stages take a launch per stage. A stage that fails or runs out of time
# is reported as such and the run goes on with the stages that do not need it; stages the budget leaves no time for
# are reported SKIPPED (then a second run with --tests-first).
#
#   devtools/gpu_checks.sh dry-run OUTDIR --tiny   the dry run with 864 and 500 particles and short timings (a
#                                        check that every stage runs end to end, not a measurement)
#   devtools/gpu_checks.sh run OUTDIR --tests-first   the correctness checks before the figures (for a second run
#                                        when the budget cut them off the first)
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
openmm_version=$(sed -n 's/^openmm==\([0-9.]*\).*/\1/p' requirements.txt)
swig_version=$(sed -n 's/^swig==\([0-9.]*\).*/\1/p' requirements.txt)

download_wheels() {   # python version (3.12), folder
    local python_version=$1 folder=$2
    rm -rf "$folder" && mkdir -p "$folder"
    python3 -m pip download -q --disable-pip-version-check --no-deps --only-binary=:all: \
        --python-version "$python_version" --implementation cp --platform manylinux_2_34_x86_64 \
        --platform manylinux_2_28_x86_64 --platform manylinux_2_17_x86_64 --platform manylinux2014_x86_64 \
        --platform manylinux_2_12_x86_64 --platform manylinux2010_x86_64 -d "$folder" \
        "openmm==$openmm_version" "openmm-cuda-13==$openmm_version" "swig==$swig_version" || return 1
    local size
    size=$(du -sm "$folder" | cut -f1)
    ls -l "$folder"
    echo "$folder: $size MiB (the device tool carries 64 MiB with the working tree)"
    [ "$size" -lt 48 ] || { echo "too large to carry" >&2; return 1; }
}

case "${1:-}" in
prepare)
    grep -qx '.gpu-wheels/' .gitignore || { echo "add .gpu-wheels/ to .gitignore first" >&2; exit 1; }
    download_wheels 3.12 .gpu-wheels
    exit
    ;;
run|dry-run)
    mode=$1
    out=${2:?"usage: devtools/gpu_checks.sh $1 OUTDIR [--tiny | --tests-first]"}
    tiny=${3:-}
    ;;
*)
    echo "usage: devtools/gpu_checks.sh prepare | run OUTDIR [--tests-first] | dry-run OUTDIR [--tiny]" >&2
    exit 2
    ;;
esac

mkdir -p "$out"
out=$(cd "$out" && pwd)
logs=$(mktemp -d)
summary="$out/summary.txt"
start=$(date +%s)
budget=465     # seconds for the whole run: under 8 minutes, leaving the device tool time to bring the files back
: > "$summary"

note() {
    echo "$*" | tee -a "$summary"
}
# stage NAME LIMIT COMMAND...: run COMMAND (a shell function or program) under a time limit cut to the budget,
# its output in $logs/NAME.log; its status, time and, on failure, its last lines go into the summary.
stage() {
    local name=$1 limit=$2
    shift 2
    local left=$((budget - ($(date +%s) - start)))
    if [ "$left" -lt 20 ]; then
        note "== $name: SKIPPED (the run's time budget is spent)"
        return 1
    fi
    [ "$limit" -le "$left" ] || limit=$left
    local began=$(date +%s) status
    # (functions and the variables they read are exported: timeout runs them in a new bash)
    timeout --kill-after=10 "$limit" bash -c '"$@"' stage "$@" > "$logs/$name.log" 2>&1
    status=$?
    local took=$(($(date +%s) - began))
    if [ $status -eq 0 ]; then
        note "== $name: OK in ${took} s"
    elif [ $status -eq 124 ] || [ $status -eq 137 ]; then
        note "== $name: TIMED OUT after ${took} s (limit ${limit} s); last lines:"
        tail -n 25 "$logs/$name.log" | sed 's/^/    /' | tee -a "$summary"
    else
        note "== $name: FAILED (exit $status) after ${took} s; last lines:"
        tail -n 25 "$logs/$name.log" | sed 's/^/    /' | tee -a "$summary"
    fi
    return $status
}
finish() {
    note "== total: $(($(date +%s) - start)) s"
    tar -czf "$out/logs.tar.gz" -C "$logs" . 2>/dev/null
    rm -rf "$logs"
}
trap finish EXIT

# What runs where: the lent machine (its python3, CUDA) or, for the dry run, this one (a python like the image's,
# made once from PyPI; OpenCL on PoCL; small systems).
if [ "$mode" = run ]; then
    python=python3
    wheels=$root/.gpu-wheels
    platform=CUDA
    large=1000188
    small=108000
    ctest_filter=CUDA
else
    image=/tmp/gendpde-image-python
    if [ ! -x "$image/bin/python" ]; then
        python3 -m venv "$image" && "$image/bin/python" -m pip install -q --disable-pip-version-check numpy scipy pytest \
            tqdm scikit-build-core cmake ninja || exit 1
    fi
    python=$image/bin/python
    wheels=/tmp/gendpde-dry-wheels
    [ -e "$wheels/.done" ] || { download_wheels 3.11 "$wheels" > /dev/null && touch "$wheels/.done"; } || exit 1
    platform=OpenCL
    large=4000
    small=500
    ctest_filter=OpenCLGenDPDESweep
    export POCL_CACHE_DIR=/tmp/gendpde-dry-pocl
    if [ "$tiny" = --tiny ]; then
        large=864
        small=500
    fi
fi
# Steps timed per throughput measurement and rounds of the benchmarks (few in the tiny dry run: a check, not figures).
steps=50
profile_steps=20
rounds=3
if [ "$tiny" = --tiny ]; then
    steps=5
    profile_steps=5
    rounds=1
fi
prefix=/tmp/gendpde-gpu-prefix
build=/tmp/gendpde-gpu-build
rm -rf "$prefix" "$build"
site=$prefix/lib/python$("$python" -c 'import sys; print("%d.%d" % sys.version_info[:2])')/site-packages
export PYTHONPATH=$site${PYTHONPATH:+:$PYTHONPATH}
export PYTHONUNBUFFERED=1 PYTHONFAULTHANDLER=1   # (a crash prints the Python stack of every thread)
note "gpu_checks.sh $mode at $(git rev-parse --short HEAD 2>/dev/null || echo '?'), $(date -u '+%Y-%m-%d %H:%M UTC')"

environment() {
    nvidia-smi || true
    echo "python: $python ($("$python" --version 2>&1))"
    "$python" -c "import numpy, scipy, tqdm, scikit_build_core; print('numpy', numpy.__version__, 'scipy', \
scipy.__version__, 'scikit-build-core', scikit_build_core.__version__)"
    for tool in nvcc cmake ninja g++; do
        echo "$tool: $(command -v $tool || echo 'not found') $($tool --version 2>/dev/null | head -n 1)"
    done
    ldconfig -p | grep -E 'libcuda\.so|libnvrtc\.so|libcufft\.so' || true
}
# cuFFT 12 and NVRTC 13 for libOpenMMCUDA: the CUDA toolkit's (whose NVRTC matches nvcc and the driver) first,
# then NVIDIA's wheels in the image's python; named in LD_LIBRARY_PATH for every later stage.
cuda_libraries() {
    local dirs="" found dir
    for dir in /usr/local/cuda/lib64 /usr/local/cuda/targets/x86_64-linux/lib; do
        [ -e "$dir/libnvrtc.so.13" ] && dirs="$dirs:$dir"
        [ -e "$dir/libcufft.so.12" ] && dirs="$dirs:$dir"
    done
    for found in $("$python" -c 'import site; print(" ".join(site.getsitepackages()))' 2>/dev/null); do
        for dir in $(find "$found/nvidia" -name 'libnvrtc.so.13*' -o -name 'libcufft.so.12*' 2>/dev/null \
                     | xargs -r -n 1 dirname | sort -u); do
            dirs="$dirs:$dir"
        done
    done
    echo "${dirs#:}" | tr ':' '\n' | awk 'NF && !seen[$0]++' | paste -sd: -
}
install() {
    "$python" -m pip install --disable-pip-version-check --no-index --no-deps --no-compile --prefix "$prefix" \
        "$wheels"/*.whl || return 1
    "$python" - <<'PYTHON'
import openmm
print("OpenMM", openmm.__version__, "from", openmm.__file__)
print("platforms:", [openmm.Platform.getPlatform(i).getName() for i in range(openmm.Platform.getNumPlatforms())])
print("plugin load failures:", openmm.Platform.getPluginLoadFailures())
PYTHON
    # The platform to test must load (the dry run has no libcuda: CUDA's failures are expected there).
    "$python" -c "import openmm, sys; openmm.Platform.getPlatformByName('$platform'); \
sys.exit(1 if [f for f in openmm.Platform.getPluginLoadFailures() if '$platform' in f] else 0)"
}
build_plugin() {
    # The build tools of the prefix (swig) on PATH; the plugin, its CUDA kernel library and its C++ tests.
    PATH=$prefix/bin:$PATH CMAKE_BUILD_PARALLEL_LEVEL=$(nproc) "$python" -m pip install --disable-pip-version-check \
        --no-index --no-deps --no-build-isolation --prefix "$prefix" -C build-dir="$build" \
        -C cmake.define.GENDPDE_BUILD_TESTS=ON . || return 1
    "$python" -c "import openmm, openmmgendpde; print(openmmgendpde.__file__); \
print('load failures:', openmm.Platform.getPluginLoadFailures())"
    ls "$site/OpenMM.libs/lib/plugins" | grep GenDPDE
}
cpp_tests() {
    # (all at once: on the H200 each CUDA test spends most of its time compiling kernels on the CPU; with 4 at a time
    # 7 of 11 had finished after 150 s)
    ctest --test-dir "$build" -R "$ctest_filter" -j 12 --timeout 170 --output-on-failure
}
# The Python side on the device: the GPU tier's platform comparisons (test_gpu_platforms.py) for this platform.
python_tests() {
    "$python" -m pytest -m gpu -q -k "$platform" "$root/python/tests/test_gpu_platforms.py" \
        "$root/python/tests/test_sweep_order.py"
}
# time_steps.py: N particles, the state melted on the device itself; ms per Isoenergetic step, then the profile.
throughput() {   # N [precisions after mixed]
    set -o pipefail   # (a function runs in a bash of its own: a failed time_steps.py must fail the stage)
    local n=$1 state=/tmp/gendpde-state-$1.npz ms precision
    shift
    ms=$("$python" benchmarks/time_steps.py --state "$state" --particles "$n" --platform "$platform" \
         --melt-platform "$platform" --precision mixed --what step --count "$steps" | tail -n 1) || return 1
    [ -n "$ms" ] || return 1
    echo "N = $n, $platform mixed: $ms ms per Isoenergetic step = $("$python" -c "print('%.3g' % ($n/($ms*1e-3)))") \
particle-steps/s"
    GENDPDE_PROFILE=1 "$python" benchmarks/time_steps.py --state "$state" --particles "$n" --platform "$platform" \
        --precision mixed --what step --count "$profile_steps" 2> "/tmp/gendpde-profile-$n.txt" || return 1
    cat "/tmp/gendpde-profile-$n.txt"
    "$python" devtools/profile_summary.py "/tmp/gendpde-profile-$n.txt" "N = $n, $platform mixed" || return 1
    for precision in "$@"; do   # (the state melted in mixed precision: the same liquid)
        ms=$("$python" benchmarks/time_steps.py --state "$state" --particles "$n" --platform "$platform" \
             --precision "$precision" --what step --count "$steps" | tail -n 1) || return 1
        [ -n "$ms" ] || return 1
        echo "N = $n, $platform $precision: $ms ms per Isoenergetic step = \
$("$python" -c "print('%.3g' % ($n/($ms*1e-3)))") particle-steps/s"
    done
}
# The step's stages in shared launches (the default) against a launch per stage: the same trajectory, bit for bit,
# and the time of each (devtools/sweep_launch_modes.py; the state file that throughput uses, melted on the device).
launch_modes() {
    "$python" devtools/sweep_launch_modes.py --platform "$platform" --precision mixed --particles "$1" \
        --state "/tmp/gendpde-state-$1.npz" --steps "$steps" --rounds 3
}
benchmarks() {
    local n=$1
    "$python" -m openmmgendpde benchmark-integrator --platform "$platform" --precision mixed --particles "$n" \
        --rounds "$rounds" || return 1
    "$python" -m openmmgendpde benchmark-force --platform "$platform" --precision mixed --particles "$n" \
        --cutoffs 1.6839 --rounds "$rounds"
}
# The device memory a Context holds per particle: nvidia-smi's count for this process with a Context of each size
# (the difference over the difference in particles: the CUDA context itself cancels); without nvidia-smi (the dry
# run on PoCL, where the device is this machine's memory) the growth of the resident set instead.
device_memory() {
    "$python" devtools/device_memory.py --platform "$platform" --precision mixed --particles "$small" "$large"
}

export python wheels platform ctest_filter prefix build site root steps profile_steps rounds small large
export -f environment cuda_libraries install build_plugin cpp_tests python_tests throughput benchmarks device_memory \
    launch_modes
stage env 30 environment
export LD_LIBRARY_PATH=$(cuda_libraries)${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
note "LD_LIBRARY_PATH for cuFFT and NVRTC: $LD_LIBRARY_PATH"
figures() {   # the lines of a stage's log that go into the summary
    grep -h "particle-steps/s\|^profile\|per particle\|^|\|a launch per stage" "$logs/$1.log" 2>/dev/null \
        | sed 's/^/    /' | tee -a "$summary"
}
correctness() {
    stage tests 120 cpp_tests
    stage python-tests 60 python_tests
}
if stage install 90 install && stage build 240 build_plugin; then
    [ "$tiny" = --tests-first ] && correctness
    # First the shared launches (ticket order across work groups, not checked on a GPU before this script first ran
    # there): should they differ from a launch per stage, or hang, every later stage takes a launch per stage.
    if ! stage launch-modes 60 launch_modes $small; then
        export GENDPDE_SWEEP_LAUNCH_PER_STAGE=1
        note "   (every later stage runs with GENDPDE_SWEEP_LAUNCH_PER_STAGE=1)"
    fi
    figures launch-modes
    stage throughput-large 90 throughput $large; figures throughput-large
    stage throughput-small 60 throughput $small single double; figures throughput-small
    stage memory 40 device_memory; figures memory
    stage benchmarks-small 120 benchmarks $small; figures benchmarks-small
    [ "$tiny" = --tests-first ] || correctness
    stage benchmarks-large 150 benchmarks $large; figures benchmarks-large
fi
