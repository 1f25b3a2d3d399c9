// A file in memory for the targets whose entry point reads a path (logs, PNGs, key files): each
// input is written into an anonymous memory file (memfd_create), named by /proc/self/fd/N,
// which the code under test opens, stats and reads like any file. No disk, nothing left behind.
#pragma once

#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace flagsim::fuzz {

class ScratchFile {
 public:
  /// `mode`: the file's permission bits (a key file must be the owner's alone).
  explicit ScratchFile(const char* name, mode_t mode = 0600) : fd_(memfd_create(name, MFD_CLOEXEC)) {
    if (fd_ < 0 || fchmod(fd_, mode) != 0) {
      std::perror("memfd_create");
      std::abort();
    }
    path_ = "/proc/self/fd/" + std::to_string(fd_);
  }
  ~ScratchFile() { close(fd_); }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  /// Makes `size` bytes the whole file; returns its path.
  const std::string& Hold(const uint8_t* data, size_t size) {
    if (ftruncate(fd_, 0) != 0 || (size > 0 && pwrite(fd_, data, size, 0) != ssize_t(size))) {
      std::perror("scratch file");
      std::abort();
    }
    return path_;
  }

 private:
  int fd_;
  std::string path_;
};

}  // namespace flagsim::fuzz
