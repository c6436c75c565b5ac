// Runs a program the way a user's script would and captures everything it says, so the CLI tests
// can check exit codes and the exact bytes on stdout and stderr. No shell is involved: each
// argument reaches the child's argv unchanged. A deadline turns a hang into a test failure.
#pragma once
#include <chrono>
#include <string>
#include <vector>

namespace boxgen::test {

struct ProcessResult {
  std::string program;     // the program's file name, for messages
  bool started = false;    // posix_spawn succeeded
  bool exited = false;     // ended through exit() (not a signal)
  int exit_code = -1;      // valid when exited
  int signal = 0;          // the signal that ended it, when it did not exit
  bool timed_out = false;  // killed by run_process after the deadline
  double seconds = 0;      // wall clock
  std::string out, err;
};

// stdin is /dev/null (or the file stdin_file), so a program waiting for input cannot block the
// test. With stdout_file set, stdout goes to that file (e.g. /dev/full to simulate a full disk)
// and `out` stays empty.
ProcessResult run_process(const std::string& program, const std::vector<std::string>& args,
                          std::chrono::seconds timeout, const std::string& stdout_file = "",
                          const std::string& stdin_file = "");

// One readable paragraph for assertion messages: command, how it ended, stdout and stderr.
std::string describe(const std::vector<std::string>& args, const ProcessResult& r);

}  // namespace boxgen::test
