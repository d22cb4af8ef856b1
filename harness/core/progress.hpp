#pragma once
// A one-line progress display on stderr ("\r 1200/6000 trials  20% | 850/s | ETA 0:05"),
// drawn only when stderr is a terminal and at most a few times per second. Any thread may call
// update(): one draws at a time (a thread that finds the line busy skips its draw).
#include <chrono>
#include <mutex>
#include <string>

namespace dabench {

class ProgressLine {
 public:
  ProgressLine(long long total, long long already_done, bool enabled);
  void update(long long done);  // call with the number of finished items (cheap when throttled)
  void finish();                // clears the line (after the threads that update it have stopped)

 private:
  using Clock = std::chrono::steady_clock;
  long long total_;
  long long start_done_;
  bool enabled_;
  Clock::time_point start_;
  Clock::time_point last_draw_;
  std::size_t last_width_ = 0;
  std::mutex drawing_;  // guards last_draw_, last_width_ and the terminal line
};

bool stderr_is_terminal();
std::string format_duration(double seconds);  // "1:02:03" / "2:03"

}  // namespace dabench
