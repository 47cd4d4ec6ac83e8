# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Where the time of a step (or a force evaluation) goes: samples `benchmarks/time_steps.py` with Linux perf and prints
the share of each function of the plugin, the parallel loops' bodies named by the function that runs them
(docs/performance.md, "Where a step's time goes").

The installed libraries are stripped; their symbols are read from the build tree's copies (same build, `build/`),
so run it after `scripts/setup.sh`. Needs perf (`apt install linux-perf`). Arguments after `--` go to
benchmarks/time_steps.py, e.g.

    .venv/bin/python benchmarks/profile_step.py --top 20 -- --state /tmp/argon32k.npz --platform CPU \
        --threads 2 --count 200
"""

import argparse
import bisect
import collections
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LIBRARIES = {
    "libOpenMMGenDPDE.so": "build/lib/libOpenMMGenDPDE.so",
    "libOpenMMGenDPDEReference.so": "build/lib/plugins/libOpenMMGenDPDEReference.so",
    "libOpenMMGenDPDECPU.so": "build/lib/plugins/libOpenMMGenDPDECPU.so",
}


def symbol_table(path):
    """(address, name) of the functions of an unstripped library, sorted by address."""
    output = subprocess.run(["nm", "-C", "--defined-only", path], capture_output=True, text=True, check=True).stdout
    table = []
    for line in output.splitlines():
        fields = line.split(" ", 2)
        if len(fields) == 3 and fields[1] in "tTwW":
            table.append((int(fields[0], 16), fields[2]))
    return sorted(table)


def short_name(name):
    """The function without its arguments; a parallel loop's body is named by the loop's caller."""
    caller = re.search(r"parallelFor<(?:GenDPDEPlugin::)?([\w:]+)", name)
    if caller:
        return caller.group(1) + " (parallel loop)"
    mangled = re.search(r"parallelForIZ+N(.*)", name)   # a body whose name the demangler left mangled
    if mangled:
        text, parts = mangled.group(1), []
        while len(parts) < 3:
            text = text[2:] if text.startswith("S_") else text
            length = re.match(r"\d+", text)
            if not length:
                break
            size = int(length.group(0))
            parts.append(text[len(length.group(0)):len(length.group(0)) + size])
            text = text[len(length.group(0)) + size:]
        parts = [part for part in parts if part != "GenDPDEPlugin"]
        if parts:
            return "::".join(parts) + " (parallel loop)"
    # (the arguments go; "(anonymous namespace)::" is not an argument list)
    return re.sub(r"\(.*", "", name.replace("(anonymous namespace)::", ""))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--top", type=int, default=20, help="functions printed (default 20)")
    parser.add_argument("--frequency", type=int, default=2000, help="samples per second (default 2000)")
    parser.add_argument("timing", nargs=argparse.REMAINDER, help="-- then benchmarks/time_steps.py's arguments")
    arguments = parser.parse_args()
    timing = arguments.timing[1:] if arguments.timing[:1] == ["--"] else arguments.timing
    tables = {}
    for library, path in LIBRARIES.items():
        if not os.path.exists(os.path.join(ROOT, path)):
            sys.exit(f"{path} is missing: run scripts/setup.sh first")
        tables[library] = symbol_table(os.path.join(ROOT, path))
    with tempfile.TemporaryDirectory() as directory:
        data = os.path.join(directory, "perf.data")
        run = subprocess.run(["perf", "record", "-q", "-F", str(arguments.frequency), "-o", data, sys.executable,
                              os.path.join(ROOT, "benchmarks", "time_steps.py")] + timing,
                             capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(run.stderr)
        print(f"time_steps.py: {run.stdout.strip()} ms per call")
        report = subprocess.run(["perf", "report", "-i", data, "-n", "--no-children", "--sort", "dso,symbol"],
                                capture_output=True, text=True, check=True).stdout
    shares, total = collections.Counter(), 0
    for line in report.splitlines():
        match = re.match(r"\s*[\d.]+%\s+(\d+)\s+(\S+)\s+\[.\]\s+(.*?)\s*$", line)
        if not match:
            continue
        samples, library = int(match.group(1)), match.group(2)
        name = re.sub(r"(\s+-)+$", "", match.group(3))   # perf's empty columns after a named symbol
        total += samples
        if library in tables and name.startswith("0x"):
            table = tables[library]
            index = bisect.bisect_right(table, (int(name.split()[0], 16), "\uffff")) - 1
            name = table[index][1] if index >= 0 else name
        shares[(library, short_name(name) or "(unnamed)")] += samples
    print(f"{total} samples; share of each function (all threads):")
    for (library, name), samples in shares.most_common(arguments.top):
        print(f"{100.0 * samples / total:6.1f}%  {library:30s} {name}")


if __name__ == "__main__":
    main()
