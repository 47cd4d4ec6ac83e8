# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""python -m openmmgendpde <subcommand> [options]: the command line (openmmgendpde.cli.main); --help for each."""

import warnings

from .cli.main import SUBCOMMANDS, main  # noqa: F401  (SUBCOMMANDS: the command line's, named here too)

if __name__ == "__main__":
    from .cli.main import format_warning
    warnings.formatwarning = format_warning
    main()
