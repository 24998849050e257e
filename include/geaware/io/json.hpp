// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// JSON for every `--json` output, built with nlohmann-json (Debian: nlohmann-json3-dev) and
// written one way. Keys keep the order in which they are inserted. Non-finite numbers are written
// as null (nlohmann's rule) and strings are escaped by the library, so no command builds JSON
// text by hand. This header is heavy: include it only where a JSON document is built.

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace geaware::io {

/// A JSON document whose object keys keep their insertion order.
using Json = nlohmann::ordered_json;

/// `doc` as text: two-space indented, NaN and ±inf as null, invalid UTF-8 replaced by U+FFFD
/// (a vehicle name or path from the user never makes the output unparsable).
[[nodiscard]] std::string dumpJson(const Json& doc);

/// Writes `doc` (with a final newline) to `path`; "-" writes to standard output. The text is
/// built before the file is opened and every write is checked (a full disk is an error naming
/// the path, never a silent 0-byte file).
void writeJson(const std::string& path, const Json& doc);

/// `s` as a JSON string literal (quotes included).
[[nodiscard]] std::string jsonString(std::string_view s);

}  // namespace geaware::io
