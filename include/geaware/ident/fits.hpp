// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Every fit of the identification layer (docs/identification.md). Each returns its parameters
// with standard errors (ident::Estimate), the residual RMS and counts (ident::FitStats), and
// warnings for data that constrain a parameter poorly; a fit that cannot be done throws
// ident::IdentError naming the log.

#include "geaware/ident/correlation.hpp"     // Spearman rank correlation, the supplementary table
#include "geaware/ident/flight_fit.hpp"      // F_G from a hover descent, drag table D(h)
#include "geaware/ident/least_squares.hpp"   // Estimate, FitStats, robust linear/nonlinear LS
#include "geaware/ident/leveling_fit.hpp"    // M_G(h) from the tilted board
#include "geaware/ident/platform_fit.hpp"    // k_T, F_G and the mixing coefficients, level board
#include "geaware/ident/rotor_fit.hpp"       // k_T, k_I, J_R, throttle curve from the stand
#include "geaware/ident/table_fit.hpp"       // knots and basis of curves fitted as tables
