// Writing a figure without ever leaving half a file: the data goes to a temporary file in the
// destination's directory, which is renamed over the destination only when complete.
#pragma once
#include <string>

namespace boxgen::analysis {

class AtomicOutput {
 public:
  // Creates the temporary file next to `path` at once, so an unwritable destination fails
  // before any work: throws std::invalid_argument (one line) naming the path.
  explicit AtomicOutput(std::string path);
  ~AtomicOutput();  // removes the temporary file unless commit() succeeded
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  const std::string& temporary() const { return temporary_; }
  // Renames the temporary file to the destination; throws std::runtime_error on failure or if
  // the temporary file is empty.
  void commit();

 private:
  std::string path_, temporary_;
  bool committed_ = false;
};

}  // namespace boxgen::analysis
