#include "harness/core/spill_sort.hpp"

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <queue>

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench {

namespace {

// Doubles as unsigned integers in the order of their values (sign-magnitude to offset binary).
std::uint64_t ordered_bits(double value) {
  const auto bits = std::bit_cast<std::uint64_t>(value);
  return (bits >> 63) != 0 ? ~bits : bits | (std::uint64_t{1} << 63);
}

bool before(const SpillSort::Record& a, const SpillSort::Record& b) {
  if (a.slot != b.slot) return a.slot < b.slot;
  return ordered_bits(a.value) < ordered_bits(b.value);
}

// One sorted run, read back in blocks.
class RunReader {
 public:
  explicit RunReader(std::FILE* file) : file_(file), block_(kBlock) { std::rewind(file_); }
  bool next(SpillSort::Record& record) {
    if (at_ == size_) {
      size_ = std::fread(block_.data(), sizeof(SpillSort::Record), block_.size(), file_);
      at_ = 0;
      if (size_ == 0 && std::ferror(file_)) throw WriteError("a temporary file of the sort cannot be read back");
      if (size_ == 0) return false;
    }
    record = block_[at_++];
    return true;
  }

 private:
  static constexpr std::size_t kBlock = 4096;  // records: 64 KiB
  std::FILE* file_;
  std::vector<SpillSort::Record> block_;
  std::size_t at_ = 0, size_ = 0;
};

}  // namespace

SpillSort::SpillSort(std::string folder, std::size_t buffer_records)
    : folder_(std::move(folder)), buffer_records_(std::max<std::size_t>(buffer_records, 1)) {}

SpillSort::~SpillSort() {
  for (std::FILE* run : runs_) std::fclose(run);
}

void SpillSort::add(std::uint32_t slot, double value) {
  buffer_.push_back({slot, value});
  if (buffer_.size() == buffer_records_) spill();
}

void SpillSort::spill() {
  std::sort(buffer_.begin(), buffer_.end(), before);
  std::string pattern = (std::filesystem::path(folder_) / ".dabench-sort-XXXXXX").string();
  const int fd = mkstemp(pattern.data());
  std::FILE* file = fd >= 0 ? fdopen(fd, "w+b") : nullptr;
  if (file == nullptr) {
    const int reason = errno;
    if (fd >= 0) close(fd);
    throw WriteError(fmt::format("{}: cannot create a temporary file to sort in ({})", folder_, std::strerror(reason)));
  }
  unlink(pattern.c_str());  // the data stays reachable through `file` only
  runs_.push_back(file);
  if (std::fwrite(buffer_.data(), sizeof(Record), buffer_.size(), file) != buffer_.size() || std::fflush(file) != 0) {
    throw WriteError(fmt::format("{}: write failed while sorting ({})", folder_, std::strerror(errno)));
  }
  buffer_.clear();
}

void SpillSort::for_each_sorted(const std::function<void(const Record&)>& visit) {
  if (runs_.empty()) {  // everything fitted in memory
    std::sort(buffer_.begin(), buffer_.end(), before);
    for (const Record& record : buffer_) visit(record);
    buffer_.clear();
    return;
  }
  if (!buffer_.empty()) spill();
  buffer_.shrink_to_fit();
  std::vector<RunReader> readers;
  readers.reserve(runs_.size());
  for (std::FILE* run : runs_) readers.emplace_back(run);
  struct Head {
    Record record;
    std::size_t run;
  };
  const auto later = [](const Head& a, const Head& b) { return before(b.record, a.record); };
  std::priority_queue<Head, std::vector<Head>, decltype(later)> heads(later);
  for (std::size_t k = 0; k < readers.size(); ++k) {
    Record record{};
    if (readers[k].next(record)) heads.push({record, k});
  }
  while (!heads.empty()) {
    const Head head = heads.top();
    heads.pop();
    visit(head.record);
    Record record{};
    if (readers[head.run].next(record)) heads.push({record, head.run});
  }
}

}  // namespace dabench
