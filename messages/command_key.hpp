// Shared keys that sign commands (flagd --key-file, flagctl --key-file, flagctl keygen).
//
// A key file holds one or more named keys, one per line: a name, then 64 hex digits (32 bytes
// from the system's random source). Blank lines and lines starting with '#' are ignored. Only
// its owner may read it: a key file that its group or others can read or write is refused, as
// ssh refuses a private key with loose permissions.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace flagsim {

struct CommandKey {
  static constexpr size_t kBytes = 32;  ///< HMAC-SHA-256 keys as long as its output
  static constexpr size_t kMaxNameLength = 32;

  std::string name;                      ///< what commands name it by (key_id): [A-Za-z0-9_.-]
  std::array<uint8_t, kBytes> secret{};  ///< never printed, logged or published
};

/// "" if `name` may name a key, else what is wrong and what is allowed.
std::string CheckKeyName(const std::string& name);

/// The keys in the key file `path`. Throws std::runtime_error naming the file (and the line)
/// when it cannot be read, has loose permissions, holds a malformed line or a name twice, or
/// holds no key.
std::vector<CommandKey> ReadKeyFile(const std::string& path);

/// A new random key named `name`, written to the new file `path` with mode 0600. Never
/// overwrites: throws std::runtime_error naming the file if it exists or cannot be written.
CommandKey WriteNewKeyFile(const std::string& path, const std::string& name);

}  // namespace flagsim
