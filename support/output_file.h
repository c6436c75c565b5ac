// Where an output file may go, and writing it so that nothing is ever lost or written half.
// Every program writes through this module: boxrecon's volumes and images, boxgen's emitted
// headers, plots and images (docs/errors.md lists the guarantees).
//
// The rules, as a user who types `-o PATH` expects them:
//   - a symbolic link is written through: its final target receives the data, the link stays a
//     link (a dangling link creates its target, as the shell's `>` does);
//   - the target must be a regular file or not exist yet: a directory, FIFO, socket or device
//     (`-o /dev/full`, `-o /dev/null`) is refused, never replaced;
//   - an output that is one of the inputs (the same file by another path, a link or a hard link)
//     is refused before any work, so a failure can never leave the input destroyed;
//   - the data goes to a temporary file `.NAME.tmp-PID-N` in the target's directory, which is
//     renamed over the target once complete (and flushed to disk): a failed write leaves the old
//     file as it was. An existing target keeps its permission bits;
//   - a set of files (an evaluator and its prefilters) is written all or nothing: every file is
//     complete before the first is renamed, and the renames hold a lock on the directory, so two
//     programs writing the same set never mix their files;
//   - on SIGINT, SIGTERM or SIGHUP (once handle_signals() has run) the temporaries are removed
//     (and the child process groups registered with ChildProcessGroup killed) before the program
//     dies of the signal. SIGKILL cannot be caught: its leftovers are
//     `.NAME.tmp-PID-N` files, and a later write of NAME removes those of processes that are
//     gone.
#pragma once
#include <cstdio>
#include <filesystem>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace boxgen::support {

// What a write does with a symbolic link at the target's name. `write_through` is what a user's
// `-o PATH` expects (above). `replace` is for directories the program owns (the filter cache,
// docs/runtime.md): the link itself is replaced by the new file and never followed, and the new
// file is created with mode 0644 (less the umask) instead of the replaced file's mode.
enum class LinkPolicy { write_through, replace };

// An output that may not or could not be written. The message is one line naming the path.
struct OutputFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The file a write to `path` lands in: `path` with every symbolic link (of the last component)
// followed. Throws OutputFileError (one line) unless that is a regular file or does not exist in
// an existing directory, or when it is the same file as one of `inputs` (inputs that do not
// exist are ignored). Writes nothing: call it before the work, so a bad -o fails fast.
std::filesystem::path check_output_file(const std::filesystem::path& path,
                                        std::span<const std::filesystem::path> inputs = {});

// A temporary file beside an output's target, renamed over the target by commit(). For writers
// that need a path (gnuplot, libpng through a FILE*) and as the building block of
// write_output_file. The destructor removes the temporary unless commit() succeeded.
class PendingOutput {
 public:
  // Checks the target as check_output_file does and creates the (empty) temporary at once, so an
  // unwritable destination fails before any work. Throws OutputFileError.
  explicit PendingOutput(const std::filesystem::path& path,
                         std::span<const std::filesystem::path> inputs = {},
                         LinkPolicy links = LinkPolicy::write_through);
  ~PendingOutput();
  PendingOutput(const PendingOutput&) = delete;
  PendingOutput& operator=(const PendingOutput&) = delete;

  const std::filesystem::path& path() const noexcept { return path_; }  // as the user gave it
  const std::filesystem::path& temporary() const noexcept { return temporary_; }
  // The temporary, opened for writing (binary) on first use; closed by commit().
  std::FILE* file();
  // Flushes and syncs the temporary and renames it over the target. Throws OutputFileError (one
  // line: the system's reason, "no space left on device" for a full disk) and removes the
  // temporary when any step fails; `problem`, when not empty, is such a failure found by the
  // caller (the writer's own error).
  void commit(const std::string& problem = {});
  // The first half of commit(): flushes, closes and syncs the temporary (throws as commit does).
  // commit() after it only renames, so a set's renames follow each other closely.
  void prepare(const std::string& problem = {});
  const std::filesystem::path& target() const noexcept { return target_; }
  // Removes the temporary and throws OutputFileError naming `problem`: the write failed.
  [[noreturn]] void abandon(const std::string& problem);

 private:
  std::filesystem::path path_, target_, temporary_;
  std::FILE* file_ = nullptr;
  int slot_ = -1;  // in the signal handler's list
  bool committed_ = false, prepared_ = false;
};

// Writes the file through `fill`, which returns false on failure, and renames it into place as
// described above. `describe_failure` (may be empty) gives the reason when `fill` returns false.
// Throws OutputFileError (one line); the target is then left as it was and no temporary remains.
void write_output_file(const std::filesystem::path& path,
                       const std::function<bool(std::FILE*)>& fill,
                       const std::function<std::string()>& describe_failure = {},
                       LinkPolicy links = LinkPolicy::write_through);

// One file of a set: its name inside the directory, and its bytes.
struct NamedText {
  std::string filename;
  std::string text;
};

// Writes every file of `files` into `directory` (created if missing), all or nothing: each is
// checked, then written to its temporary and synced, and only when all are complete are they
// renamed, under an exclusive lock on the directory. Throws OutputFileError (one line); on failure
// no target has changed and no temporary remains.
//
// Signals: SIGINT, SIGTERM and SIGHUP that arrive while the renames run are held until the last
// rename is done (then the program dies of them as usual), so they never leave part of a set
// renamed. SIGKILL cannot be held: before the renames a journal `.boxgen-set-PID-N` (the pairs
// temporary, target) is written and synced, and removed after them; the next write_file_set into
// the directory first completes the renames of every journal whose process is gone.
void write_file_set(const std::filesystem::path& directory, std::span<const NamedText> files);

// For tests: a function write_file_set calls between its first and second rename (nothing when
// null), so a test can stop the writer there (raise(SIGSTOP)) and send it a signal.
void set_between_renames_hook_for_tests(void (*hook)());

// A child process group (its leader's pid) that the handlers of handle_signals() kill with
// SIGKILL, and whose leader they reap, before they remove the temporaries: a compiler started by
// the program must not outlive it and re-create a temporary (loader/filter_compiler.cpp).
// Registered while the object lives.
class ChildProcessGroup {
 public:
  explicit ChildProcessGroup(int leader);
  ~ChildProcessGroup();
  ChildProcessGroup(const ChildProcessGroup&) = delete;
  ChildProcessGroup& operator=(const ChildProcessGroup&) = delete;

 private:
  int slot_ = -1;
};

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove every pending temporary and then
// die of the signal as before, and ignores SIGPIPE, so that a write to a closed pipe fails with
// EPIPE and the program can end quietly with a non-zero status (apps/common/exit_status.h).
// Programs call it first thing in main(); idempotent.
void handle_signals();

}  // namespace boxgen::support
