// SPDX-License-Identifier: BSD-3-Clause
// The translation unit that builds the test suite's precompiled header (tests/CMakeLists.txt).
