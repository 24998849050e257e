// SPDX-License-Identifier: BSD-3-Clause
// Wall probe: the estimator must not compile against the controller's headers (it depends on
// model/ only: the state estimate and the low-pass filter live there).
#include <geaware/control/controller.hpp>
#include <geaware/estimation/eskf.hpp>
int wallProbe() { return 0; }
