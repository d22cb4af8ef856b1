#pragma once
// Appends blocks of rows to one or more files in block order while blocks finish in any order
// (a reorder buffer). A block carries one text per file. Whenever blocks become ready, each
// file in turn gets all of them (one fwrite per block) and is flushed before the next file is
// written, so after a crash or Ctrl-C every file holds a prefix of whole blocks (its last line
// may be cut; --resume trims it) and an earlier file never holds fewer blocks than a later one.
#include <cstdio>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace dabench {

class OrderedWriter {
 public:
  // `files` stay owned by the caller; `next_block` is the first block still to be written.
  OrderedWriter(std::vector<std::FILE*> files, long long next_block) : files_(std::move(files)), next_block_(next_block) {}

  // Thread-safe; texts[k] goes to files[k]. Returns the number of blocks written so far
  // (including earlier runs' offset).
  long long submit(long long block, std::vector<std::string>&& texts);
  long long next_block() const { return next_block_; }
  bool failed() const { return failed_; }

 private:
  std::vector<std::FILE*> files_;
  long long next_block_;
  bool failed_ = false;
  std::map<long long, std::vector<std::string>> pending_;
  std::mutex mutex_;
};

}  // namespace dabench
