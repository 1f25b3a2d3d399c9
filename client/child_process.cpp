#include "client/child_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>

extern char** environ;

namespace flagsim {
namespace {

/// posix_spawn's attributes and file actions, released however Start leaves.
struct SpawnSetup {
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attributes);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
  }
};

}  // namespace

std::string FindOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string directories = path != nullptr ? path : "/usr/bin:/bin";
  size_t start = 0;
  while (start <= directories.size()) {
    const size_t end = std::min(directories.find(':', start), directories.size());
    const std::string directory = end > start ? directories.substr(start, end - start) : ".";
    const std::string candidate = directory + "/" + program;
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return "";
}

// pipe => child: its read end as stdin, SIGPIPE back to default => exec; we keep the write end
std::string ChildProcess::Start(const std::string& program, const std::vector<std::string>& arguments) {
  program_ = program;
  if (FindOnPath(program).empty()) {
    return program + " is not installed (not found on PATH)";
  }
  int ends[2];
  if (pipe2(ends, O_CLOEXEC) != 0) return std::string("cannot make a pipe: ") + std::strerror(errno);
  std::signal(SIGPIPE, SIG_IGN);  // a child that exits early must not kill us as we write
  SpawnSetup setup;
  posix_spawn_file_actions_adddup2(&setup.actions, ends[0], STDIN_FILENO);  // dup2 clears CLOEXEC
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&setup.attributes, &defaults);
  posix_spawnattr_setflags(&setup.attributes, POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  const int failed =
      posix_spawnp(&pid_, program.c_str(), &setup.actions, &setup.attributes, argv.data(), environ);
  close(ends[0]);
  if (failed != 0) {
    close(ends[1]);
    pid_ = -1;
    return "cannot start " + program + ": " + std::strerror(failed);
  }
  input_ = ends[1];
  return "";
}

std::string ChildProcess::Write(const uint8_t* data, size_t size) {
  if (input_ < 0) return program_ + " is not running";
  while (size > 0) {
    const ssize_t written = write(input_, data, size);
    if (written < 0 && errno == EINTR) continue;
    if (written < 0) {
      return errno == EPIPE ? program_ + " stopped reading its input"
                            : std::string("writing to ") + program_ + " failed: " + std::strerror(errno);
    }
    data += written;
    size -= size_t(written);
  }
  return "";
}

std::string ChildProcess::Finish() {
  if (input_ >= 0) close(input_);
  input_ = -1;
  if (pid_ <= 0) return "";
  int status = 0;
  pid_t waited;
  do {
    waited = waitpid(pid_, &status, 0);
  } while (waited < 0 && errno == EINTR);
  pid_ = -1;
  if (waited < 0) return std::string("cannot wait for ") + program_ + ": " + std::strerror(errno);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  if (WIFEXITED(status)) return program_ + " failed (exit code " + std::to_string(WEXITSTATUS(status)) + ")";
  return program_ + " was killed by signal " + std::to_string(WTERMSIG(status));
}

ChildProcess::~ChildProcess() { Finish(); }

}  // namespace flagsim
