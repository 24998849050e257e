// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/io/input_file.hpp"

#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace geaware::io {

namespace {
std::mutex g_inputs_mutex;
std::vector<InputFileRead>& inputsRead() {
  static std::vector<InputFileRead> inputs;
  return inputs;
}
thread_local InputFileCollector* t_collector = nullptr;
}  // namespace

InputFileCollector::InputFileCollector() noexcept : outer_(t_collector) { t_collector = this; }

InputFileCollector::~InputFileCollector() { t_collector = outer_; }

void noteInputFile(const std::filesystem::path& file, std::string_view noun) {
  // Every collector of the thread, innermost first: an inner one's files are the outer ones' too
  // (recorded here, where an allocation may throw, not in a destructor).
  for (InputFileCollector* c = t_collector; c != nullptr; c = c->outer_) c->files_.push_back(file);
  const std::lock_guard<std::mutex> lock(g_inputs_mutex);
  for (const auto& in : inputsRead()) {
    if (in.path == file) return;
  }
  inputsRead().push_back({file, std::string(noun)});
}

std::vector<InputFileRead> inputFilesRead() {
  const std::lock_guard<std::mutex> lock(g_inputs_mutex);
  return inputsRead();
}

std::string readInputFile(const std::filesystem::path& file, std::string_view noun,
                          std::string_view kind) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw std::runtime_error(file.string() +
                             (std::filesystem::exists(file, ec)
                                  ? ": not a regular file (expected a " + std::string(kind) + ")"
                                  : ": no such " + std::string(noun)));
  }
  noteInputFile(file, noun);
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (!ec && size > kMaxInputFileBytes) {
    throw std::runtime_error(file.string() + ": " + std::to_string(size) + " bytes, larger than a " +
                             std::string(noun) + " can be (at most 64 MiB; expected a " + std::string(kind) + ")");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read " + std::string(noun));
  std::string text;
  std::size_t line = 1;
  std::size_t line_start = 0;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    const std::size_t from = text.size();
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    const auto tooLong = [&](std::size_t line_end) {
      if (line_end - line_start <= kMaxLineBytes) return;
      throw std::runtime_error(file.string() + ":" + std::to_string(line) + ": " +
                               lineTooLong(std::string_view(text).substr(line_start, line_end - line_start)));
    };
    for (std::size_t i = from; i < text.size(); ++i) {
      if (text[i] != '\n') continue;
      tooLong(i);
      ++line;
      line_start = i + 1;
    }
    tooLong(text.size());
  }
  if (in.bad()) throw std::runtime_error(file.string() + ": cannot read " + std::string(noun));
  return text;
}

std::string lineTooLong(std::string_view start) {
  constexpr std::size_t kEcho = 80;
  std::string echo;
  for (const char c : start.substr(0, kEcho)) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      echo += c;
    } else {
      constexpr char kHex[] = "0123456789abcdef";
      echo += "\\x";
      echo += kHex[u >> 4];
      echo += kHex[u & 0xf];
    }
  }
  return "line longer than 1 MiB (starts '" + echo +
         (start.size() > kEcho ? "…" : "") + "'); expected a text file with shorter lines";
}

}  // namespace geaware::io
