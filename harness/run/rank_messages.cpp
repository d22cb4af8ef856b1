#include "harness/run/rank_messages.hpp"

#include <charconv>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

namespace dabench {

namespace {

void put_u64(std::string& out, std::uint64_t value) {
  for (int b = 0; b < 8; ++b) out.push_back(static_cast<char>((value >> (8 * b)) & 0xffu));
}

std::uint64_t get_u64(std::string_view message, std::size_t& at) {
  if (message.size() - at < 8) throw std::runtime_error("rank message: truncated");
  std::uint64_t value = 0;
  for (int b = 0; b < 8; ++b) value |= static_cast<std::uint64_t>(static_cast<unsigned char>(message[at + b])) << (8 * b);
  at += 8;
  return value;
}

long long to_integer(const std::string& field) {
  long long value = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (error != std::errc() || end != field.data() + field.size()) {
    throw std::runtime_error(fmt::format("rank message: '{}' is not an integer", field));
  }
  return value;
}

std::vector<std::string> fields_of(std::string_view message, std::size_t at_least, const char* what) {
  std::vector<std::string> fields = unpack_fields(message);
  if (fields.size() < at_least) throw std::runtime_error(fmt::format("rank message: {} with {} fields", what, fields.size()));
  return fields;
}

}  // namespace

std::string pack_fields(const std::vector<std::string>& fields) {
  std::size_t bytes = 8;
  for (const std::string& field : fields) bytes += 8 + field.size();
  std::string out;
  out.reserve(bytes);
  put_u64(out, fields.size());
  for (const std::string& field : fields) {
    put_u64(out, field.size());
    out += field;
  }
  return out;
}

std::vector<std::string> unpack_fields(std::string_view message) {
  std::size_t at = 0;
  const std::uint64_t count = get_u64(message, at);
  if (count > message.size() / 8) throw std::runtime_error("rank message: bad field count");
  std::vector<std::string> fields;
  fields.reserve(count);
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::uint64_t size = get_u64(message, at);
    if (size > message.size() - at) throw std::runtime_error("rank message: truncated");
    fields.emplace_back(message.substr(at, size));
    at += size;
  }
  if (at != message.size()) throw std::runtime_error("rank message: trailing bytes");
  return fields;
}

std::string encode(const Hello& hello) {
  return pack_fields({hello.host, hello.fingerprint, std::to_string(hello.threads), hello.error});
}

std::string encode(const Start& start) { return pack_fields({start.error}); }

std::string encode(const ChunkResult& result) {
  std::vector<std::string> fields = {result.chunk ? std::to_string(result.chunk->begin) : "-1",
                                     result.chunk ? std::to_string(result.chunk->end) : "-1",
                                     result.interrupted ? "1" : "0", std::string(sizeof(double), '\0'),
                                     std::string(sizeof(double) * result.unit_seconds.size(), '\0')};
  // Doubles as their bytes: exact, and every rank is the same machine type.
  std::memcpy(fields[3].data(), &result.busy_seconds, sizeof(double));
  if (!result.unit_seconds.empty()) std::memcpy(fields[4].data(), result.unit_seconds.data(), fields[4].size());
  fields.insert(fields.end(), result.texts.begin(), result.texts.end());
  return pack_fields(fields);
}

std::string encode_chunk(const std::optional<WorkChunk>& chunk) {
  return chunk ? pack_fields({std::to_string(chunk->begin), std::to_string(chunk->end)}) : pack_fields({"-1", "-1"});
}

Hello decode_hello(std::string_view message) {
  const auto fields = fields_of(message, 4, "hello");
  return Hello{fields[0], fields[1], static_cast<int>(to_integer(fields[2])), fields[3]};
}

Start decode_start(std::string_view message) { return Start{fields_of(message, 1, "start")[0]}; }

namespace {
// A chunk's two fields: none for (-1, -1), else 0 <= begin < end.
std::optional<WorkChunk> chunk_of(const std::string& begin_field, const std::string& end_field) {
  const long long begin = to_integer(begin_field), end = to_integer(end_field);
  if (begin == -1 && end == -1) return std::nullopt;
  if (begin < 0 || end <= begin) throw std::runtime_error(fmt::format("rank message: bad chunk [{}, {})", begin, end));
  return WorkChunk{begin, end};
}
}  // namespace

ChunkResult decode_chunk_result(std::string_view message) {
  auto fields = fields_of(message, 5, "chunk result");
  ChunkResult result;
  result.chunk = chunk_of(fields[0], fields[1]);
  result.interrupted = fields[2] == "1";
  if (fields[3].size() != sizeof(double)) throw std::runtime_error("rank message: bad busy time");
  std::memcpy(&result.busy_seconds, fields[3].data(), sizeof(double));
  const std::size_t units = result.chunk ? static_cast<std::size_t>(result.chunk->end - result.chunk->begin) : 0;
  if (fields[4].size() != units * sizeof(double)) throw std::runtime_error("rank message: bad unit times");
  result.unit_seconds.resize(units);
  if (units > 0) std::memcpy(result.unit_seconds.data(), fields[4].data(), fields[4].size());
  result.texts.assign(std::make_move_iterator(fields.begin() + 5), std::make_move_iterator(fields.end()));
  return result;
}

std::optional<WorkChunk> decode_chunk(std::string_view message) {
  const auto fields = fields_of(message, 2, "chunk");
  return chunk_of(fields[0], fields[1]);
}

}  // namespace dabench
