#pragma once
// Appends blocks of rows to one or more files in block order while blocks finish in any order
// (a reorder buffer). A block carries one text per file. Whenever blocks become ready, each
// file in turn gets all of them (one fwrite per block) and is flushed before the next file is
// written, so after a crash or Ctrl-C every file holds a prefix of whole blocks (its last line
// may be cut; --resume trims it) and an earlier file never holds fewer blocks than a later one.
// The first failed write (ENOSPC, EIO, EFBIG) cuts that file back to the blocks it held before
// (the files should be unbuffered, so nothing of the failed write waits in a stdio buffer) and
// ends all writing: failure() then names the file and the error.
#include <cstdio>
#include <map>
#include <mutex>
#include <optional>
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

  struct Failure {
    std::size_t file = 0;  // index into `files`
    int error = 0;         // errno of the failed write or flush
  };
  bool failed() const;
  std::optional<Failure> failure() const;

 private:
  std::vector<std::FILE*> files_;
  long long next_block_;
  std::optional<Failure> failure_;
  std::map<long long, std::vector<std::string>> pending_;
  mutable std::mutex mutex_;
};

}  // namespace dabench
