// SPDX-License-Identifier: BSD-3-Clause
// Wall probe: a controller-side or identification target must not compile against the
// simulator's world.
#include <geaware/sim/world.hpp>
int wallProbe() { return 0; }
