#include "harness/core/ordered_writer.hpp"

#include <iterator>

namespace dabench {

long long OrderedWriter::submit(long long block, std::vector<std::string>&& texts) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.emplace(block, std::move(texts));
  // Blocks below next_block_ are written, so the ready ones are the map's first entries.
  auto end = pending_.begin();
  long long ready = 0;
  while (end != pending_.end() && end->first == next_block_ + ready) {
    ++end;
    ++ready;
  }
  if (ready == 0) return next_block_;
  for (std::size_t f = 0; f < files_.size(); ++f) {
    for (auto it = pending_.begin(); it != end; ++it) {
      const std::string& text = it->second[f];
      if (std::fwrite(text.data(), 1, text.size(), files_[f]) != text.size()) failed_ = true;
    }
    if (std::fflush(files_[f]) != 0) failed_ = true;
  }
  pending_.erase(pending_.begin(), end);
  next_block_ += ready;
  return next_block_;
}

}  // namespace dabench
