#include "geaware/io/input_file.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace geaware::io {

std::string readInputFile(const std::filesystem::path& file, std::string_view noun,
                          std::string_view kind) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw std::runtime_error(file.string() +
                             (std::filesystem::exists(file, ec)
                                  ? ": not a regular file (expected a " + std::string(kind) + ")"
                                  : ": no such " + std::string(noun)));
  }
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  if (!in || !(text << in.rdbuf())) {
    throw std::runtime_error(file.string() + ": cannot read " + std::string(noun));
  }
  return text.str();
}

}  // namespace geaware::io
