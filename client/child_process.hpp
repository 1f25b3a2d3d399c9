// A child process (ffmpeg, for videos) that reads what we write from a pipe on its standard
// input. Its arguments go to it as an argument vector (posix_spawnp), never through a shell,
// so nothing in a file name can run as a command. Its standard output and error are ours: its
// messages reach the user.
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace flagsim {

class ChildProcess {
 public:
  ChildProcess() = default;
  ~ChildProcess();  ///< an unfinished process gets end of input and is waited for
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// Starts `program` (found on PATH) with `arguments`. Returns "" or why it could not start,
  /// naming the program (not installed, say). Writing to it after it exits fails with EPIPE,
  /// not a signal: SIGPIPE is ignored in this process from then on.
  std::string Start(const std::string& program, const std::vector<std::string>& arguments);

  /// Writes all `size` bytes to its input; "" or why not (it stopped reading: see Finish()).
  std::string Write(const uint8_t* data, size_t size);

  /// Ends its input and waits for it; "" if it exited with 0, else how it ended.
  std::string Finish();

  bool running() const { return pid_ > 0; }

 private:
  std::string program_;
  pid_t pid_ = -1;
  int input_ = -1;  ///< the pipe's write end
};

/// The full path of `program` on $PATH, or "" if it is not there (or not executable).
std::string FindOnPath(const std::string& program);

}  // namespace flagsim
