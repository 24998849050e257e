// SPDX-License-Identifier: BSD-3-Clause
// Wall probe: the controller must not compile against the simulator's headers.
#include <geaware/control/controller.hpp>
#include <geaware/sim/plant.hpp>
int wallProbe() { return 0; }
