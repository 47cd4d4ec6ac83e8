# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The device memory a Context of liquid argon (V-B, R* = 1.6839, Isoenergetic) holds per particle: a Context of each
size is made and stepped in this process, one after the other and all kept (first one of the smaller size that
takes the process's one-time costs), and the memory this process holds on the GPU is read from nvidia-smi after
each: a later Context of N particles takes F + a N (F: its own CUDA context, programs and fixed buffers), so
a = (what the larger took - what the second smaller took) / (the difference in particles). Without nvidia-smi (OpenCL
on a CPU, where the device memory is the process's) the growth of the resident set is used instead, labelled so.

    python devtools/device_memory.py --platform CUDA --precision mixed --particles 108000 1000188
"""

import argparse
import os
import shutil
import subprocess

from openmmgendpde import GenDPDEIntegrator
from openmmgendpde.models.argon import liquid_argon


def process_memory_mib():
    """(MiB this process holds on the GPU per nvidia-smi, or the resident set where there is none; the source)."""
    if shutil.which("nvidia-smi"):
        text = subprocess.run(["nvidia-smi", "--query-compute-apps=pid,used_memory", "--format=csv,noheader,nounits"],
                              capture_output=True, text=True, check=True).stdout
        for line in text.splitlines():
            fields = [field.strip() for field in line.split(",")]
            if len(fields) == 2 and fields[0] == str(os.getpid()) and fields[1].isdigit():
                return float(fields[1]), "GPU memory of this process (nvidia-smi)"
        # In a container nvidia-smi may not see this process's id: the memory used on the device instead (a lent
        # GPU runs nothing else).
        text = subprocess.run(["nvidia-smi", "--query-gpu=memory.used", "--format=csv,noheader,nounits", "-i", "0"],
                              capture_output=True, text=True, check=True).stdout
        return float(text.split()[0]), "GPU memory used on device 0 (nvidia-smi; this process not listed)"
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return float(line.split()[1]) / 1024, "resident set (no nvidia-smi: not device memory)"
    raise RuntimeError("no memory count")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--platform", default="CUDA")
    parser.add_argument("--precision", default="mixed")
    parser.add_argument("--particles", type=int, nargs=2, required=True, help="the two sizes, smaller first")
    parser.add_argument("--steps", type=int, default=5)
    arguments = parser.parse_args()
    kept, readings = [], []
    for n in [arguments.particles[0]] + arguments.particles:
        model = liquid_argon(n, 1.6839, "VB", seed=1, mode=GenDPDEIntegrator.Isoenergetic)
        context = model.context(arguments.platform, properties={"Precision": arguments.precision}, seed=1)
        model.integrator.step(arguments.steps)
        kept.append((model, context))
        mib, source = process_memory_mib()
        readings.append(mib)
        print(f"N = {n}: {mib:.0f} MiB ({source}) with the Contexts so far")
    (n0, n1), (base, m0, m1) = arguments.particles, readings   # (base: after the first Context)
    took0, took1 = m0 - base, m1 - m0
    print(f"{arguments.platform} {arguments.precision}: {(took1 - took0) * 2**20 / (n1 - n0):.0f} bytes per particle "
          f"({source}: the Context of N = {n1} took {took1:.0f} MiB, that of N = {n0} {took0:.0f} MiB)")


if __name__ == "__main__":
    main()
