// SPDX-License-Identifier: BSD-3-Clause
// CSV logs: io::CsvReader on bytes in memory (the reader io::readCsv, behind every rig and
// flight log of `identify`, runs on a file: the same parser, only the byte source differs), row
// by row as readCsv reads it, with the columns of a rotor-stand log (ident/rig_logs.cpp: the time column
// strictly increasing, each column range-checked). The same bytes are read twice: with a buffer
// larger than the input (the path of every log under the default 4 MiB buffer: one read, then
// the end; the default itself would cost a 4 MiB allocation per execution) and with the
// smallest buffer (64 bytes), which makes lines cross refills and buffer growth; both readings
// must agree (the same table, or the same error).
#include <limits>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "geaware/io/csv_reader.hpp"

namespace {

geaware::io::CsvReadOptions rotorStandColumns(std::size_t buffer_bytes) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  geaware::io::CsvReadOptions o;
  o.columns = {{"t_s", -kInf, kInf},
               {"throttle", 0.0, 1.0},
               {"rpm", 0.0, 1e5},
               {"thrust_N", -1e4, 1e4},
               {"torque_Nm", -1e3, 1e3}};
  o.time_column = "t_s";
  o.min_rows = 2;
  o.buffer_bytes = buffer_bytes;
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  struct Outcome {
    std::string error;  // empty: read
    geaware::io::CsvTable table;
  };
  Outcome outcome[2];
  int i = 0;
  for (const std::size_t buffer_bytes : {2 * size + 64, std::size_t{64}}) {
    Outcome& out = outcome[i++];
    geaware::fuzz::expectNamedErrors([&] {
      try {
        const auto options = rotorStandColumns(buffer_bytes);
        geaware::io::CsvReader reader(geaware::fuzz::text(data, size),
                                      std::string(geaware::fuzz::kSource), options);
        out.table.columns.resize(options.columns.size());
        std::vector<double> row(options.columns.size());
        while (reader.next(row)) {
          if (out.table.columns.front().empty()) out.table.first_data_line = reader.line();
          for (std::size_t k = 0; k < row.size(); ++k) out.table.columns[k].push_back(row[k]);
        }
      } catch (const std::exception& e) {
        out.error = e.what();
        throw;
      }
    });
  }
  const Outcome& a = outcome[0];
  const Outcome& b = outcome[1];
  if (a.error != b.error || a.table.columns != b.table.columns ||
      a.table.first_data_line != b.table.first_data_line) {
    std::fprintf(stderr, "fuzz: the buffer size changed the result: '%s' / '%s'\n", a.error.c_str(),
                 b.error.c_str());
    std::abort();
  }
  return 0;
}
