#include "run_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <thread>

extern char** environ;

namespace boxgen::test {

namespace {

using Clock = std::chrono::steady_clock;

int remaining_ms(Clock::time_point deadline) {
  const auto left =
      std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left > 0 ? static_cast<int>(left) : 0;
}

// Appends what is ready on fd; returns false at end of file (or on an error other than EINTR).
bool drain(int fd, std::string& into) {
  std::array<char, 65536> buf;
  const ssize_t n = ::read(fd, buf.data(), buf.size());
  if (n > 0) {
    into.append(buf.data(), static_cast<size_t>(n));
    return true;
  }
  return n < 0 && errno == EINTR;
}

void record_status(int status, ProcessResult& r) {
  if (WIFEXITED(status)) {
    r.exited = true;
    r.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    r.signal = WTERMSIG(status);
  }
}

}  // namespace

ProcessResult run_process(const std::string& program, const std::vector<std::string>& args,
                          std::chrono::seconds timeout, const std::string& stdout_file,
                          const std::string& stdin_file) {
  ProcessResult r;
  r.program = program.substr(program.find_last_of('/') + 1);
  const auto start = Clock::now();
  const auto deadline = start + timeout;
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) return r;
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    ::close(out_pipe[0]);
    ::close(out_pipe[1]);
    return r;
  }

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(
      &actions, 0, stdin_file.empty() ? "/dev/null" : stdin_file.c_str(), O_RDONLY, 0);
  if (stdout_file.empty())
    posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);  // dup2 clears O_CLOEXEC on 1 and 2
  else  // the stdout pipe then only sees end of file: its write end is close-on-exec
    posix_spawn_file_actions_addopen(&actions, 1, stdout_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);

  std::vector<std::string> storage;
  storage.reserve(args.size() + 1);
  storage.push_back(program);
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);

  pid_t pid = 0;
  const int spawn_error =
      posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  if (spawn_error != 0) {
    ::close(out_pipe[0]);
    ::close(err_pipe[0]);
    r.err = std::string("posix_spawn failed: ") + std::strerror(spawn_error);
    return r;
  }
  r.started = true;

  // Read both pipes until both reach end of file, so a child filling one pipe never stalls.
  std::array<pollfd, 2> fds{pollfd{out_pipe[0], POLLIN, 0}, pollfd{err_pipe[0], POLLIN, 0}};
  std::array<std::string*, 2> sinks{&r.out, &r.err};
  int open_fds = 2;
  while (open_fds > 0 && !r.timed_out) {
    const int ready = ::poll(fds.data(), fds.size(), remaining_ms(deadline));
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0)
      break;  // cannot happen with valid descriptors; the wait below still has the deadline
    if (ready == 0) {
      r.timed_out = Clock::now() >= deadline;
      continue;
    }
    for (size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].fd < 0 || fds[i].revents == 0) continue;
      if (!drain(fds[i].fd, *sinks[i])) {
        ::close(fds[i].fd);
        fds[i].fd = -1;  // poll ignores negative descriptors
        --open_fds;
      }
    }
  }

  // The pipes are closed; the child may still be running (or have closed its output early).
  int status = 0;
  while (!r.timed_out) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) {
      record_status(status, r);
      break;
    }
    if (done < 0 && errno != EINTR) break;
    if (Clock::now() >= deadline)
      r.timed_out = true;
    else
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (r.timed_out) {
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    record_status(status, r);
  }
  for (auto& f : fds)
    if (f.fd >= 0) ::close(f.fd);
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

std::string describe(const std::vector<std::string>& args, const ProcessResult& r) {
  std::string s = "command: " + r.program;
  for (const auto& a : args) s += " '" + a + "'";
  s += "\nended: ";
  if (!r.started)
    s += "could not start";
  else if (r.timed_out)
    s += "TIMED OUT (killed)";
  else if (r.exited)
    s += "exit code " + std::to_string(r.exit_code);
  else
    s += "signal " + std::to_string(r.signal) + " (" + strsignal(r.signal) + ")";
  s += " after " + std::to_string(r.seconds) + " s";
  auto clip = [](const std::string& t) {
    return t.size() > 4000 ? t.substr(0, 4000) + "\n[... clipped]" : t;
  };
  s += "\n--- stdout (" + std::to_string(r.out.size()) + " bytes) ---\n" + clip(r.out);
  s += "\n--- stderr (" + std::to_string(r.err.size()) + " bytes) ---\n" + clip(r.err);
  return s;
}

}  // namespace boxgen::test
