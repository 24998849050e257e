// SPDX-License-Identifier: BSD-3-Clause
// Wall probe: compiles only for targets that link geaware_io.
#include <geaware/io/vehicle_file.hpp>
int wallProbe() { return 0; }
