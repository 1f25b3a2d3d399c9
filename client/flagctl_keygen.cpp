// flagctl keygen: a new key file for signed commands (messages/command_key.hpp). The same file
// goes to flagd --key-file and to each client's --key-file; only its owner can read it.
#include <cstdio>
#include <stdexcept>

#include "client/flagctl_commands.hpp"
#include "messages/command_key.hpp"

namespace flagsim {

int Keygen(const std::string& path, const std::string& name) {
  try {
    WriteNewKeyFile(path, name);
  } catch (const std::runtime_error& error) {
    std::fprintf(stderr, "flagctl: %s\n", error.what());
    return CheckKeyName(name).empty() ? kFailed : kUsage;
  }
  std::printf(
      "%s: key '%s' (32 random bytes), readable by you only.\n"
      "Give it to the server (flagd --key-file %s) and to each client that may steer it\n"
      "(flagctl --key-file %s, also for flagctl serve); copy it only over a private channel.\n",
      path.c_str(), name.c_str(), path.c_str(), path.c_str());
  return kOk;
}

}  // namespace flagsim
