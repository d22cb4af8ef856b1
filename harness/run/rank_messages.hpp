#pragma once
// The messages between the ranks of an Open MPI run (harness/run/runner.cpp): each a list of
// byte fields, sent as one MPI message (field count, then each field's length and bytes, as
// 8-byte little-endian integers). The exchange:
//   worker → rank 0, tag kHelloTag: a Hello, once, after reading the experiment;
//   rank 0 → worker, tag kStartTag: a Start, once, after opening the output folder;
//   worker thread t → rank 0, tag t: a BlockResult, both a request for a block and the rows of
//     the block it finished (if any); each thread keeps two requests in flight;
//   rank 0 → worker thread t, tag t: the block to run next (kNoBlock: stop), one per request.
#include <string>
#include <string_view>
#include <vector>

namespace dabench {

constexpr int kHelloTag = 30000;  // above every thread tag (threads ≤ 1024), below MPI's 32767 minimum
constexpr int kStartTag = 30001;
constexpr long long kNoBlock = -1;

std::string pack_fields(const std::vector<std::string>& fields);
std::vector<std::string> unpack_fields(std::string_view message);  // throws std::runtime_error if malformed

struct Hello {
  std::string host;
  std::string fingerprint;  // of the worker's plan; must equal rank 0's
  int threads = 1;
  std::string error;        // the worker's InputError reading the experiment, or ""
};

struct Start {
  std::string error;        // rank 0's InputError (workers then stop), or ""
  long long first_block = 0;
  long long skip_in_first = 0;  // items of first_block already written (--resume)
};

struct BlockResult {
  long long block = kNoBlock;  // the block these texts belong to; kNoBlock: only a request
  bool interrupted = false;    // the sender was interrupted (SIGINT/SIGTERM)
  double busy_seconds = 0.0;   // the sending thread's busy time so far
  std::vector<std::string> texts;  // one per output file
};

std::string encode(const Hello& hello);
std::string encode(const Start& start);
std::string encode(const BlockResult& result);
std::string encode_block(long long block);
Hello decode_hello(std::string_view message);
Start decode_start(std::string_view message);
BlockResult decode_block_result(std::string_view message);
long long decode_block(std::string_view message);

}  // namespace dabench
