// Progress of a long step on stderr, the same for every command: only on a terminal and without
// --quiet, and only once the step has run BOXGEN_PROGRESS_AFTER seconds (default 2; 0: at once).
// What the command computes and writes never depends on it.
//
//   Progress progress("resampling");
//   for (...) { ...; progress.update(done / total); }   // "\rresampling  42%"
//   // the destructor ends the line when anything was shown
//
// A step that cannot count its work (a prefilter's solve) shows a Stage instead: "LABEL ..." once
// it has run that long, and " done (S s)" when it ends.
#pragma once
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace boxgen::app {

// BOXGEN_PROGRESS_AFTER's seconds (default 2). Throws std::invalid_argument (one line) for
// anything but a number >= 0.
double progress_after();

class Progress {
 public:
  // Shows nothing unless stderr is a terminal and --quiet is not given (checked here, once).
  explicit Progress(std::string label);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Whether the step may show progress at all (a terminal, no --quiet): a caller that would
  // split its work only to report it can skip that when this is false.
  bool enabled() const noexcept { return enabled_; }
  // `done` of the step, in [0, 1].
  void update(double done);

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  bool enabled_ = false, shown_ = false;
  Clock::time_point start_;
  std::chrono::duration<double> after_{};
};

// The stage's line comes from a thread that waits BOXGEN_PROGRESS_AFTER seconds (at once for 0:
// then the line is written here, so that it always shows) unless the stage ends first.
class Stage {
 public:
  explicit Stage(std::string label);
  ~Stage();
  Stage(const Stage&) = delete;
  Stage& operator=(const Stage&) = delete;

 private:
  using Clock = std::chrono::steady_clock;
  void show();  // with mutex_ held
  std::string label_;
  Clock::time_point start_;
  int exceptions_;  // std::uncaught_exceptions() at the start: an error ends the line bare
  std::mutex mutex_;
  std::condition_variable ended_;
  bool over_ = false, shown_ = false;
  std::thread watcher_;
};

}  // namespace boxgen::app
