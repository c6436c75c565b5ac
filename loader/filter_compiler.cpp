#include "loader/filter_compiler.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <cerrno>  // program_invocation_name (glibc)
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "boxgen/loader_config.h"
#include "loader/filter_loader.h"

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX, for posix_spawn

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

std::string first_line_of(const std::string& command) {
  std::string out;
  if (std::FILE* p = ::popen(command.c_str(), "r")) {
    char line[512];
    if (std::fgets(line, sizeof line, p)) out = line;
    ::pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
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
  t.version = first_line_of(shell_quote(t.compiler) + " --version 2>/dev/null");
  // The build's optimisation flags (as the registry's evaluators get), this machine's instruction
  // set (the object's SIMD kernels are compiled for it alone, not for every Highway target as the
  // runtime's are: a quarter of the compile), position independent, only the two entry points
  // exported, OpenMP for the batch paths, no fused multiply-adds (the SIMD path and the scalar
  // path round alike, as in the runtime).
  t.flags = words(config::kFlags);
  for (const char* f :
       {"-march=native", "-std=c++20", "-fPIC", "-shared", "-fvisibility=hidden",
        "-fvisibility-inlines-hidden", "-fopenmp", "-ffp-contract=off", "-Wno-psabi", "-w"})
    t.flags.emplace_back(f);
  t.flags.push_back("-I" + t.include_dir.string());
  t.libraries = words(config::kLibraries);
  return t;
}

void compile_shared_object(const Toolchain& t, const fs::path& source, const fs::path& output,
                           const fs::path& log, const std::string& what) {
  std::vector<std::string> args{t.compiler};
  args.insert(args.end(), t.flags.begin(), t.flags.end());
  for (std::string a : {std::string("-x"), std::string("c++"), source.string(), std::string("-x"),
                        std::string("none"), std::string("-o"), output.string(),
                        std::string("-Wl,--exclude-libs,ALL"), t.archive.string()})
    args.push_back(std::move(a));
  args.insert(args.end(), t.libraries.begin(), t.libraries.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0)
    throw LoadError(
        fmt::format("cannot run the C++ compiler {}: {}", t.compiler, std::strerror(spawned)));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      throw LoadError(fmt::format("waiting for {}: {}", t.compiler, std::strerror(errno)));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw LoadError(fmt::format("compiling filter {} failed (the compiler's messages: {})", what,
                                log.string()));
  std::error_code ec;
  fs::remove(log, ec);
}

}  // namespace boxgen::loader
