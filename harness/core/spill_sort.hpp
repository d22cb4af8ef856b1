#pragma once
// Sorting more (slot, value) records than should be held in memory: up to `buffer_records` are
// kept in memory; beyond that each full buffer is sorted and written as a run to an unlinked
// temporary file in `folder` (gone when closed, even after a kill), and the runs are merged.
// Memory: buffer_records × 16 bytes, plus 64 KiB per run while merging.
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace dabench {

class SpillSort {
 public:
  struct Record {
    std::uint32_t slot;
    double value;
  };

  SpillSort(std::string folder, std::size_t buffer_records);
  ~SpillSort();
  SpillSort(const SpillSort&) = delete;
  SpillSort& operator=(const SpillSort&) = delete;

  void add(std::uint32_t slot, double value);  // WriteError when a run cannot be written
  // Calls visit for every record, in order of slot, then value (a total order: -0 before +0,
  // NaNs last). Once only.
  void for_each_sorted(const std::function<void(const Record&)>& visit);
  std::size_t runs() const { return runs_.size(); }  // files written so far

 private:
  void spill();
  std::string folder_;
  std::size_t buffer_records_;
  std::vector<Record> buffer_;
  std::vector<std::FILE*> runs_;
};

}  // namespace dabench
