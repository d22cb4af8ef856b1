#pragma once
// Appends blocks of rows to a file in block order while blocks finish in any order (a reorder
// buffer). Each flushed block is written with one fwrite and flushed, so after a crash or
// Ctrl-C the file holds a prefix of whole blocks (the last line may be cut; --resume trims it).
#include <cstdio>
#include <map>
#include <mutex>
#include <string>

namespace dabench {

class OrderedWriter {
 public:
  // `file` stays owned by the caller; `next_block` is the first block still to be written.
  OrderedWriter(std::FILE* file, long long next_block) : file_(file), next_block_(next_block) {}

  // Thread-safe. Returns the number of blocks written so far (including earlier runs' offset).
  long long submit(long long block, std::string&& rows);
  long long next_block() const { return next_block_; }
  bool failed() const { return failed_; }

 private:
  std::FILE* file_;
  long long next_block_;
  bool failed_ = false;
  std::map<long long, std::string> pending_;
  std::mutex mutex_;
};

}  // namespace dabench
