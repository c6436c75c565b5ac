// Where an output file may go, and writing it so that nothing is ever lost or written half.
// Both programs write through this module: boxrecon's volumes and grids (nrrd_io.h) and boxgen's
// emitted headers.
//
// The rules, as a user who types `-o PATH` expects them:
//   - a symbolic link is written through: its final target receives the data, the link stays a
//     link (a dangling link creates its target, as the shell's `>` does);
//   - the target must be a regular file or not exist yet: a directory, FIFO, socket or device
//     (`-o /dev/full`, `-o /dev/null`) is refused, never replaced;
//   - an output that is one of the inputs (the same file by another path, a link or a hard link)
//     is refused before any work, so a failure can never leave the input destroyed;
//   - the data goes to a temporary file in the target's directory, which is renamed over the
//     target once complete (and flushed to disk): a failed write leaves the old file as it was.
//     An existing target keeps its permission bits.
#pragma once
#include <cstdio>
#include <filesystem>
#include <functional>
#include <span>
#include <stdexcept>

namespace boxgen::runtime {

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

// Writes the file through `fill`, which returns false on failure, and renames it into place as
// described above. `describe_failure` (may be empty) gives the reason when `fill` returns false.
// Throws OutputFileError (one line); the target is then left as it was and no temporary remains.
void write_output_file(const std::filesystem::path& path,
                       const std::function<bool(std::FILE*)>& fill,
                       const std::function<std::string()>& describe_failure = {});

}  // namespace boxgen::runtime
