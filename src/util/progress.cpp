#include "util/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <fmt/format.h>

#include "util/world.h"

namespace vaegail {

namespace {
double seconds_between(std::chrono::steady_clock::time_point a,
                       std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}
}  // namespace

Progress::Progress(std::string label, std::int64_t total, std::string unit)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total),
      start_(std::chrono::steady_clock::now()), last_draw_(start_), tty_(isatty(STDERR_FILENO)),
      // Under mpirun the ranks share one terminal; rank 0 speaks for the run.
      quiet_(!World::get().is_root()) {}

// The final bar (finish()), unless an exception is ending the job: then a bar in progress is
// cleared, so that the error's one line stands alone on stderr.
Progress::~Progress() {
  if (std::uncaught_exceptions() == 0)
    finish();
  else if (tty_ && !quiet_ && !finished_)
    std::fputs("\r\033[K", stderr);
}

void Progress::advance(std::int64_t n) { set(done_ + n); }

void Progress::set(std::int64_t done) {
  done_ = done;
  const auto now = std::chrono::steady_clock::now();
  const double since = seconds_between(last_draw_, now);
  if (!quiet_ && ((tty_ && since >= 0.1) || (!tty_ && since >= 10.0))) draw(false);
}

void Progress::resume(std::int64_t done) {
  start_done_ = done;
  set(done);
}

void Progress::set_status(std::string status) { status_ = std::move(status); }

void Progress::set_time_budget(double seconds) { time_budget_ = seconds; }

double Progress::eta_seconds(std::int64_t left, double rate, double budget_left) {
  const double by_work = rate > 0 ? left / rate : -1;
  if (budget_left < 0) return by_work;
  return by_work < 0 ? budget_left : std::min(by_work, budget_left);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (!quiet_) draw(true);
}

std::string Progress::format_duration(double seconds) {
  if (!(seconds >= 0) || seconds > 1e7) return "--:--";
  const long s = static_cast<long>(seconds + 0.5);
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{:02}:{:02}", s / 60, s % 60);
}

void Progress::draw(bool final) {
  const auto now = std::chrono::steady_clock::now();
  last_draw_ = now;
  const double elapsed = seconds_between(start_, now);
  const double rate = elapsed > 0 ? (done_ - start_done_) / elapsed : 0;
  const double eta =
      eta_seconds(total_ - done_, rate, time_budget_ < 0 ? -1 : std::max(0.0, time_budget_ - elapsed));
  const double frac = total_ > 0 ? static_cast<double>(done_) / total_ : 0;
  const int width = 24;
  std::string bar(width, ' ');
  for (int i = 0; i < static_cast<int>(frac * width + 1e-9) && i < width; ++i) bar[i] = '#';
  std::fprintf(stderr, "%s%s [%s] %lld/%lld %3.0f%% %.1f %s/s elapsed %s eta %s%s%s%s",
               tty_ ? "\r\033[K" : "", label_.c_str(), bar.c_str(),
               static_cast<long long>(done_), static_cast<long long>(total_), 100 * frac, rate,
               unit_.c_str(), format_duration(elapsed).c_str(),
               final ? "00:00" : format_duration(eta).c_str(), status_.empty() ? "" : "  ",
               status_.c_str(), (final || !tty_) ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace vaegail
