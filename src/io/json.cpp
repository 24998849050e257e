// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/json.hpp"

#include "geaware/io/output_file.hpp"


namespace geaware::io {

std::string dumpJson(const Json& doc) {
  return doc.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string jsonString(std::string_view s) {
  return Json(std::string(s)).dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

void writeJson(const std::string& path, const Json& doc) {
  writeFileAtomically(path, dumpJson(doc) + "\n", "the JSON output");
}

}  // namespace geaware::io
