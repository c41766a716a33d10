#include "engine/progress.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace rift {

namespace {
std::string format_seconds(double s) {
  if (!(s >= 0) || s > 1e7) return "--";
  const int total = static_cast<int>(s + 0.5);
  if (total >= 3600) return fmt::format("{}h{:02d}m", total / 3600, total / 60 % 60);
  if (total >= 60) return fmt::format("{}m{:02d}s", total / 60, total % 60);
  return fmt::format("{}s", total);
}
}  // namespace

Progress::Progress(int64_t total_steps, double end_time, bool enabled)
    : total_(total_steps), end_time_(end_time), enabled_(enabled) {
  tty_ = isatty(STDERR_FILENO) && std::getenv("CI") == nullptr;
  min_interval_ = tty_ ? 0.25 : 10.0;
  start_ = last_ = std::chrono::steady_clock::now();
}

void Progress::update(int64_t step, double time, const std::string& extra) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (start_step_ < 0) start_step_ = step, start_ = now;
  if (std::chrono::duration<double>(now - last_).count() < min_interval_ && step < total_) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? (step - start_step_) / elapsed : 0.0;
  const double eta = rate > 0 ? (total_ - step) / rate : -1.0;
  const std::string line =
      fmt::format("step {}/{}  t = {:.4e} s  {:5.1f}%  {:.1f} steps/s  ETA {}{}", step, total_, time,
                  100.0 * time / end_time_, rate, format_seconds(eta), extra.empty() ? "" : "  " + extra);
  if (tty_) {
    std::fprintf(stderr, "\r\033[K%s", line.c_str());
    std::fflush(stderr);
    drawn_ = true;
  } else {
    spdlog::info("{}", line);
  }
}

void Progress::finish() {
  if (drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

}  // namespace rift
