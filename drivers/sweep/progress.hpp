// SPDX-License-Identifier: BSD-3-Clause
// The sweep's progress line (samples done, rate, time left), on standard error: redrawn in
// place on a terminal, else one line per tenth of the sweep or per minute, for logs.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace gencoord::sweep {

/// "2 min 5 s", "41 s", "0.3 s".
inline std::string duration_text(double seconds) {
  char text[64];
  if (seconds < 10) std::snprintf(text, sizeof text, "%.1f s", seconds);
  else if (seconds < 120) std::snprintf(text, sizeof text, "%.0f s", seconds);
  else if (seconds < 7200)
    std::snprintf(text, sizeof text, "%d min %d s", static_cast<int>(seconds / 60),
                  static_cast<int>(seconds) % 60);
  else
    std::snprintf(text, sizeof text, "%d h %d min", static_cast<int>(seconds / 3600),
                  static_cast<int>(seconds / 60) % 60);
  return text;
}

class Progress {
 public:
  using Clock = std::chrono::steady_clock;

  /// `total` samples, of which `done_before` were complete when this run started.
  Progress(long long total, long long done_before)
      : total_(total), before_(done_before), terminal_(isatty(STDERR_FILENO) == 1) {}

  void add(long long samples) { now_ += samples; }
  long long samples_this_run() const { return now_; }
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  /// Prints the line when it is due (or `force`) and has news.
  void show(bool force = false) {
    const auto now = Clock::now();
    const long long done = before_ + now_;
    const int tenth = total_ > 0 ? static_cast<int>(10 * done / total_) : 10;
    const bool due = terminal_ ? now - shown_ > std::chrono::milliseconds(500)
                               : tenth > tenth_shown_ || now - shown_ > std::chrono::minutes(1);
    if ((!force && !due) || done == done_shown_) return;
    shown_ = now;
    done_shown_ = done;
    tenth_shown_ = tenth;
    const double seconds = this->seconds();
    const double rate = seconds > 0 ? static_cast<double>(now_) / seconds : 0.0;
    std::string left = "time left unknown";
    if (done >= total_) left = "done";
    else if (rate > 0) left = duration_text(static_cast<double>(total_ - done) / rate) + " left";
    std::fprintf(stderr, "%ssweep: %lld of %lld samples (%.1f%%), %.4g samples/s, %s%s",
                 terminal_ ? "\r" : "", done, total_,
                 100.0 * static_cast<double>(done) / static_cast<double>(total_), rate,
                 left.c_str(), terminal_ ? "\033[K" : "\n");
    std::fflush(stderr);
  }

  /// Ends the redrawn line on a terminal.
  void finish() {
    show(true);
    if (terminal_) std::fputc('\n', stderr);
  }

 private:
  long long total_, before_, now_ = 0;
  bool terminal_;
  Clock::time_point start_ = Clock::now(), shown_ = start_;
  int tenth_shown_ = -1;
  long long done_shown_ = -1;
};

}  // namespace gencoord::sweep
