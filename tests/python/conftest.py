# SPDX-License-Identifier: BSD-3-Clause
"""Shared fixtures of the Python module's tests (run by CTest as /usr/bin/python3 -m pytest,
label python; python/CMakeLists.txt sets PYTHONPATH, GEAWARE_SOURCE_DIR and GEAWARE_CLI)."""
import os
import pathlib

import pytest


@pytest.fixture(scope="session")
def source_dir():
    return pathlib.Path(os.environ.get("GEAWARE_SOURCE_DIR", pathlib.Path(__file__).parents[2]))


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("GEAWARE_CLI")
    if not path:
        pytest.fail("GEAWARE_CLI (the geaware executable) is not set; run through CTest")
    return path
