// A progress bar for long jobs: done/total, rate, ETA and any extra status, on stderr.
// On a terminal it redraws one line; otherwise (CI, logs) it prints a line every ~10 s.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace vaegail {

class Progress {
 public:
  Progress(std::string label, std::int64_t total, std::string unit = "it");
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::int64_t n = 1);
  void set(std::int64_t done);
  // Work done before this process (a resumed run): shown in the count, left out of the rate.
  void resume(std::int64_t done);
  // Short text shown after the rate, e.g. "loss 1.23".
  void set_status(std::string status);
  // A job that also stops after `seconds` of wall-clock time (e.g. `gail train --minutes`): the
  // ETA is then whichever comes first, the work or the budget, not the work alone.
  void set_time_budget(double seconds);
  void finish();

  static std::string format_duration(double seconds);
  // Seconds left: `left` units at `rate` units/s, capped by `budget_left` seconds when that is
  // >= 0; -1 when neither bounds it (no rate yet and no budget).
  static double eta_seconds(std::int64_t left, double rate, double budget_left);

 private:
  void draw(bool final);

  std::string label_, unit_, status_;
  std::int64_t total_, done_ = 0, start_done_ = 0;
  double time_budget_ = -1;  // seconds from start_; < 0: none
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool tty_, quiet_, finished_ = false;
};

}  // namespace vaegail
