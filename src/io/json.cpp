#include "geaware/io/json.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <stdexcept>

namespace geaware::io {

std::string dumpJson(const Json& doc) {
  return doc.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string jsonString(std::string_view s) {
  return Json(std::string(s)).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

void writeJson(const std::string& path, const Json& doc) {
  const std::string text = dumpJson(doc) + "\n";
  if (path == "-") {
    std::cout << text << std::flush;
    if (!std::cout) throw std::runtime_error("standard output: cannot write the JSON output");
    return;
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    throw std::runtime_error(path + ": cannot open for writing the JSON output: " + std::strerror(errno));
  }
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const int write_errno = errno;
  const bool flushed = std::fflush(f) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!written || !flushed || !closed) {
    const int e = !written ? write_errno : (!flushed ? flush_errno : errno);
    throw std::runtime_error(path + ": cannot write the JSON output: " + std::strerror(e));
  }
}

}  // namespace geaware::io
