#pragma once
// The messages between the ranks of an Open MPI run (harness/run/runner.cpp): each a list of
// byte fields, sent as one MPI message (field count, then each field's length and bytes, as
// 8-byte little-endian integers). The exchange:
//   worker → rank 0, tag kHelloTag: a Hello, once, after reading the experiment;
//   rank 0 → worker, tag kStartTag: a Start, once, after opening the output folder;
//   worker thread t → rank 0, tag t: a ChunkResult, both a request for a chunk of work units and
//     the rows and unit times of the chunk it finished (if any); each thread keeps two requests
//     in flight;
//   rank 0 → worker thread t, tag t: the chunk to run next (none: stop), one per request.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "harness/run/work_queue.hpp"

namespace dabench {

constexpr int kHelloTag = 30000;  // above every thread tag (threads ≤ 1024), below MPI's 32767 minimum
constexpr int kStartTag = 30001;

std::string pack_fields(const std::vector<std::string>& fields);
std::vector<std::string> unpack_fields(std::string_view message);  // throws std::runtime_error if malformed

struct Hello {
  std::string host;
  std::string fingerprint;  // of the worker's plan; must equal rank 0's
  int threads = 1;
  std::string error;        // the worker's InputError reading the experiment, or ""
};

struct Start {
  std::string error;  // rank 0's InputError (workers then stop), or ""
};

struct ChunkResult {
  std::optional<WorkChunk> chunk;  // the units these texts belong to; none: only a request
  bool interrupted = false;        // the sender was interrupted (SIGINT/SIGTERM)
  double busy_seconds = 0.0;       // the sending thread's busy time so far
  std::vector<double> unit_seconds;  // each unit's time, in order
  std::vector<std::string> texts;    // one per output file
};

std::string encode(const Hello& hello);
std::string encode(const Start& start);
std::string encode(const ChunkResult& result);
std::string encode_chunk(const std::optional<WorkChunk>& chunk);
Hello decode_hello(std::string_view message);
Start decode_start(std::string_view message);
ChunkResult decode_chunk_result(std::string_view message);
std::optional<WorkChunk> decode_chunk(std::string_view message);

}  // namespace dabench
