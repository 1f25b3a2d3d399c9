#include "client/gateway/compressed_image.hpp"

#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <vector>

#include "client/gateway/bus_json.hpp"
#include "common/jpeg_file.hpp"

namespace flagsim::gateway {

std::string EncodeJpeg(const uint8_t* rgb, int width, int height, int quality) {
  return flagsim::EncodeJpeg(rgb, width, height, quality);
}

std::string Base64(std::string_view bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t left = bytes.size() - i;
    uint32_t group = uint32_t(uint8_t(bytes[i])) << 16;
    if (left > 1) group |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (left > 2) group |= uint8_t(bytes[i + 2]);
    out += kAlphabet[(group >> 18) & 63];
    out += kAlphabet[(group >> 12) & 63];
    out += left > 1 ? kAlphabet[(group >> 6) & 63] : '=';
    out += left > 2 ? kAlphabet[group & 63] : '=';
  }
  return out;
}

std::string CompressedImageJson(const std::string& jpeg, int64_t utime) {
  return nlohmann::json{
      {"timestamp", TimeJson(utime)}, {"frame_id", "camera"}, {"data", Base64(jpeg)}, {"format", "jpeg"}}
      .dump();
}

}  // namespace flagsim::gateway
