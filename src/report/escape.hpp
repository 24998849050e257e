#pragma once
// Text escaping for the HTML writer: element content and attribute values, and JSON literals
// that are embedded inside a <script> element.

#include <string>
#include <string_view>

namespace geaware::report::detail {

/// `text` with & < > " ' replaced by character references, safe in element content and in
/// quoted attribute values.
[[nodiscard]] std::string escapeHtml(std::string_view text);

/// A JSON string literal (with quotes). Besides the JSON escapes, < > & are written as
/// \u003c \u003e \u0026 so that no "</script" or "<!--" can appear in the embedded data.
[[nodiscard]] std::string jsonString(std::string_view text);

/// The shortest decimal text that reads back as exactly `value`; "null" when not finite
/// (JSON has no NaN or infinity; plotly draws null as a gap).
[[nodiscard]] std::string jsonNumber(double value);

}  // namespace geaware::report::detail
