#pragma once
// The progress line: step, simulated time, % done, steps/s, ETA. Rate-limited. On a terminal (and
// CI unset) it redraws one line in place; otherwise it logs a plain line every `log_every` seconds
// so CI logs stay line-oriented.
#include <chrono>
#include <cstdint>
#include <string>

namespace rift {

class Progress {
 public:
  Progress(int64_t total_steps, double end_time, bool enabled);
  void update(int64_t step, double time, const std::string& extra = "");
  void finish();

 private:
  int64_t total_;
  double end_time_;
  bool enabled_, tty_;
  double min_interval_;
  std::chrono::steady_clock::time_point start_, last_;
  int64_t start_step_ = -1;
  bool drawn_ = false;
};

}  // namespace rift
