#pragma once
// Reading a whole input file (vehicle, truth, scenario, weights) before it is parsed, with the
// errors every reader gives the same way.

#include <filesystem>
#include <string>
#include <string_view>

namespace geaware::io {

/// The bytes of `file`. Throws std::runtime_error naming the file: "<file>: no such <noun>",
/// "<file>: not a regular file (expected a <kind>)" or "<file>: cannot read <noun>", where
/// `noun` is e.g. "vehicle file" and `kind` "vehicle YAML file".
[[nodiscard]] std::string readInputFile(const std::filesystem::path& file, std::string_view noun,
                                        std::string_view kind);

}  // namespace geaware::io
