// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Text escaping for the HTML writer: element content and attribute values, and JSON text
// that is embedded inside a <script> element.

#include <string>
#include <string_view>

namespace geaware::report::detail {

/// `text` with & < > " ' replaced by character references, safe in element content and in
/// quoted attribute values.
[[nodiscard]] std::string escapeHtml(std::string_view text);

/// JSON text made safe inside a <script> element: < > & written as \u003c \u003e \u0026 (they
/// occur only inside strings), so no "</script" or "<!--" can appear in the embedded data.
[[nodiscard]] std::string scriptSafeJson(std::string_view json);

}  // namespace geaware::report::detail
