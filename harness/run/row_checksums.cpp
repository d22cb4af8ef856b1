#include "harness/run/row_checksums.hpp"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

std::uint32_t row_checksum(std::string_view row) {
  std::uint32_t hash = 2166136261u;  // FNV-1a, 32 bits
  for (const char c : row) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 16777619u;
  }
  return hash;
}

namespace {

void append_checksum(std::string& out, std::string_view row) {
  char text[9];
  fmt::format_to(text, "{:08x}", row_checksum(row));
  out.append(text, 8);
}

}  // namespace

void append_checksum_lines(std::string& out, const std::vector<std::string>& names, const std::vector<std::string>& texts) {
  for (std::size_t k = 0; k < texts.size(); ++k) {
    const std::string_view text = texts[k];
    if (text.empty()) continue;
    out += names[k];
    char separator = ',';
    for (std::size_t at = 0; at < text.size();) {
      const std::size_t end = text.find('\n', at);
      out += separator;
      separator = ' ';
      append_checksum(out, text.substr(at, end - at));
      at = end + 1;
    }
    out += '\n';
  }
}

RecordedChecksums::RecordedChecksums(const std::string& checksums_path, std::string file_name)
    : path_(checksums_path), name_(std::move(file_name)), in_(checksums_path, std::ios::binary) {
  std::string header;
  if (!in_ || !std::getline(in_, header) || header + "\n" != kChecksumsHeader) {
    throw InputError(fmt::format("{}: missing or not a dabench checksums file, so the rows beside it cannot be verified",
                                 path_));
  }
}

std::optional<std::uint32_t> RecordedChecksums::next() {
  while (at_ == std::string::npos) {
    // A last line cut short (a kill while it was written) records nothing.
    if (!std::getline(in_, line_) || in_.eof()) return std::nullopt;
    ++line_number_;
    const std::size_t comma = line_.find(',');
    if (comma == std::string::npos || comma + 1 == line_.size()) {
      throw InputError(fmt::format("{}:{}: malformed line (not FILE,CHECKSUMS)", path_, line_number_));
    }
    if (std::string_view(line_).substr(0, comma) == name_) at_ = comma + 1;
  }
  const std::size_t end = std::min(line_.find(' ', at_), line_.size());
  std::uint32_t value = 0;
  const char* first = line_.data() + at_;
  const char* last = line_.data() + end;
  const auto [stop, error] = std::from_chars(first, last, value, 16);
  if (end - at_ != 8 || error != std::errc() || stop != last) {
    throw InputError(fmt::format("{}:{}: malformed checksum '{}'", path_, line_number_, line_.substr(at_, end - at_)));
  }
  at_ = end < line_.size() ? end + 1 : std::string::npos;
  return value;
}

VerifiedRows verify_rows(const std::string& path, std::size_t header_bytes, RecordedChecksums& recorded,
                         const std::function<void(long long, std::string_view, std::uintmax_t)>& on_row) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read ({})", path, std::strerror(errno)));
  in.seekg(static_cast<std::streamoff>(header_bytes));
  VerifiedRows verified;
  std::uintmax_t offset = header_bytes;
  std::string row;
  while (true) {
    const std::optional<std::uint32_t> expected = recorded.next();
    if (!expected) return verified;  // the rows after the recorded ones are unverified
    const long long line = verified.rows + 2;  // after the one-line header
    if (!std::getline(in, row) || in.eof()) {
      throw InputError(fmt::format("{}:{}: missing: checksums.csv records more rows than the file holds whole "
                                   "(rows were deleted or the file cut)", path, line));
    }
    if (row_checksum(row) != *expected) {
      throw InputError(fmt::format("{}:{}: not the row written there (its checksum differs from checksums.csv: "
                                   "edited, cut short, or a row deleted before it)", path, line));
    }
    on_row(verified.rows, row, offset);
    ++verified.rows;
    offset += row.size() + 1;
  }
}

void ChecksumLineWriter::add(std::string_view row) {
  line_ += count_ == 0 ? name_ + "," : std::string(" ");
  append_checksum(line_, row);
  if (++count_ == kPerLine) flush();
}

int ChecksumLineWriter::flush() {
  if (count_ > 0 && reason_ == 0) {
    line_ += '\n';
    if (std::fwrite(line_.data(), 1, line_.size(), out_) != line_.size()) reason_ = errno != 0 ? errno : EIO;
  }
  line_.clear();
  count_ = 0;
  return reason_;
}

void rewrite_checksums(const std::string& folder, const std::vector<std::string>& names,
                       const std::vector<std::size_t>& header_bytes, const std::vector<long long>& rows) {
  const std::filesystem::path target = std::filesystem::path(folder) / kChecksumsFile;
  const std::string temporary = fmt::format("{}.tmp.{}", target.string(), getpid());
  std::FILE* out = std::fopen(temporary.c_str(), "wb");
  if (out == nullptr) throw WriteError(fmt::format("{}: cannot write ({})", target.string(), std::strerror(errno)));
  int reason = std::fputs(kChecksumsHeader, out) >= 0 ? 0 : (errno != 0 ? errno : EIO);
  for (std::size_t k = 0; k < names.size() && reason == 0; ++k) {
    std::ifstream in((std::filesystem::path(folder) / names[k]).string(), std::ios::binary);
    in.seekg(static_cast<std::streamoff>(header_bytes[k]));
    ChecksumLineWriter lines(out, names[k]);
    std::string row;
    for (long long r = 0; r < rows[k]; ++r) {
      if (!std::getline(in, row)) {
        std::fclose(out);
        std::filesystem::remove(temporary);
        throw InputError(fmt::format("{}: changed while being read", names[k]));
      }
      lines.add(row);
    }
    reason = lines.flush();
  }
  if (std::fclose(out) != 0 && reason == 0) reason = errno != 0 ? errno : EIO;
  std::error_code error;
  std::string message = reason != 0 ? fmt::format("write failed ({})", std::strerror(reason)) : "";
  if (reason == 0) {
    std::filesystem::rename(temporary, target, error);
    if (!error) return;
    message = fmt::format("cannot replace file ({})", error.message());
  }
  std::filesystem::remove(temporary, error);
  throw WriteError(fmt::format("{}: {}", target.string(), message));
}

}  // namespace dabench
