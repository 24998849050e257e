// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The campaign's summary (`geaware bench`; docs/results.md): the text printed after the run and
// the JSON document of --json. Built from a CampaignResult only; the run is campaign.hpp.

#include <string>

#include "geaware/experiments/campaign.hpp"
#include "geaware/io/json.hpp"

namespace geaware::experiments {

/// Human-readable summary: calibration, Table I (ours mean ± std beside the paper's), the
/// hover curves, the ratios and checks, the wall time.
[[nodiscard]] std::string formatCampaign(const CampaignResult& r);

/// The JSON document of docs/results.md: {"experiments":[…],"hover":[…],…} (NaN as null).
[[nodiscard]] io::Json campaignJson(const CampaignResult& r);

}  // namespace geaware::experiments
