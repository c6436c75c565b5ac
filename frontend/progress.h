// Progress of a long derivation on stderr: stage, cells done of total, elapsed. Silent for the
// first two seconds (most derivations finish sooner), then on a terminal one line rewritten in
// place, otherwise (--progress into a file or pipe) a line per stage and at most one a second.
#pragma once
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "generator/piecewise_form.h"

namespace boxgen::frontend {

using namespace ::boxgen::generator;  // NOLINT(google-build-using-namespace): the generator's front
                                      // end

class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool forced)
      : tty_(isatty(STDERR_FILENO) != 0),
        enabled_(forced || tty_),
        start_(std::chrono::steady_clock::now()) {}
  ~ProgressPrinter() { finish(); }
  // Clears the progress line on a terminal: call before printing the result.
  void finish() {
    if (printed_ && tty_) std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
    printed_ = false;
  }
  ProgressPrinter(const ProgressPrinter&) = delete;
  ProgressPrinter& operator=(const ProgressPrinter&) = delete;

  ProgressFn callback() {
    if (!enabled_) return {};
    return [this](const char* stage, std::size_t done, std::size_t total) {
      report(stage, done, total);
    };
  }

 private:
  void report(const char* stage, std::size_t done, std::size_t total) {
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const bool new_stage = stage_ != stage;
    if (t < 2 || (!new_stage && t - last_ < (tty_ ? 0.2 : 1.0) && done != total)) return;
    stage_ = stage;
    last_ = t;
    printed_ = true;
    std::string cells =
        total ? " " + std::to_string(done) + "/" + std::to_string(total) + " cells" : "";
    if (tty_)
      std::fprintf(stderr, "\r\033[Kboxgen: %s%s, %.1f s", stage, cells.c_str(), t);
    else
      std::fprintf(stderr, "boxgen: %s%s, %.1f s\n", stage, cells.c_str(), t);
    std::fflush(stderr);
  }

  bool tty_, enabled_, printed_ = false;
  std::chrono::steady_clock::time_point start_;
  std::string stage_;
  double last_ = 0;
};

}  // namespace boxgen::frontend
