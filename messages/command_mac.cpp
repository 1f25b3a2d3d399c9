#include "messages/command_mac.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>

#include <stdexcept>

namespace flagsim {

Mac ComputeMac(const CommandKey& key, const std::string& channel, const uint8_t* encoded, size_t size) {
  // One message, three parts: the channel, a separator no channel name holds, the encoding.
  std::vector<uint8_t> message(channel.begin(), channel.end());
  message.push_back(0);
  message.insert(message.end(), encoded, encoded + size);
  Mac mac{};
  unsigned int length = 0;
  if (HMAC(EVP_sha256(), key.secret.data(), static_cast<int>(key.secret.size()), message.data(),
           message.size(), mac.data(), &length) == nullptr ||
      length != mac.size())
    throw std::runtime_error("HMAC-SHA-256 failed");
  return mac;
}

bool MacMatches(const Mac& expected, const uint8_t* carried) {
  return CRYPTO_memcmp(expected.data(), carried, expected.size()) == 0;
}

}  // namespace flagsim
