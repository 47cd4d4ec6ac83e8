# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Sum up a GENDPDE_PROFILE report (the standard error of a run with GENDPDE_PROFILE=1; docs/performance.md) in a
few lines that start with "profile": launches and host transfers per step (the force's and the integrator's, over the
integrator's steps), the sweep order's builds per step, the neighbour list's builds, the critical path in levels and
the sweep's device time per level.

    python devtools/profile_summary.py profile.txt "N = 1000188, CUDA mixed"
"""

import re
import sys


def parse(text):
    owners = {}
    owner = None
    for line in text.splitlines():
        match = re.match(r"GenDPDE (\S+), device time per part", line)
        if match:
            owner = owners.setdefault(match.group(1), {"parts": {}})
            continue
        match = re.match(r"  (.+?)\s+(\d+)\s+([0-9.]+)\s+([0-9.]+)$", line)
        if match and owner is not None:
            owner["parts"][match.group(1)] = (int(match.group(2)), float(match.group(3)))
            continue
        match = re.match(r"GenDPDE (\S+), counts: (\d+) calls .*?, ([0-9.]+) launches and ([0-9.]+) host transfers",
                         line)
        if match:
            entry = owners.setdefault(match.group(1), {"parts": {}})
            entry["calls"] = int(match.group(2))
            entry["launches"] = float(match.group(3)) * int(match.group(2))
            entry["transfers"] = float(match.group(4)) * int(match.group(2))
        match = re.search(r"critical path (\d+) levels", line)
        if match:
            owners.setdefault(line.split(",")[0].split()[1], {"parts": {}})["levels"] = int(match.group(1))
        match = re.match(r"GenDPDE (\S+), sweep order: (\d+) builds in (\d+) steps", line)
        if match:
            owners[match.group(1)]["builds"] = int(match.group(2))
        match = re.match(r"GenDPDE (\S+), neighbour list: (\d+) builds", line)
        if match:
            owners.setdefault(match.group(1), {"parts": {}})["list builds"] = int(match.group(2))
    return owners


def main():
    path = sys.argv[1]
    label = sys.argv[2] if len(sys.argv) > 2 else path
    owners = parse(open(path).read())
    integrator = owners.get("GenDPDEIntegrator")
    if integrator is None or "calls" not in integrator:
        print(f"profile {label}: no integrator counts in {path}")
        return 1
    steps = integrator["calls"]
    launches = {name: entry.get("launches", 0.0) / steps for name, entry in owners.items()}
    transfers = sum(entry.get("transfers", 0.0) for entry in owners.values()) / steps
    print(f"profile {label}: {steps} steps (with the 10 untimed ones); launches per step "
          + " + ".join(f"{name} {value:.2f}" for name, value in launches.items())
          + f" = {sum(launches.values()):.2f}; host transfers per step {transfers:.3f}")
    force = owners.get("GenDPDEForce", {})
    if "builds" in integrator:
        print(f"profile {label}: sweep order builds {integrator['builds']} in {steps} steps "
              f"({integrator['builds'] / steps:.4f} per step); neighbour list builds {force.get('list builds', '?')}")
    sweep = integrator["parts"].get("sweep (8 colours)")
    if "levels" in integrator and sweep:
        per_step = 1e3 * sweep[1] / sweep[0]
        print(f"profile {label}: critical path {integrator['levels']} levels; sweep {per_step:.1f} us per step = "
              f"{per_step / integrator['levels']:.3f} us per level")
    for name, entry in owners.items():
        parts = ", ".join(f"{part} {1e3 * total / steps:.1f}" for part, (calls, total) in entry["parts"].items())
        print(f"profile {label}: {name} device time per step (us; synchronised per part): {parts}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
