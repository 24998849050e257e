// SPDX-License-Identifier: BSD-3-Clause
// MATLAB .mat files (v5, v7 compressed, v7.3 HDF5) through libmatio (Debian libmatio-dev, built
// with HDF5). Every variable's class, rank and size is read first (Mat_VarReadNextInfo, no data)
// and checked before its data is read: numeric real vectors become channels, the columns of an
// N×k matrix (k ≤ 64, the longer side the samples) channels `name[j]`, struct fields (nested up
// to 8 levels) channels of a topic named after the struct; numeric scalars become parameters.
// Channels of one length form one topic: top-level vectors topic `mat`, a struct's fields the
// struct's topic (a second length: instance 1, …). A topic's time is its first channel called
// t, t_s, time, time_s or timestamp [s] (a log map's `time:` may name another), else the sample
// number, with a warning. Anything else (text, cells, complex or sparse data, more than two
// dimensions) is skipped and named in one warning.

#include <matio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <string_view>

#include "geaware/io/input_file.hpp"
#include "geaware/io/log_channels.hpp"
#include "mat_layout.hpp"

namespace geaware::io {
namespace {

constexpr std::size_t kMaxColumns = 64;
constexpr int kMaxDepth = 8;

// libmatio's messages, kept for the error that follows them instead of printed.
thread_local std::string g_matio_message;
void matioLog(int /*level*/, char* message) {
  if (message != nullptr && g_matio_message.size() < 400) {
    g_matio_message += (g_matio_message.empty() ? "" : "; ") + std::string(message);
  }
}

struct MatCloser {
  void operator()(mat_t* m) const noexcept { Mat_Close(m); }
};
struct VarFree {
  void operator()(matvar_t* v) const noexcept { Mat_VarFree(v); }
};
using MatPtr = std::unique_ptr<mat_t, MatCloser>;
using VarPtr = std::unique_ptr<matvar_t, VarFree>;

bool numericClass(matio_classes c) {
  switch (c) {
    case MAT_C_DOUBLE:
    case MAT_C_SINGLE:
    case MAT_C_INT8:
    case MAT_C_UINT8:
    case MAT_C_INT16:
    case MAT_C_UINT16:
    case MAT_C_INT32:
    case MAT_C_UINT32:
    case MAT_C_INT64:
    case MAT_C_UINT64:
      return true;
    default:
      return false;
  }
}

FieldType fieldType(matio_classes c) {
  switch (c) {
    case MAT_C_SINGLE:
      return FieldType::kFloat;
    case MAT_C_INT8:
      return FieldType::kInt8;
    case MAT_C_UINT8:
      return FieldType::kUInt8;
    case MAT_C_INT16:
      return FieldType::kInt16;
    case MAT_C_UINT16:
      return FieldType::kUInt16;
    case MAT_C_INT32:
      return FieldType::kInt32;
    case MAT_C_UINT32:
      return FieldType::kUInt32;
    case MAT_C_INT64:
      return FieldType::kInt64;
    case MAT_C_UINT64:
      return FieldType::kUInt64;
    default:
      return FieldType::kDouble;
  }
}

double element(const void* data, matio_classes c, std::size_t i) {
  switch (c) {
    case MAT_C_DOUBLE:
      return static_cast<const double*>(data)[i];
    case MAT_C_SINGLE:
      return static_cast<const float*>(data)[i];
    case MAT_C_INT8:
      return static_cast<const std::int8_t*>(data)[i];
    case MAT_C_UINT8:
      return static_cast<const std::uint8_t*>(data)[i];
    case MAT_C_INT16:
      return static_cast<const std::int16_t*>(data)[i];
    case MAT_C_UINT16:
      return static_cast<const std::uint16_t*>(data)[i];
    case MAT_C_INT32:
      return static_cast<const std::int32_t*>(data)[i];
    case MAT_C_UINT32:
      return static_cast<const std::uint32_t*>(data)[i];
    case MAT_C_INT64:
      return static_cast<double>(static_cast<const std::int64_t*>(data)[i]);
    case MAT_C_UINT64:
      return static_cast<double>(static_cast<const std::uint64_t*>(data)[i]);
    default:
      return std::nan("");
  }
}

bool isTimeName(std::string n) {
  for (auto& c : n) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return n == "t" || n == "t_s" || n == "time" || n == "time_s" || n == "timestamp";
}

class MatParser {
 public:
  MatParser(std::string source, const LogReadOptions& options, std::uintmax_t max_numbers)
      : source_(std::move(source)), options_(options), max_numbers_(max_numbers) {
    log_.source = source_;
    log_.format = "mat";
  }

  // Checks every variable's size from its header, before any data is read.
  void checkSizes(mat_t* mat) {
    std::uint64_t elements = 0;
    for (;;) {
      VarPtr info(Mat_VarReadNextInfo(mat));
      if (!info) break;
      elements += count(info.get(), 0);
      if (elements > max_numbers_) {
        fail("variable '" + name(info.get()) + "': the variables claim more than " +
             std::to_string(max_numbers_) +
             " numbers (more than the file's bytes can hold, or than 1 GiB of doubles); refused "
             "before reading");
      }
      names_.emplace_back(name(info.get()));
    }
  }

  LogData run(mat_t* mat) {
    for (const auto& n : names_) {
      g_matio_message.clear();
      VarPtr var(Mat_VarRead(mat, n.c_str()));
      if (!var) fail("variable '" + n + "' could not be read" + why());
      add(var.get(), "", n, 0);
    }
    finish();
    return std::move(log_);
  }

  [[noreturn]] void fail(const std::string& message) const { throw LogError(source_, message); }
  static std::string why() {
    return g_matio_message.empty() ? "" : " (libmatio: " + g_matio_message + ")";
  }

 private:
  static std::string name(const matvar_t* v) { return v->name != nullptr ? v->name : "?"; }

  // Numbers a variable holds (struct fields summed), with its dimensions checked for overflow.
  std::uint64_t count(const matvar_t* v, int depth) {
    if (depth > kMaxDepth) return 0;
    std::uint64_t n = 1;
    for (int k = 0; k < v->rank && v->dims != nullptr; ++k) {
      if (v->dims[k] != 0 && n > max_numbers_ / v->dims[k]) {
        fail("variable '" + name(v) + "': dimensions too large (more numbers than a log may hold)");
      }
      n *= v->dims[k];
    }
    if (v->class_type == MAT_C_STRUCT && n == 1) {
      if (v->data == nullptr) return 0;  // no fields read (libmatio then has no field array)
      std::uint64_t sum = 0;
      const unsigned fields = Mat_VarGetNumberOfFields(const_cast<matvar_t*>(v));
      for (unsigned f = 0; f < fields; ++f) {
        const matvar_t* field = Mat_VarGetStructFieldByIndex(const_cast<matvar_t*>(v), f, 0);
        if (field != nullptr) sum += count(field, depth + 1);
      }
      return sum;
    }
    return numericClass(v->class_type) ? n : 0;
  }

  void skip(const std::string& path, const std::string& why_skipped) {
    if (skipped_.size() < 20) skipped_.push_back(path + " (" + why_skipped + ")");
    ++skipped_count_;
  }

  // `topic` empty: a top-level variable (topic "mat").
  void add(matvar_t* v, const std::string& topic, const std::string& path, int depth) {
    if (v->class_type == MAT_C_STRUCT) {
      std::size_t n = 1;
      for (int k = 0; k < v->rank; ++k) n *= v->dims[k];
      if (n != 1) return skip(path, "a struct array");
      if (depth >= kMaxDepth) return skip(path, "nested deeper than 8");
      if (v->data == nullptr) return skip(path, "a struct without fields");
      const unsigned fields = Mat_VarGetNumberOfFields(v);
      char* const* names = Mat_VarGetStructFieldnames(v);
      for (unsigned f = 0; f < fields; ++f) {
        matvar_t* field = Mat_VarGetStructFieldByIndex(v, f, 0);
        const std::string fname =
            names != nullptr && names[f] != nullptr ? names[f] : std::to_string(f);
        if (field == nullptr) continue;
        // A top-level struct is a topic; a nested one's fields are "inner.field" in it.
        add(field, topic.empty() ? path : topic, topic.empty() ? fname : path + "." + fname,
            depth + 1);
      }
      return;
    }
    const std::string full = topic.empty() ? path : topic + "." + path;
    if (!numericClass(v->class_type)) return skip(full, "not numeric");
    if (v->isComplex != 0) return skip(full, "complex");
    if (v->rank != 2) return skip(full, std::to_string(v->rank) + " dimensions");
    const std::size_t rows = v->dims[0], cols = v->dims[1];
    if (rows == 0 || cols == 0) return skip(full, "empty");
    if (v->data == nullptr) return skip(full, "no data");
    const std::string& channel = path;
    const std::string where = topic.empty() ? "mat" : topic;
    if (rows == 1 && cols == 1) {
      log_.parameters[full] = element(v->data, v->class_type, 0);
      return;
    }
    if (rows == 1 || cols == 1) {
      std::vector<double> values(rows * cols);
      for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = element(v->data, v->class_type, i);
      return put(where, channel, fieldType(v->class_type), std::move(values));
    }
    const bool by_rows = rows >= cols;  // samples along the longer side
    const std::size_t samples = by_rows ? rows : cols, width = by_rows ? cols : rows;
    if (width > kMaxColumns)
      return skip(full, std::to_string(rows) + "×" + std::to_string(cols) + " matrix");
    for (std::size_t j = 0; j < width; ++j) {
      std::vector<double> values(samples);
      for (std::size_t i = 0; i < samples; ++i) {
        values[i] =
            element(v->data, v->class_type, by_rows ? i + j * rows : j + i * rows);  // column-major
      }
      put(where, channel + "[" + std::to_string(j) + "]", fieldType(v->class_type),
          std::move(values));
    }
  }

  void put(const std::string& topic, const std::string& channel, FieldType type,
           std::vector<double> values) {
    if (!options_.topics.empty() &&
        std::find(options_.topics.begin(), options_.topics.end(), topic) == options_.topics.end()) {
      return;
    }
    Topic* t = nullptr;
    for (auto& x : log_.topics) {
      if (x.name == topic && x.channels.front().values.size() == values.size()) t = &x;
    }
    if (t == nullptr) {
      unsigned instance = 0;
      for (const auto& x : log_.topics) instance += x.name == topic ? 1U : 0U;
      log_.topics.push_back({topic, instance, {}, {}});
      t = &log_.topics.back();
    }
    t->channels.push_back({channel, "", type, std::move(values)});
  }

  void finish() {
    for (auto& t : log_.topics) {
      const Channel* time = nullptr;
      for (const auto& c : t.channels) {
        if (time == nullptr && isTimeName(c.name)) time = &c;
      }
      const std::size_t n = t.channels.front().values.size();
      if (time != nullptr) {
        t.time_s = time->values;
      } else {
        t.time_s.resize(n);
        for (std::size_t i = 0; i < n; ++i) t.time_s[i] = static_cast<double>(i);
        log_.warnings.push_back(
            "topic " + t.name + "[" + std::to_string(t.instance) +
            "]: no time variable (t, t_s, time, time_s, timestamp): the sample number stands "
            "for the time [s]; a log map's `time:` may name another");
      }
    }
    if (skipped_count_ > 0) {
      std::string s;
      for (const auto& x : skipped_) s += (s.empty() ? "" : ", ") + x;
      log_.warnings.push_back(std::to_string(skipped_count_) + " variables are no channels: " + s +
                              (skipped_count_ > skipped_.size() ? ", …" : ""));
    }
  }

  std::string source_;
  const LogReadOptions& options_;
  std::uintmax_t max_numbers_;
  LogData log_;
  std::vector<std::string> names_;
  std::vector<std::string> skipped_;
  std::size_t skipped_count_ = 0;
};

}  // namespace

bool looksLikeMat(std::span<const std::byte> head) noexcept {
  static constexpr char kMagic[] = "MATLAB ";
  return head.size() >= 7 && std::memcmp(head.data(), kMagic, 7) == 0;
}

LogData readMat(const std::filesystem::path& file, const LogReadOptions& options) {
  const std::string source = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw LogError(source, std::filesystem::exists(file, ec)
                               ? "not a regular file (expected a .mat file)"
                               : "no such .mat file");
  }
  const auto bytes = std::filesystem::file_size(file, ec);
  if (ec) throw LogError(source, "cannot read the size of the .mat file: " + ec.message());
  if (bytes > options.max_bytes) {
    throw LogError(source,
                   std::to_string(bytes) + " bytes, larger than a log may be; refused unread");
  }
  noteInputFile(file, ".mat file");
  static const bool logging = [] {
    Mat_LogInitFunc("geaware", &matioLog);
    return true;
  }();
  (void)logging;
  g_matio_message.clear();
  const std::uintmax_t walked = detail::checkMatLayout(file, bytes, options.max_bytes);
  MatPtr mat(Mat_Open(source.c_str(), MAT_ACC_RDONLY));
  if (!mat) {
    std::string head(128, '\0');
    std::ifstream(file, std::ios::binary).read(head.data(), 128);
    const bool v73 = head.rfind("MATLAB 7.3", 0) == 0;
    throw LogError(
        source,
        std::string(v73 ? "a v7.3 (HDF5) .mat file libmatio could not open (a libmatio built "
                          "without HDF5 cannot read v7.3: save with -v7, or install a libmatio "
                          "with HDF5, as Debian's libmatio-dev is)"
                        : "not a MATLAB .mat file libmatio can open (v5, v7 or v7.3 expected)") +
            MatParser::why());
  }
  MatParser parser(
      source, options,
      walked > 0 ? std::min<std::uintmax_t>(walked, options.max_bytes / 8) : options.max_bytes / 8);
  parser.checkSizes(mat.get());
  return parser.run(mat.get());
}

}  // namespace geaware::io
