#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The licence header of every source file (LICENSE: MIT): list the files without one, or add it.

    .venv/bin/python devtools/licence_headers.py            # the tracked source files that lack it (exit 1 if any)
    .venv/bin/python devtools/licence_headers.py --add      # add it where it is missing

The header is two lines in the file's comment syntax, first in the file (after a shebang):

    SPDX-License-Identifier: MIT
    Copyright (c) 2026 The openmm-gendpde developers

The LAMMPS package (lammps/) carries LAMMPS's own header block instead, which names the same licence and holders.
python/tests/test_licence_headers.py runs the check.
"""

import argparse
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
SPDX = "SPDX-License-Identifier: MIT"
HOLDERS = "Copyright (c) 2026 The openmm-gendpde developers"
#: Comment syntax by file name ending: (first line, second line).
C_STYLE = (f"/* {SPDX}\n", f" * {HOLDERS} */\n")
HASH_STYLE = (f"# {SPDX}\n", f"# {HOLDERS}\n")
STYLES = {".h": C_STYLE, ".cpp": C_STYLE, ".cc": C_STYLE, ".i": C_STYLE, ".h.in": C_STYLE, ".cpp.in": C_STYLE,
          ".py": HASH_STYLE, ".py.in": HASH_STYLE, ".sh": HASH_STYLE, ".cmake": HASH_STYLE,
          "CMakeLists.txt": HASH_STYLE, ".ci/run": HASH_STYLE}
#: How many lines from the top a header may start at (a shebang, LAMMPS's block).
WITHIN = 12


def style_of(path):
    """The comment style for ``path`` (relative, as git lists it), or None if it is not a source file."""
    for ending, style in STYLES.items():
        if str(path).endswith(ending):
            return style
    return None


def source_files():
    """The tracked source files, relative paths."""
    listed = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    return [pathlib.Path(line) for line in listed.splitlines() if style_of(line) is not None]


def has_header(text):
    """Whether ``text`` names the licence and its holders near its top (ours or LAMMPS's block for lammps/)."""
    top = "\n".join(text.splitlines()[:WITHIN])
    return HOLDERS in top and (SPDX in top or "MIT License" in top)


def with_header(text, style):
    """``text`` with the header added first (after a shebang line)."""
    lines = text.splitlines(keepends=True)
    shebang = [lines.pop(0)] if lines and lines[0].startswith("#!") else []
    return "".join(shebang + list(style) + lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--add", action="store_true", help="add the header where it is missing")
    arguments = parser.parse_args(argv)
    missing = [path for path in source_files() if not has_header((ROOT / path).read_text())]
    if arguments.add:
        for path in missing:
            (ROOT / path).write_text(with_header((ROOT / path).read_text(), style_of(path)))
        print(f"added the header to {len(missing)} files")
        return 0
    for path in missing:
        print(path)
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
