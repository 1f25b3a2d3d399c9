// Decoding bytes from the bus that nobody vouches for. Size, fingerprint and every array length
// are checked before lcm-gen's decode runs (see wire_schema.hpp), and decode runs inside a try.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace flagsim::wire {

/// Checks `size` bytes claimed to be an encoded `type_name` with fingerprint `hash`.
/// Returns "" if they may be decoded, otherwise the reason they may not.
std::string CheckEncoded(const char* type_name, int64_t hash, const uint8_t* data, size_t size,
                         size_t max_size);

/// Decodes a Message from untrusted bytes; nullopt (with *error set) if they are not one.
template <class Message>
std::optional<Message> CheckedDecode(const uint8_t* data, size_t size, size_t max_size, std::string* error) {
  *error = CheckEncoded(Message::getTypeName(), Message::getHash(), data, size, max_size);
  if (!error->empty()) return std::nullopt;
  Message message;
  try {
    const int used = message.decode(data, 0, static_cast<int>(size));
    if (used == static_cast<int>(size)) return message;
    *error = std::string("not a valid ") + Message::getTypeName();
  } catch (const std::exception& exception) {
    *error = std::string("not a valid ") + Message::getTypeName() + ": " + exception.what();
  }
  return std::nullopt;
}

}  // namespace flagsim::wire
