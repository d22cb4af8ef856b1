#include "harness/core/input_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

namespace fs = std::filesystem;

void check_input_file(const std::string& path, std::string_view what, std::uintmax_t max_bytes) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error || !fs::exists(status)) throw InputError(fmt::format("{}: cannot read {} (no such file)", path, what));
  if (fs::is_directory(status)) throw InputError(fmt::format("{}: is a folder, not {}", path, what));
  if (!fs::is_regular_file(status)) {
    throw InputError(fmt::format("{}: not a regular file (a device, pipe or socket); {} must be a file", path, what));
  }
  const std::uintmax_t size = fs::file_size(path, error);
  if (error) throw InputError(fmt::format("{}: cannot read {} ({})", path, what, error.message()));
  if (size > max_bytes) {
    throw InputError(fmt::format("{}: {} bytes; {} must be at most {} bytes", path, size, what, max_bytes));
  }
}

std::string read_input_file(const std::string& path, std::string_view what, std::uintmax_t max_bytes) {
  check_input_file(path, what, max_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read {}", path, what));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  std::string text = std::move(buffer).str();
  if (in.bad() || text.size() > max_bytes) throw InputError(fmt::format("{}: cannot read {} (changed while read?)", path, what));
  return text;
}

namespace {

// Length of the well-formed UTF-8 sequence at text[at] (RFC 3629: no overlongs, no surrogates,
// at most U+10FFFF), or 0.
std::size_t utf8_length(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[at + k]); };
  const unsigned char lead = byte(0);
  const std::size_t length = lead >= 0xC2 && lead <= 0xDF ? 2 : lead >= 0xE0 && lead <= 0xEF ? 3
                             : lead >= 0xF0 && lead <= 0xF4 ? 4 : 0;
  if (length == 0) return 0;
  // The second byte's range (the rest are 0x80..0xBF): E0 and F0 exclude overlongs, ED the
  // surrogates, F4 what lies beyond U+10FFFF.
  const unsigned char low = lead == 0xE0 ? 0xA0 : lead == 0xF0 ? 0x90 : 0x80;
  const unsigned char high = lead == 0xED ? 0x9F : lead == 0xF4 ? 0x8F : 0xBF;
  if (at + length > text.size()) return 0;
  if (byte(1) < low || byte(1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k) {
    if (byte(k) < 0x80 || byte(k) > 0xBF) return 0;
  }
  return length;
}

}  // namespace

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    const auto c = static_cast<unsigned char>(text[at]);
    if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
      ++at;
      continue;
    }
    const std::size_t length = c >= 0x80 ? utf8_length(text, at) : 0;
    if (length > 0) {
      out.append(text.substr(at, length));
      at += length;
      continue;
    }
    out += fmt::format("\\x{:02X}", c);
    ++at;
  }
  return out;
}

}  // namespace dabench
