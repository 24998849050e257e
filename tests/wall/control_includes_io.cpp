// SPDX-License-Identifier: BSD-3-Clause
// Wall probe: must not compile when linked only against geaware_control.
#include <geaware/control/controller.hpp>
#include <geaware/io/vehicle_file.hpp>
int wallProbe() { return 0; }
