# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""Every tracked source file names its licence and holders near its top (devtools/licence_headers.py; LICENSE)."""

import pathlib

from helpers import load_file

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


def _licence_headers():
    return load_file(REPOSITORY / "devtools" / "licence_headers.py")


def test_the_checker_tells_a_header_from_none():
    headers = _licence_headers()
    cpp, shell = headers.style_of("a/b.cpp"), headers.style_of("x.sh")
    assert headers.has_header(headers.with_header("int x;\n", cpp))
    assert headers.has_header(headers.with_header("#!/bin/sh\necho\n", shell))
    assert headers.with_header("#!/bin/sh\necho\n", shell).startswith("#!/bin/sh\n# SPDX-License-Identifier: MIT\n")
    assert not headers.has_header("int x;\n")
    assert not headers.has_header("// Copyright (c) 2026 The openmm-gendpde developers\n")   # no licence named
    assert headers.style_of("README.md") is None


def test_every_source_file_has_its_licence_header():
    headers = _licence_headers()
    files = headers.source_files()
    assert len(files) > 250
    assert [str(path) for path in files if not headers.has_header((REPOSITORY / path).read_text())] == []
