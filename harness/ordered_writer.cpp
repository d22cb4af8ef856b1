#include "harness/ordered_writer.hpp"

namespace dabench {

long long OrderedWriter::submit(long long block, std::string&& rows) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.emplace(block, std::move(rows));
  bool wrote = false;
  for (auto it = pending_.begin(); it != pending_.end() && it->first == next_block_; it = pending_.erase(it)) {
    const std::string& text = it->second;
    if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) failed_ = true;
    ++next_block_;
    wrote = true;
  }
  if (wrote && std::fflush(file_) != 0) failed_ = true;
  return next_block_;
}

}  // namespace dabench
