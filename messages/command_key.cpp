#include "messages/command_key.hpp"

#include <fcntl.h>
#include <openssl/rand.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <set>
#include <sstream>
#include <stdexcept>

namespace flagsim {
namespace {

std::runtime_error FileError(const std::string& path, const std::string& what) {
  return std::runtime_error("key file " + path + ": " + what);
}

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// Reads the secret from its hex digits; false if `hex` is not 2 * kBytes of them.
bool ParseSecret(const std::string& hex, std::array<uint8_t, CommandKey::kBytes>* secret) {
  if (hex.size() != 2 * CommandKey::kBytes) return false;
  for (size_t k = 0; k < CommandKey::kBytes; ++k) {
    const int high = HexDigit(hex[2 * k]), low = HexDigit(hex[2 * k + 1]);
    if (high < 0 || low < 0) return false;
    (*secret)[k] = static_cast<uint8_t>(16 * high + low);
  }
  return true;
}

/// The whole file, read through a descriptor whose permissions are checked first.
std::string ReadPrivateFile(const std::string& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw FileError(path, std::strerror(errno));
  struct stat info {};
  if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    close(fd);
    throw FileError(path, "not a regular file");
  }
  if ((info.st_mode & 077) != 0) {
    close(fd);
    char mode[8];
    std::snprintf(mode, sizeof(mode), "%04o", static_cast<unsigned>(info.st_mode & 07777));
    throw FileError(path, std::string("mode ") + mode +
                              " lets its group or others read or write it; allowed: the owner only "
                              "(chmod 600 " +
                              path + ")");
  }
  std::string text;
  char buffer[4096];
  ssize_t got;
  while ((got = read(fd, buffer, sizeof(buffer))) > 0) text.append(buffer, static_cast<size_t>(got));
  close(fd);
  if (got < 0) throw FileError(path, std::strerror(errno));
  return text;
}

}  // namespace

std::string CheckKeyName(const std::string& name) {
  if (name.empty() || name.size() > CommandKey::kMaxNameLength)
    return "key name '" + name + "': " + std::to_string(name.size()) + " characters; allowed 1 .. " +
           std::to_string(CommandKey::kMaxNameLength);
  for (const char c : name) {
    const bool allowed = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                         c == '_' || c == '.' || c == '-';
    if (!allowed) return "key name '" + name + "': allowed letters, digits, '_', '.' and '-'";
  }
  return "";
}

std::vector<CommandKey> ReadKeyFile(const std::string& path) {
  std::istringstream lines(ReadPrivateFile(path));
  std::vector<CommandKey> keys;
  std::set<std::string> names;
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    std::istringstream words(line);
    CommandKey key;
    std::string hex, extra;
    if (!(words >> key.name) || key.name[0] == '#') continue;
    const std::string where = "line " + std::to_string(number) + ": ";
    const std::string bad_name = CheckKeyName(key.name);
    if (!bad_name.empty()) throw FileError(path, where + bad_name);
    if (!(words >> hex) || (words >> extra) || !ParseSecret(hex, &key.secret))
      throw FileError(path, where + "allowed: NAME and " + std::to_string(2 * CommandKey::kBytes) +
                                " hex digits (flagctl keygen writes them)");
    if (!names.insert(key.name).second) throw FileError(path, where + "key '" + key.name + "' again");
    keys.push_back(key);
  }
  if (keys.empty()) throw FileError(path, "no key in it (flagctl keygen -o FILE makes one)");
  return keys;
}

CommandKey WriteNewKeyFile(const std::string& path, const std::string& name) {
  const std::string bad_name = CheckKeyName(name);
  if (!bad_name.empty()) throw std::runtime_error(bad_name);
  CommandKey key;
  key.name = name;
  if (RAND_bytes(key.secret.data(), static_cast<int>(key.secret.size())) != 1)
    throw std::runtime_error("no random bytes for a key from the system");
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0)
    throw FileError(path, errno == EEXIST ? "exists; a new key never overwrites one" : std::strerror(errno));
  std::string text = "# flagsim command keys: NAME HEX, one per line; keep this file private (mode 600)\n";
  text += name + " ";
  char digits[3];
  for (const uint8_t byte : key.secret) {
    std::snprintf(digits, sizeof(digits), "%02x", byte);
    text += digits;
  }
  text += "\n";
  const bool written = write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const bool closed = close(fd) == 0;
  if (!written || !closed) {
    unlink(path.c_str());
    throw FileError(path, "could not be written");
  }
  return key;
}

}  // namespace flagsim
