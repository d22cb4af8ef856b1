#include "harness/core/ordered_writer.hpp"

#include <unistd.h>

#include <cerrno>
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
  if (ready == 0 || failure_) return next_block_;
  for (std::size_t f = 0; f < files_.size(); ++f) {
    std::FILE* file = files_[f];
    const long before = std::ftell(file);
    errno = 0;
    bool written = true;
    for (auto it = pending_.begin(); it != end && written; ++it) {
      const std::string& text = it->second[f];
      written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
    }
    written = written && std::fflush(file) == 0;
    if (!written) {
      failure_ = Failure{f, errno != 0 ? errno : EIO};
      // Whole blocks only: what part of this write reached the file is cut off again.
      if (before >= 0 && ftruncate(fileno(file), before) == 0) std::fseek(file, before, SEEK_SET);
      pending_.clear();
      return next_block_;
    }
  }
  pending_.erase(pending_.begin(), end);
  next_block_ += ready;
  return next_block_;
}

bool OrderedWriter::failed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failure_.has_value();
}

std::optional<OrderedWriter::Failure> OrderedWriter::failure() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failure_;
}

}  // namespace dabench
