// SPDX-License-Identifier: BSD-3-Clause
// Wall probe: a controller-side or identification target must not compile against the
// truth-file reader (it fills the simulator's world).
#include <geaware/io/truth_file.hpp>
int wallProbe() { return 0; }
