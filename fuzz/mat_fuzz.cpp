// SPDX-License-Identifier: BSD-3-Clause
// MATLAB .mat files: io::readMat (libmatio opens files by name, so the bytes go to a file of this
// process first), then what `geaware logs inspect` does with the log. libmatio itself is not
// instrumented: a crash inside it is still a crash here.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_support.hpp"
#include "geaware/io/json.hpp"
#include "geaware/io/log_channels.hpp"
#include "geaware/io/log_inspect.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("geaware_fuzz_mat_" + std::to_string(::getpid()) + ".mat");
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                static_cast<std::streamsize>(size));
  try {
    const geaware::io::LogData log = geaware::io::readMat(file);
    const geaware::io::LogSummary summary = geaware::io::inspectLog(log);
    (void)geaware::io::summaryText(summary);
    (void)geaware::io::dumpJson(geaware::io::summaryJson(summary));
  } catch (const std::exception& e) {
    // The errors name the file (the temporary one here), not fuzz::kSource.
    if (std::string_view(e.what()).rfind(file.string(), 0) != 0) {
      std::fprintf(stderr, "fuzz: an error that does not name the input: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
