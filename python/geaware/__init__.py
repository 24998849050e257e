# SPDX-License-Identifier: BSD-3-Clause
"""geaware: ground-effect-aware modelling and control of multicopters, from Python.

The C++ library behind the command line `geaware` (docs/python.md). SI units everywhere,
rotor speeds in rpm; every name carries its unit. Files are read by the same strict readers
as the command line: a malformed file raises geaware.ConfigError (a ValueError) naming the
file, the line and the key.
"""
from ._geaware import *  # noqa: F401,F403
from ._geaware import __doc__ as _native_doc  # noqa: F401

__all__ = [name for name in dir() if not name.startswith("_")]
