#include "harness/core/input_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/core/utf8.hpp"

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

std::string printable_line(std::string_view text, std::size_t max_bytes) {
  const std::string line = printable(text);
  if (line.size() <= max_bytes) return line;
  const auto continuation = [&line](std::size_t at) { return (static_cast<unsigned char>(line[at]) & 0xC0) == 0x80; };
  std::size_t head = max_bytes / 2 - 3, tail = line.size() - (max_bytes / 2 - 3);
  while (head > 0 && continuation(head)) --head;  // cut between characters, never inside one
  while (tail < line.size() && continuation(tail)) ++tail;
  return line.substr(0, head) + " ... " + line.substr(tail);
}

}  // namespace dabench
