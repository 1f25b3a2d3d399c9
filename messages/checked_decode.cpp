#include "messages/checked_decode.hpp"

#include "messages/wire_schema.hpp"

namespace flagsim::wire {

std::string CheckEncoded(const char* type_name, int64_t hash, const uint8_t* data, size_t size,
                         size_t max_size) {
  if (size > max_size) {
    return std::to_string(size) + " bytes is over the " + std::to_string(max_size) + "-byte limit for " +
           type_name;
  }
  if (size < 8) return "truncated: " + std::to_string(size) + " bytes";
  uint64_t fingerprint = 0;  // big-endian, as LCM writes it
  for (int i = 0; i < 8; ++i) fingerprint = (fingerprint << 8) | data[i];
  if (static_cast<int64_t>(fingerprint) != hash) {
    return std::string("wrong type fingerprint: not a ") + type_name;
  }
  return Schema::Flagsim().CheckWire(type_name, data, size);
}

}  // namespace flagsim::wire
