// SPDX-License-Identifier: BSD-3-Clause
// Crazyflie uSD logs (both versions): io::readCrazyflieUsd on bytes in memory (io::readLog streams
// a file through the same parser), then what `geaware logs inspect` does with the log.
#include <span>

#include "fuzz_support.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/log_channels.hpp"
#include "geaware/io/log_inspect.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    const geaware::io::LogData log = geaware::io::readCrazyflieUsd(
        std::as_bytes(std::span(data, size)), std::string(geaware::fuzz::kSource));
    const geaware::io::LogSummary summary = geaware::io::inspectLog(log);
    (void)geaware::io::summaryText(summary);
    (void)geaware::io::dumpJson(geaware::io::summaryJson(summary));
  });
  return 0;
}
