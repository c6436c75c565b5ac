#include "loader/filter_compiler.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <algorithm>
#include <atomic>
#include <cerrno>  // program_invocation_name (glibc)
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <future>
#include <memory>
#include <sstream>

#include "boxgen/loader_config.h"
#include "loader/filter_cache.h"
#include "loader/filter_loader.h"
#include "runtime/nrrd_checks.h"
#include "support/output_file.h"

namespace boxgen::loader {

namespace fs = std::filesystem;

namespace {

bool executable(const fs::path& p) {
  std::error_code ec;
  return !p.empty() && fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

// `name` as the shell finds it: a path as given, a bare name on PATH.
fs::path on_path(const std::string& name) {
  if (name.find('/') != std::string::npos) return executable(name) ? fs::path(name) : fs::path();
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && executable(fs::path(dir) / name)) return fs::path(dir) / name;
  return {};
}

// What a child process did: its exit status (as waitpid gives it), whether it was stopped at the
// time limit, and the first bytes of its output.
struct ProcessResult {
  int status = 0;
  bool timed_out = false;
  std::string output;
  std::size_t dropped = 0;  // bytes of output beyond the kept ones
};

// Runs `args` (args[0] an absolute path) with no shell, standard input /dev/null, standard output
// (and standard error, when `with_errors`) into a pipe of which the first `keep` bytes are kept,
// in a process group of its own that dies with it: killed with SIGKILL when `seconds` pass, when
// `check` throws (rethrown once the group is gone) or when a signal stops this process
// (support::ChildProcessGroup); PR_SET_PDEATHSIG kills the compiler's driver even when this
// process is killed outright.
ProcessResult run_limited(std::vector<std::string> args, double seconds, std::size_t keep,
                          bool with_errors, const std::function<void()>& check) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int out[2];
  if (::pipe2(out, O_CLOEXEC) != 0)
    throw LoadError(fmt::format("cannot run {}: {}", args[0], std::strerror(errno)));
  const int null_fd = ::open("/dev/null", O_RDWR | O_CLOEXEC);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {  // the child: async-signal-safe calls only until exec
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::signal(SIGPIPE, SIG_DFL);  // the parent ignores it (handle_signals); exec keeps ignored ones
    ::dup2(null_fd, STDIN_FILENO);
    ::dup2(out[1], STDOUT_FILENO);
    ::dup2(with_errors ? out[1] : null_fd, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  const int fork_error = errno;
  ::close(out[1]);
  if (null_fd >= 0) ::close(null_fd);
  if (pid < 0) {
    ::close(out[0]);
    throw LoadError(fmt::format("cannot run {}: {}", args[0], std::strerror(fork_error)));
  }
  ::setpgid(pid, pid);  // also here, so the group exists before anything is sent to it
  const support::ChildProcessGroup registered(pid);
  ProcessResult result;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  std::exception_ptr stopped;
  bool open = true, exited = false, reaped = false;
  while (open || !exited) {
    if (!exited) {
      int status = 0;
      const pid_t done = ::waitpid(pid, &status, WNOHANG);
      if (done == pid) exited = true, result.status = status;
    }
    if (exited && !reaped) {
      ::kill(-pid, SIGKILL);  // a descendant left behind must not hold the pipe
      reaped = true;
    }
    if (open) {
      pollfd p{out[0], POLLIN, 0};
      if (::poll(&p, 1, 100) > 0) {
        char buffer[8192];
        const ssize_t n = ::read(out[0], buffer, sizeof buffer);
        if (n > 0) {
          const auto got = static_cast<std::size_t>(n);
          const std::size_t room = keep - std::min(keep, result.output.size());
          result.output.append(buffer, std::min(room, got));
          result.dropped += got - std::min(room, got);
        } else if (n == 0 || errno != EINTR) {
          open = false;
        }
      }
    } else if (!exited) {
      ::usleep(20000);
    }
    if (exited) continue;
    if (std::chrono::steady_clock::now() > deadline) result.timed_out = true;
    if (check && !stopped) try {
        check();
      } catch (...) {
        stopped = std::current_exception();
      }
    if (result.timed_out || stopped) {
      ::kill(-pid, SIGKILL);
      int status = 0;
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      exited = reaped = true;
      open = false;
    }
  }
  ::close(out[0]);
  if (stopped) std::rethrow_exception(stopped);
  return result;
}

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::string find_compiler(const CompileOptions& options) {
  const char* env = std::getenv("BOXGEN_CXX");
  std::string wanted = !options.compiler.empty() ? options.compiler : (env ? env : "");
  if (!wanted.empty()) {
    const fs::path p = on_path(wanted);
    if (p.empty())
      throw LoadError(fmt::format(
          "the C++ compiler '{}' (from {}) is not an executable: compiling a filter from a SPEC "
          "needs one; install g++ (Debian: sudo apt-get install g++) or point BOXGEN_CXX at one",
          wanted.substr(0, 80), options.compiler.empty() ? "BOXGEN_CXX" : "the options"));
    return fs::absolute(p).string();
  }
  for (const char* candidate : {config::kCompiler, "c++", "g++"}) {
    const fs::path p = on_path(candidate);
    if (!p.empty()) return fs::absolute(p).string();
  }
  throw LoadError(
      "no C++ compiler found (looked for the build's compiler, c++ and g++ on PATH): compiling a "
      "filter from a SPEC needs one; install g++ (Debian: sudo apt-get install g++, or "
      "build-essential)");
}

// The binary (program or shared library) that holds this code.
fs::path this_binary() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&find_toolchain), &info) == 0 || !info.dli_fname) return {};
  std::error_code ec;
  // In the program itself, dladdr names it as it was started (argv[0]): ask the kernel instead.
  const std::string name = info.dli_fname;
  if (name.empty() || name == program_invocation_name || name.find('/') == std::string::npos)
    return fs::read_symlink("/proc/self/exe", ec);
  const fs::path p = fs::canonical(name, ec);
  return ec ? fs::path(info.dli_fname) : p;
}

// The engine: the build tree's sources and archive when this code runs from the build tree,
// else the installed headers and archive of the prefix above it.
void find_engine(Toolchain& t) {
  const fs::path binary = this_binary();
  std::error_code ec;
  const fs::path build = fs::weakly_canonical(config::kBinaryDir, ec);
  const std::string b = binary.string(), root = build.string() + "/";
  if (!binary.empty() && b.compare(0, root.size(), root) == 0) {
    t.include_dir = config::kSourceDir;
    t.archive = config::kRuntimeArchive;
    const fs::path precompiled = config::kPrecompiledDir;
    if (!precompiled.empty() &&
        fs::is_regular_file(precompiled / "runtime" / "compiled_filter.h.gch", ec))
      t.precompiled_dir = precompiled;
  } else {
    for (fs::path dir = binary.parent_path(); !dir.empty(); dir = dir.parent_path()) {
      if (fs::exists(dir / config::kInstalledInclude / "runtime" / "emitted_filter.h", ec) &&
          fs::exists(dir / config::kInstalledArchive, ec)) {
        t.include_dir = dir / config::kInstalledInclude;
        t.archive = dir / config::kInstalledArchive;
        break;
      }
      if (dir == dir.root_path()) break;
    }
  }
  if (t.include_dir.empty() || !fs::exists(t.archive, ec))
    throw LoadError(fmt::format(
        "the runtime's headers and library are not found beside {} (build boxgen, or install it "
        "with cmake --install): they are needed to compile a filter from a SPEC",
        binary.empty() ? std::string("this program") : binary.string()));
}

}  // namespace

// The processor, for -march=native: a cache shared by machines of other kinds keeps one entry
// for each.
std::string processor() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model, flags;
  while (std::getline(in, line) && (model.empty() || flags.empty())) {
    if (model.empty() && line.rfind("model name", 0) == 0) model = line;
    if (flags.empty() && line.rfind("flags", 0) == 0) flags = line;
  }
  return model + "\n" + flags;
}

std::string Toolchain::identity() const {
  std::string id = compiler + "\n" + version + "\n" + processor() + "\n";
  for (const auto& f : flags) id += f + " ";
  std::error_code ec;
  const auto size = fs::file_size(archive, ec);
  const auto time = fs::last_write_time(archive, ec).time_since_epoch().count();
  id += fmt::format("\n{} {} {}\n", archive.string(), size, time);
  for (const auto& l : libraries) id += l + " ";
  return id;
}

Toolchain find_toolchain(const CompileOptions& options) {
  Toolchain t;
  t.compiler = find_compiler(options);
  find_engine(t);
  const double limit = std::min(30.0, compile_time_limit(options));
  const ProcessResult version = run_limited({t.compiler, "--version"}, limit, 4096, false, {});
  if (version.timed_out)
    throw LoadError(fmt::format(
        "the C++ compiler {} did not answer `--version` within {} s: point BOXGEN_CXX at a "
        "working compiler",
        t.compiler, limit));
  t.version = version.output.substr(0, version.output.find_first_of("\r\n"));
  // The build's flags for a filter (loader/CMakeLists.txt says why each is there).
  t.flags = words(config::kFlags);
  t.flags.push_back("-I" + t.include_dir.string());
  // The precompiled header was made by the build's compiler for the build tree's headers.
  std::error_code ec;
  if (!t.precompiled_dir.empty() && !fs::equivalent(t.compiler, config::kCompiler, ec))
    t.precompiled_dir.clear();
  t.libraries = words(config::kLibraries);
  return t;
}

double compile_time_limit(const CompileOptions& options) {
  if (options.compile_seconds > 0) return options.compile_seconds;
  const char* env = std::getenv("BOXGEN_COMPILE_TIMEOUT");
  if (!env || !*env) return 600;
  char* end = nullptr;
  const double seconds = std::strtod(env, &end);
  if (*end != '\0' || !(seconds > 0) || !std::isfinite(seconds))
    throw LoadError(
        fmt::format("BOXGEN_COMPILE_TIMEOUT must be a positive number of seconds, not '{}'",
                    runtime::nrrd_checks::printable(env, 40)));
  return seconds;
}

namespace {

// True when `path` is a regular file of ours that starts as an ELF object does; makes it 0644
// (the linker's mode follows the umask, and the cache loads nothing others can write).
bool wrote_object(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat info {};
  char magic[4] = {};
  const bool ok = ::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) && info.st_uid == ::geteuid() &&
                  ::pread(fd, magic, 4, 0) == 4 &&
                  std::memcmp(magic,
                              "\x7f"
                              "ELF",
                              4) == 0 &&
                  ::fchmod(fd, 0644) == 0;
  ::close(fd);
  return ok;
}

}  // namespace

namespace {

// The failure of a compile or link step, or empty when it wrote its ELF object.
std::string step_failure(const ProcessResult& run, const Toolchain& t, const fs::path& output,
                         bool linked, const std::string& what, double seconds) {
  if (run.timed_out)
    return fmt::format(
        "compiling filter {} was stopped after {} s (the limit: BOXGEN_COMPILE_TIMEOUT)", what,
        seconds);
  if (!WIFEXITED(run.status) || WEXITSTATUS(run.status) != 0)
    return fmt::format("compiling filter {} failed", what);
  if (!wrote_object(output))
    return fmt::format("the C++ compiler {} exited 0 but wrote no {} for filter {}", t.compiler,
                       linked ? "shared object" : "object file", what);
  return {};
}

// Throws LoadError for `failure`, with the step's messages written into the log.
[[noreturn]] void fail_step(const std::string& failure, const ProcessResult& run,
                            const fs::path& log) {
  std::string text = run.output;
  if (run.dropped > 0)
    text += fmt::format("\n[boxgen: {} more bytes of the compiler's messages were dropped]\n",
                        run.dropped);
  try {
    write_entry_file(log, text);
  } catch (const std::exception&) {
    throw LoadError(failure + " (its messages could not be written)");
  }
  throw LoadError(fmt::format("{} (the compiler's messages: {})", failure,
                              runtime::nrrd_checks::printable(log.string())));
}

std::vector<std::string> compile_args(const Toolchain& t, const fs::path& source,
                                      const fs::path& output, bool link) {
  std::vector<std::string> args{t.compiler};
  if (!t.precompiled_dir.empty()) args.push_back("-I" + t.precompiled_dir.string());
  args.insert(args.end(), t.flags.begin(), t.flags.end());
  if (!link) args.emplace_back("-c");
  for (std::string a : {std::string("-x"), std::string("c++"), source.string(), std::string("-x"),
                        std::string("none"), std::string("-o"), output.string()})
    args.push_back(std::move(a));
  return args;
}

void add_link_args(const Toolchain& t, std::vector<std::string>& args) {
  args.emplace_back("-Wl,--exclude-libs,ALL");
  args.push_back(t.archive.string());
  args.insert(args.end(), t.libraries.begin(), t.libraries.end());
}

}  // namespace

void compile_shared_object(const Toolchain& t, const std::vector<fs::path>& sources,
                           const fs::path& output, const fs::path& log, const std::string& what,
                           double seconds, const std::function<void()>& check) {
  std::error_code ec;
  if (sources.size() == 1) {
    auto args = compile_args(t, sources[0], output, true);
    add_link_args(t, args);
    const ProcessResult run = run_limited(args, seconds, kMaxLogBytes, true, check);
    const std::string failure = step_failure(run, t, output, true, what, seconds);
    if (!failure.empty()) fail_step(failure, run, log);
    fs::remove(log, ec);  // a link there is removed, never followed
    return;
  }
  // Each source into an object at once (the machine's cores share the work), then one link. The
  // objects are temporaries beside the output, removed whatever happens.
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::unique_ptr<support::PendingOutput>> objects;
  for (std::size_t i = 0; i < sources.size(); ++i)
    objects.push_back(std::make_unique<support::PendingOutput>(fs::path(sources[i].string() + ".o"),
                                                               std::span<const fs::path>{},
                                                               support::LinkPolicy::replace));
  // The other compiles run on threads of their own and stop when this one is stopped (`stop`);
  // `check` is called on this thread only (Python's interrupt check must be).
  std::atomic<bool> stop{false};
  const auto stopped = [&stop] {
    if (stop.load()) throw LoadError("stopped");
  };
  std::vector<std::future<ProcessResult>> others;
  for (std::size_t i = 1; i < sources.size(); ++i)
    others.push_back(std::async(std::launch::async, [&, i] {
      return run_limited(compile_args(t, sources[i], objects[i]->temporary(), false), seconds,
                         kMaxLogBytes, true, stopped);
    }));
  std::vector<ProcessResult> runs(sources.size());
  try {
    runs[0] = run_limited(compile_args(t, sources[0], objects[0]->temporary(), false), seconds,
                          kMaxLogBytes, true, check);
    if (const std::string failure =
            step_failure(runs[0], t, objects[0]->temporary(), false, what, seconds);
        !failure.empty()) {
      stop.store(true);
      for (auto& f : others) f.wait();
      fail_step(failure, runs[0], log);
    }
    for (std::size_t i = 1; i < sources.size(); ++i) {
      while (others[i - 1].wait_for(std::chrono::milliseconds(100)) != std::future_status::ready)
        if (check) check();
      runs[i] = others[i - 1].get();
    }
  } catch (...) {
    stop.store(true);
    for (auto& f : others)
      if (f.valid()) f.wait();
    throw;
  }
  for (std::size_t i = 1; i < sources.size(); ++i) {
    const std::string failure =
        step_failure(runs[i], t, objects[i]->temporary(), false, what, seconds);
    if (!failure.empty()) fail_step(failure, runs[i], log);
  }
  const double left =
      seconds - std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<std::string> args{t.compiler};
  args.insert(args.end(), t.flags.begin(), t.flags.end());
  for (const auto& o : objects) args.push_back(o->temporary().string());
  args.emplace_back("-o");
  args.push_back(output.string());
  add_link_args(t, args);
  const ProcessResult run = run_limited(args, std::max(left, 1.0), kMaxLogBytes, true, check);
  const std::string failure = step_failure(run, t, output, true, what, seconds);
  if (!failure.empty()) fail_step(failure, run, log);
  fs::remove(log, ec);
}

}  // namespace boxgen::loader
