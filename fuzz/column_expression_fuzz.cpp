// SPDX-License-Identifier: BSD-3-Clause
// `--column NAME=EXPR` (io/column_expression.hpp): the bytes as an option's value, parsed, then
// evaluated on three rows of two fields with units, as a CSV or a log map would.
#include <array>
#include <vector>

#include "fuzz_support.hpp"
#include "geaware/io/column_expression.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  geaware::fuzz::expectNamedErrors([&] {
    const auto d =
        geaware::io::parseColumnDefinition(geaware::fuzz::text(data, size), geaware::fuzz::kSource);
    const std::array<double, 3> a = {1.0, 2.0, 0.0}, b = {-1.0, 1e300, 3.0};
    std::vector<geaware::io::ColumnExpression::FieldData> fields;
    for (std::size_t k = 0; k < d.expression.fields().size(); ++k)
      fields.push_back({k % 2 ? b : a, k % 2 ? "mm" : ""});
    (void)d.expression.evaluate(fields, 3, geaware::io::unitOfColumnName(d.name), d.name);
  });
  return 0;
}
