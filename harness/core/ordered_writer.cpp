#include "harness/core/ordered_writer.hpp"

#include <unistd.h>

#include <cerrno>
#include <iterator>

namespace dabench {

long long OrderedWriter::submit(long long begin, long long end, std::vector<std::string>&& texts) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.emplace(begin, Piece{end, std::move(texts)});
  // Positions below next_ are written, so the ready pieces are the map's first entries.
  auto last = pending_.begin();
  long long ready_end = next_;
  while (last != pending_.end() && last->first == ready_end) {
    ready_end = last->second.end;
    ++last;
  }
  if (ready_end == next_ || failure_) return next_;
  for (std::size_t f = 0; f < files_.size(); ++f) {
    std::FILE* file = files_[f];
    const long before = std::ftell(file);
    errno = 0;
    bool written = true;
    for (auto it = pending_.begin(); it != last && written; ++it) {
      const std::string& text = it->second.texts[f];
      written = std::fwrite(text.data(), 1, text.size(), file) == text.size();
    }
    written = written && std::fflush(file) == 0;
    if (!written) {
      failure_ = Failure{f, errno != 0 ? errno : EIO};
      // Whole pieces only: what part of this write reached the file is cut off again.
      if (before >= 0 && ftruncate(fileno(file), before) == 0) std::fseek(file, before, SEEK_SET);
      pending_.clear();
      return next_;
    }
  }
  pending_.erase(pending_.begin(), last);
  next_ = ready_end;
  return next_;
}

long long OrderedWriter::next() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_;
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
