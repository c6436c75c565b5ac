#include "apps/boxrecon/progress.h"

#include <unistd.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <utility>

#include "frontend/filter_choice.h"
#include "runtime/nrrd_checks.h"

namespace boxgen::app {

double progress_after() {
  const char* text = std::getenv("BOXGEN_PROGRESS_AFTER");
  if (!text || !*text) return 2;
  char* end = nullptr;
  const double seconds = std::strtod(text, &end);
  if (*end != '\0' || !(seconds >= 0) || !std::isfinite(seconds))
    throw std::invalid_argument(
        fmt::format("BOXGEN_PROGRESS_AFTER must be a number of seconds >= 0, got '{}'",
                    runtime::nrrd_checks::printable(text, 40)));
  return seconds;
}

Progress::Progress(std::string label)
    : label_(std::move(label)), enabled_(!frontend::quiet() && ::isatty(STDERR_FILENO) != 0) {
  if (!enabled_) return;
  after_ = std::chrono::duration<double>(progress_after());
  start_ = Clock::now();
}

Progress::~Progress() {
  if (shown_) std::fputc('\n', stderr);
}

void Progress::update(double done) {
  if (!enabled_ || !(shown_ || Clock::now() - start_ >= after_)) return;
  shown_ = true;
  const int percent = static_cast<int>(std::floor(100 * std::fmin(std::fmax(done, 0.0), 1.0)));
  std::fprintf(stderr, "\r%s %3d%%", label_.c_str(), percent);
  std::fflush(stderr);
}

Stage::Stage(std::string label)
    : label_(std::move(label)), start_(Clock::now()), exceptions_(std::uncaught_exceptions()) {
  if (frontend::quiet() || ::isatty(STDERR_FILENO) == 0) return;
  const std::chrono::duration<double> after(progress_after());
  if (after.count() == 0) {
    const std::lock_guard<std::mutex> lock(mutex_);
    show();
    return;
  }
  watcher_ = std::thread([this, after] {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!ended_.wait_for(lock, after, [this] { return over_; })) show();
  });
}

Stage::~Stage() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    over_ = true;
    if (shown_ && std::uncaught_exceptions() > exceptions_) {
      std::fputc('\n', stderr);  // the error's line follows on its own line
    } else if (shown_) {
      const std::chrono::duration<double> took = Clock::now() - start_;
      std::fprintf(stderr, " done (%.1f s)\n", took.count());
    }
  }
  ended_.notify_all();
  if (watcher_.joinable()) watcher_.join();
}

void Stage::show() {
  shown_ = true;
  std::fprintf(stderr, "%s ...", label_.c_str());
  std::fflush(stderr);
}

}  // namespace boxgen::app
