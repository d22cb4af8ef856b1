#pragma once
// Reading a user's input file (an experiment, a weights matrix, a shard's meta.json) whole, and
// quoting user text in a one-line message. An input must be a regular file of bounded size: a
// character device (/dev/zero), a FIFO or a folder never reaches a parser, so nothing waits on
// an endless stream; a message escapes control bytes and malformed UTF-8 (\xNN), so an error
// that quotes a binary file cannot drive the terminal.
#include <cstdint>
#include <string>
#include <string_view>

namespace dabench {

constexpr std::uintmax_t kMaxExperimentBytes = std::uintmax_t{1} << 20;  // 1 MiB of INI text
constexpr std::uintmax_t kMaxWeightsBytes = std::uintmax_t{1} << 30;     // 1 GiB of CSV (~10^8 weights)
constexpr std::uintmax_t kMaxMetaBytes = std::uintmax_t{16} << 20;       // 16 MiB of meta.json

// Throws InputError naming `path` and `what` ("experiment file", ...) unless it is a readable
// regular file of at most max_bytes.
void check_input_file(const std::string& path, std::string_view what, std::uintmax_t max_bytes);
// check_input_file, then the file's bytes.
std::string read_input_file(const std::string& path, std::string_view what, std::uintmax_t max_bytes);

// `text` with control bytes (C0, DEL) and bytes outside well-formed UTF-8 written as \xNN;
// valid UTF-8 (γ, é) is kept.
std::string printable(std::string_view text);

// printable(text), and when that is longer than `max_bytes` its first and last parts joined by
// " ... " (a 4 KiB path keeps its start and the system's reason at the end of the message).
std::string printable_line(std::string_view text, std::size_t max_bytes = 600);

}  // namespace dabench
