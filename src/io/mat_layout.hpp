// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Private to io/: a v5/v7 .mat file's data elements walked before libmatio reads it
// (src/io/mat_layout.cpp).

#include <cstdint>
#include <filesystem>

namespace geaware::io::detail {

/// Walks every data element of a v5/v7 .mat file (nested ones, compressed ones inflated as they
/// are walked, at most `limit` bytes), checking that each fits in its variable and the file and
/// that no variable's dimensions claim more elements than its bytes or limit / 8. Returns the
/// bytes walked (an upper bound on the numbers the file can hold), 0 for a v7.3 (HDF5) file,
/// which is not walked (as libmatio, by the header's version field, not its text). Throws
/// LogError naming the file and the variable's byte, or the header's byte for a header libmatio
/// would read as a MATLAB v4 file (not read) or a file shorter than the header.
[[nodiscard]] std::uintmax_t checkMatLayout(const std::filesystem::path& file, std::uintmax_t size,
                                            std::uintmax_t limit);

}  // namespace geaware::io::detail
