#pragma once
// checksums.csv of a run folder: a 32-bit FNV-1a checksum of every row dabench wrote to
// trials.csv and the kind's per-item files, so that `--resume` and `merge` find a row that was
// edited, cut short or deleted by hand before they use it, and name it.
//
// Its lines are `FILE,C1 C2 ...` (hexadecimal, one per row of FILE, in order after FILE's
// header). The runner writes one line per file and block of rows, after the block's rows are
// flushed to their files, so a row is recorded only once it is whole; rows written just before
// a kill may be unrecorded (--resume drops and recomputes them). A last line cut short is
// ignored; any other malformed line is an error.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dabench {

inline constexpr const char* kChecksumsFile = "checksums.csv";
inline constexpr const char* kChecksumsHeader = "file,row_checksums\n";

std::uint32_t row_checksum(std::string_view row);  // of the row without its newline

// Appends to `out` a line per non-empty text (whole rows, each ending in '\n'): names[k] and the
// checksums of texts[k]'s rows.
void append_checksum_lines(std::string& out, const std::vector<std::string>& names, const std::vector<std::string>& texts);

// The checksums recorded for one file, in order, read line by line from checksums.csv.
class RecordedChecksums {
 public:
  // InputError when checksums.csv is missing or its header is not kChecksumsHeader.
  RecordedChecksums(const std::string& checksums_path, std::string file_name);
  std::optional<std::uint32_t> next();  // none after the last; InputError for a malformed line

 private:
  std::string path_, name_;
  std::ifstream in_;
  std::string line_;
  long long line_number_ = 1;
  std::size_t at_ = std::string::npos;  // in line_, of the next checksum; npos: read the next line
};

struct VerifiedRows {
  long long rows = 0;  // the rows whose checksums match, from the first on
};

// Reads `path`'s rows after its first `header_bytes` bytes and compares each with the next
// recorded checksum, calling on_row(index, row, byte offset of the row) for each matching row.
// InputError naming the file and line of the first row that differs, or of the first missing
// row when the file holds fewer complete rows than are recorded. Rows after the recorded ones
// are left unverified (not counted in `rows`).
VerifiedRows verify_rows(const std::string& path, std::size_t header_bytes, RecordedChecksums& recorded,
                         const std::function<void(long long, std::string_view, std::uintmax_t)>& on_row);

// Appends one file's row checksums to an open checksums.csv, 512 to a line (merge, and
// rewrite_checksums). flush() ends the last line and returns the errno of the first failed
// write, 0 if none.
class ChecksumLineWriter {
 public:
  ChecksumLineWriter(std::FILE* out, std::string name) : out_(out), name_(std::move(name)) {}
  void add(std::string_view row);
  int flush();

 private:
  static constexpr int kPerLine = 512;
  std::FILE* out_;
  std::string name_, line_;
  int count_ = 0, reason_ = 0;
};

// Writes `folder`/checksums.csv afresh (whole or not at all) for the first rows[k] rows of each
// file names[k] there (their checksums computed from the files).
void rewrite_checksums(const std::string& folder, const std::vector<std::string>& names,
                       const std::vector<std::size_t>& header_bytes, const std::vector<long long>& rows);

}  // namespace dabench
