#include "harness/core/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace dabench {

bool stderr_is_terminal() { return isatty(STDERR_FILENO) != 0; }

std::string format_duration(double seconds) {
  const long long total = static_cast<long long>(seconds + 0.5);
  const long long h = total / 3600, m = (total / 60) % 60, s = total % 60;
  return h > 0 ? fmt::format("{}:{:02}:{:02}", h, m, s) : fmt::format("{}:{:02}", m, s);
}

ProgressLine::ProgressLine(long long total, long long already_done, bool enabled)
    : total_(total), start_done_(already_done), enabled_(enabled), start_(Clock::now()), last_draw_(start_) {}

void ProgressLine::update(long long done) {
  if (!enabled_) return;
  const std::unique_lock<std::mutex> lock(drawing_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // another thread is drawing this moment
  const auto now = Clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(200) && done < total_) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0.0 ? static_cast<double>(done - start_done_) / elapsed : 0.0;
  const double fraction = total_ > 0 ? static_cast<double>(done) / static_cast<double>(total_) : 1.0;
  constexpr int kBar = 24;
  const int filled = static_cast<int>(fraction * kBar);
  const std::string eta = rate > 0.0 ? format_duration(static_cast<double>(total_ - done) / rate) : "?";
  const std::string text = fmt::format("\r[{}{}] {}/{} trials {:3.0f}% | {:.0f}/s | ETA {}", std::string(filled, '#'),
                                       std::string(kBar - filled, '.'), done, total_, 100.0 * fraction, rate, eta);
  last_width_ = std::max(last_width_, text.size());
  std::fputs(text.c_str(), stderr);
  std::fflush(stderr);
}

void ProgressLine::finish() {
  if (!enabled_ || last_width_ == 0) return;
  std::string blank(last_width_ + 1, ' ');
  blank.front() = '\r';
  blank.back() = '\r';
  std::fputs(blank.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace dabench
