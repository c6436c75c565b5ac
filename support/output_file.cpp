#include "support/output_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>

namespace boxgen::support {

namespace {

namespace fs = std::filesystem;

// A path made fit for a one-line message: control characters become '?'.
std::string shown(const fs::path& path) {
  std::string out;
  const std::string text = path.string();
  for (char ch : std::string_view(text).substr(0, 200))
    out += (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) ? '?' : ch;
  if (text.size() > 200) out += "...";
  return out;
}

[[noreturn]] void refuse(const fs::path& path, const std::string& why) {
  throw OutputFileError("cannot write '" + shown(path) + "': " + why);
}

// The system's reason in the project's words: strerror's text, lower-cased as the rest of our
// messages ("no space left on device").
std::string reason(int error) {
  std::string text = std::strerror(error);
  if (!text.empty() && text[0] >= 'A' && text[0] <= 'Z' && (text.size() < 2 || text[1] > 'Z'))
    text[0] = static_cast<char>(text[0] - 'A' + 'a');
  return text;
}

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Follows the symbolic links of `path` (at most 40, as the kernel does) to the file a write lands
// in. Sets `exists` and, if it exists, `info`.
fs::path follow_links(const fs::path& path, bool& exists, struct stat& info) {
  fs::path target = path;
  for (int depth = 0; depth <= 40; ++depth) {
    if (::lstat(target.c_str(), &info) != 0) {
      if (errno != ENOENT) refuse(path, reason(errno));
      exists = false;
      return target;
    }
    if (!S_ISLNK(info.st_mode)) {
      exists = true;
      return target;
    }
    std::error_code ec;
    const fs::path next = fs::read_symlink(target, ec);
    if (ec) refuse(path, ec.message());
    target = next.is_absolute() ? next : target.parent_path() / next;
  }
  refuse(path, "too many levels of symbolic links");
}

fs::path directory_of(const fs::path& target) {
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

// The temporaries of this process, for the signal handler: fixed storage, so that the handler
// only reads memory and calls unlink() (both async-signal-safe). A slot is claimed by a
// compare-and-swap on its state and published once its path is complete.
constexpr int kSlots = 64;
constexpr std::size_t kPathBytes = 4096;
enum SlotState : int { kFree = 0, kClaimed = 1, kLive = 2 };
struct Slot {
  std::atomic<int> state{kFree};
  std::array<char, kPathBytes> path{};
};
std::array<Slot, kSlots> g_slots;

int register_temporary(const fs::path& temp) {
  const std::string text = fs::absolute(temp).string();
  if (text.size() >= kPathBytes) return -1;  // not removed on a signal; still removed on errors
  for (int s = 0; s < kSlots; ++s) {
    int expected = kFree;
    if (g_slots[s].state.compare_exchange_strong(expected, kClaimed)) {
      std::memcpy(g_slots[s].path.data(), text.c_str(), text.size() + 1);
      g_slots[s].state.store(kLive);
      return s;
    }
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0) g_slots[slot].state.store(kFree);
}

// The child process groups to kill on a signal (ChildProcessGroup), stored like the temporaries.
std::array<std::atomic<int>, kSlots> g_children{};

// Renames of a set in progress (write_file_set), and a signal that arrived during them: the
// handler records it and returns, and the last renamer raises it again once its renames are done.
std::atomic<int> g_renaming{0};
std::atomic<int> g_deferred_signal{0};

extern "C" void remove_temporaries_and_die(int signal) {
  if (g_renaming.load() > 0) {
    g_deferred_signal.store(signal);
    if (g_renaming.load() > 0) return;  // else the renamer may have looked already: die now
  }
  for (auto& child : g_children)
    if (const int leader = child.load(); leader > 0) {
      ::kill(-leader, SIGKILL);
      ::waitpid(leader, nullptr, 0);  // its output files are closed once it is gone
    }
  for (auto& slot : g_slots)
    if (slot.state.load() == kLive) ::unlink(slot.path.data());
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

// Removes `.NAME.tmp-PID-N` files beside `target` left by processes that no longer exist (a
// SIGKILL during an earlier write): the only leftovers a write can leave.
void remove_stale_temporaries(const fs::path& target) {
  const std::string prefix = "." + target.filename().string() + ".tmp-";
  std::error_code ec;
  for (fs::directory_iterator it(directory_of(target), ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    const std::size_t dash = rest.find('-');
    if (dash == std::string::npos || dash == 0) continue;
    long pid = 0;
    try {
      pid = std::stol(rest.substr(0, dash));
    } catch (const std::exception&) {
      continue;
    }
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

}  // namespace

fs::path check_output_file(const fs::path& path, std::span<const fs::path> inputs) {
  const std::string name = path.filename().string();
  if (name.empty() || name == "." || name == "..") refuse(path, "not a file name");
  bool exists = false;
  struct stat info {};
  fs::path target = follow_links(path, exists, info);
  if (exists) {
    if (!S_ISREG(info.st_mode))
      refuse(path, fmt::format("{}{} is {}; only regular files are written",
                               target == path ? "it" : "its link target '",
                               target == path ? "" : shown(target) + "'", kind_of(info.st_mode)));
    for (const fs::path& input : inputs) {
      struct stat in {};
      if (::stat(input.c_str(), &in) == 0 && in.st_dev == info.st_dev && in.st_ino == info.st_ino)
        refuse(path, fmt::format("it is the input '{}'; write to another file", shown(input)));
    }
  } else {
    const fs::path dir = directory_of(target);
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
      refuse(path, fmt::format("the directory '{}' does not exist", shown(dir)));
    if (target.filename().empty()) refuse(path, "not a file name");
  }
  return target;
}

namespace {

// The target of a write that replaces a link instead of following it: `path` itself, which must
// be a regular file, a symbolic link or absent, in an existing directory.
fs::path check_replaced_file(const fs::path& path) {
  const std::string name = path.filename().string();
  if (name.empty() || name == "." || name == "..") refuse(path, "not a file name");
  struct stat info {};
  if (::lstat(path.c_str(), &info) == 0) {
    if (!S_ISREG(info.st_mode) && !S_ISLNK(info.st_mode))
      refuse(path, fmt::format("it is {}; only regular files are written", kind_of(info.st_mode)));
  } else if (errno != ENOENT) {
    refuse(path, reason(errno));
  } else {
    std::error_code ec;
    if (!fs::is_directory(directory_of(path), ec))
      refuse(path, fmt::format("the directory '{}' does not exist", shown(directory_of(path))));
  }
  return path;
}

}  // namespace

PendingOutput::PendingOutput(const fs::path& path, std::span<const fs::path> inputs,
                             LinkPolicy links)
    : path_(path),
      target_(links == LinkPolicy::replace ? check_replaced_file(path)
                                           : check_output_file(path, inputs)) {
  remove_stale_temporaries(target_);
  struct stat old {};
  const bool replacing = links == LinkPolicy::write_through && ::stat(target_.c_str(), &old) == 0;
  static std::atomic<unsigned> counter{0};
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    temporary_ = directory_of(target_) / fmt::format(".{}.tmp-{}-{}", target_.filename().string(),
                                                     static_cast<long>(::getpid()), counter++);
    // Registered before it exists, so that a signal between the two cannot leave it behind (the
    // name holds our pid: no other live process creates it).
    slot_ = register_temporary(temporary_);
    fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                links == LinkPolicy::replace ? 0644 : 0666);
    if (fd < 0) {
      const int error = errno;
      unregister_temporary(slot_);
      slot_ = -1;
      if (error != EEXIST) refuse(path, reason(error));
    }
  }
  if (fd < 0) refuse(path, "could not create a temporary file next to it");
  // The replacement keeps the permissions of the file it replaces (a new file gets 0666 & ~umask).
  if (replacing && ::fchmod(fd, old.st_mode & 07777) != 0) {
    const int error = errno;
    ::close(fd);
    ::unlink(temporary_.c_str());  // the destructor is not run for a throwing constructor
    unregister_temporary(slot_);
    refuse(path, reason(error));
  }
  ::close(fd);
}

PendingOutput::~PendingOutput() {
  if (file_) std::fclose(file_);
  if (!committed_) ::unlink(temporary_.c_str());
  unregister_temporary(slot_);
}

std::FILE* PendingOutput::file() {
  if (!file_) {
    // Opened without following a link: the temporary is ours, created above.
    const int fd = ::open(temporary_.c_str(), O_WRONLY | O_TRUNC | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0 || !(file_ = ::fdopen(fd, "wb"))) {
      const int error = errno;
      if (fd >= 0) ::close(fd);
      refuse(path_, reason(error));
    }
  }
  return file_;
}

void PendingOutput::prepare(const std::string& problem_found) {
  std::string problem = problem_found;
  if (file_) {
    if (problem.empty() && (std::fflush(file_) != 0 || std::ferror(file_))) problem = reason(errno);
    if (std::fclose(file_) != 0 && problem.empty()) problem = reason(errno);
    file_ = nullptr;
  }
  if (problem.empty()) {
    // Written by us or by another program (gnuplot): make it durable before it replaces anything.
    const int fd = ::open(temporary_.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0 || ::fsync(fd) != 0) problem = reason(errno);
    if (fd >= 0) ::close(fd);
  }
  if (!problem.empty()) abandon(problem);
  prepared_ = true;
}

void PendingOutput::commit(const std::string& problem_found) {
  if (!prepared_ || !problem_found.empty()) prepare(problem_found);
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) abandon(reason(errno));
  committed_ = true;
  unregister_temporary(slot_);
  slot_ = -1;
}

void PendingOutput::abandon(const std::string& problem) {
  if (file_) std::fclose(file_);
  file_ = nullptr;
  ::unlink(temporary_.c_str());
  unregister_temporary(slot_);
  slot_ = -1;
  committed_ = true;  // nothing left to remove
  refuse(path_, problem);
}

void write_output_file(const fs::path& path, const std::function<bool(std::FILE*)>& fill,
                       const std::function<std::string()>& describe_failure, LinkPolicy links) {
  PendingOutput out(path, {}, links);
  std::FILE* file = out.file();
  std::string problem;
  if (!fill(file)) {
    problem = describe_failure ? describe_failure() : std::string();
    if (problem.empty())
      problem = std::ferror(file) ? reason(errno) : "the data could not be written";
  }
  out.commit(problem);
}

namespace {

void (*g_between_renames)() = nullptr;

// The directory's lock (flock), released when the object goes.
class DirectoryLock {
 public:
  explicit DirectoryLock(const fs::path& directory)
      : fd_(::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0) {
      const int error = errno;
      if (fd_ >= 0) ::close(fd_);
      refuse(directory, reason(error));
    }
  }
  ~DirectoryLock() { ::close(fd_); }
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int fd_;
};

constexpr std::string_view kJournalPrefix = ".boxgen-set-";

// The pid in a journal's name `.boxgen-set-PID-N`, or 0.
long journal_pid(const std::string& name) {
  if (name.rfind(kJournalPrefix, 0) != 0) return 0;
  try {
    return std::stol(name.substr(kJournalPrefix.size()));
  } catch (const std::exception&) {
    return 0;
  }
}

// Completes the renames of every journal in `directory` whose writer is gone (a SIGKILL between
// two renames of a set), then removes the journal. Called under the directory's lock.
void finish_interrupted_sets(const fs::path& directory) {
  std::error_code ec;
  for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec)) {
    const long pid = journal_pid(it->path().filename().string());
    if (pid <= 0 || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
    std::string text;
    {
      const int fd = ::open(it->path().c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
      if (fd < 0) continue;
      char buffer[4096];
      for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;)
        text.append(buffer, static_cast<std::size_t>(n));
      ::close(fd);
    }
    // Pairs temporary '\0' target '\0'; a temporary already renamed is gone.
    for (std::size_t at = 0; at < text.size();) {
      const std::size_t a = text.find('\0', at), b = text.find('\0', a + 1);
      if (a == std::string::npos || b == std::string::npos) break;
      const std::string temporary = text.substr(at, a - at), target = text.substr(a + 1, b - a - 1);
      struct stat info {};
      if (::lstat(temporary.c_str(), &info) == 0 && S_ISREG(info.st_mode))
        (void)std::rename(temporary.c_str(), target.c_str());
      at = b + 1;
    }
    ::unlink(it->path().c_str());
  }
}

}  // namespace

void set_between_renames_hook_for_tests(void (*hook)()) { g_between_renames = hook; }

void write_file_set(const fs::path& directory, std::span<const NamedText> files) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec || !fs::is_directory(directory, ec))
    throw OutputFileError("cannot create the output directory '" + shown(directory) + "'");
  for (const NamedText& f : files) (void)check_output_file(directory / f.filename);
  // Under one lock, so that two writers of the same set never interleave.
  const DirectoryLock lock(directory);
  finish_interrupted_sets(directory);
  // Every file complete and durable in its temporary before any target changes.
  std::vector<std::unique_ptr<PendingOutput>> pending;
  for (const NamedText& f : files) {
    pending.push_back(std::make_unique<PendingOutput>(directory / f.filename));
    std::FILE* file = pending.back()->file();
    if (std::fwrite(f.text.data(), 1, f.text.size(), file) != f.text.size() ||
        std::fflush(file) != 0) {
      const int error = errno;
      refuse(directory / f.filename, reason(error));  // pending's destructors remove them all
    }
  }
  for (auto& p : pending) p->prepare();
  // The journal of the renames, for a SIGKILL between two of them.
  static std::atomic<unsigned> counter{0};
  std::string journal_text;
  for (auto& p : pending)
    journal_text +=
        fs::absolute(p->temporary()).string() + '\0' + fs::absolute(p->target()).string() + '\0';
  PendingOutput journal(
      directory / fmt::format("{}{}-{}", kJournalPrefix, static_cast<long>(::getpid()), counter++));
  if (std::fwrite(journal_text.data(), 1, journal_text.size(), journal.file()) !=
      journal_text.size())
    journal.abandon(reason(errno));
  journal.commit();
  // The renames, with SIGINT, SIGTERM and SIGHUP held until the last one is done.
  g_renaming.fetch_add(1);
  std::string problem;
  try {
    for (std::size_t i = 0; i < pending.size(); ++i) {
      if (i == 1 && g_between_renames) g_between_renames();
      pending[i]->commit();
    }
  } catch (const OutputFileError& e) {
    problem = e.what();
  }
  ::unlink(journal.path().c_str());
  if (g_renaming.fetch_sub(1) == 1)
    if (const int signal = g_deferred_signal.exchange(0); signal != 0) std::raise(signal);
  if (!problem.empty()) throw OutputFileError(problem);
}

ChildProcessGroup::ChildProcessGroup(int leader) {
  for (int s = 0; s < kSlots; ++s) {
    int expected = 0;
    if (g_children[s].compare_exchange_strong(expected, leader)) {
      slot_ = s;
      return;
    }
  }
}

ChildProcessGroup::~ChildProcessGroup() {
  if (slot_ >= 0) g_children[slot_].store(0);
}

void handle_signals() {
  static const bool installed = [] {
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_die;
    sigemptyset(&action.sa_mask);
    for (int s : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(s, &action, nullptr);
    std::signal(SIGPIPE, SIG_IGN);
    return true;
  }();
  (void)installed;
}

}  // namespace boxgen::support
