#pragma once
// Appends pieces of rows to one or more files in order while the pieces finish in any order (a
// reorder buffer). A piece covers the positions [begin, end) of a sequence (the run's work units)
// and carries one text per file. Whenever pieces become ready (they continue the written
// prefix), each file in turn gets all of them (one fwrite per piece) and is flushed before the
// next file is written, so after a crash or Ctrl-C every file holds a prefix of whole pieces (its
// last line may be cut; --resume trims it) and an earlier file never holds fewer pieces than a
// later one. The first failed write (ENOSPC, EIO, EFBIG) cuts that file back to the pieces it
// held before (the files should be unbuffered, so nothing of the failed write waits in a stdio
// buffer) and ends all writing: failure() then names the file and the error.
#include <cstdio>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace dabench {

class OrderedWriter {
 public:
  // `files` stay owned by the caller; `next` is the first position still to be written.
  OrderedWriter(std::vector<std::FILE*> files, long long next) : files_(std::move(files)), next_(next) {}

  // Thread-safe; texts[k] goes to files[k]. Pieces must not overlap and must together cover the
  // positions from `next` on. Returns the end of the written prefix (earlier runs' included).
  long long submit(long long begin, long long end, std::vector<std::string>&& texts);
  long long next() const;

  struct Failure {
    std::size_t file = 0;  // index into `files`
    int error = 0;         // errno of the failed write or flush
  };
  bool failed() const;
  std::optional<Failure> failure() const;

 private:
  std::vector<std::FILE*> files_;
  long long next_;
  std::optional<Failure> failure_;
  struct Piece {
    long long end;
    std::vector<std::string> texts;
  };
  std::map<long long, Piece> pending_;  // by begin
  mutable std::mutex mutex_;
};

}  // namespace dabench
