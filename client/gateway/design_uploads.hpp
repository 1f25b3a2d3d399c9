// The page's way to change the flag's design (/flag/design): a built-in design by name, or a
// person's image uploaded in parts that each fit a WebSocket message, in order, base64 in JSON:
//
//   {"name": "checker"}                                          => PARAM design=checker
//   {"name": "flag.png", "size": N, "offset": K, "data": BASE64}  => part K .. K + len of N bytes
//
// Each client has at most one upload under way; a part at offset 0 starts it again. When the
// last part arrives the whole file is checked (client/design_upload.hpp) and handed back, to be
// sent to the server in DESIGN pieces. Parts are refused with what is wrong and what is allowed.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace flagsim::gateway {

class DesignUploads {
 public:
  static constexpr size_t kMaxPartBytes =
      144 * 1024;  ///< decoded: 192 KiB of base64, within a WebSocket message

  struct Step {
    std::string problem;   ///< "" or why the request is refused (the upload is dropped)
    std::string built_in;  ///< a built-in design's name: set it by PARAM
    bool whole = false;    ///< the last part came: `name` and `bytes` are the checked file
    std::string name;
    std::vector<uint8_t> bytes;
    int64_t held = 0, size = 0;  ///< an upload under way: bytes held so far, of size
  };

  /// Takes one request of `client`.
  Step Take(int client, const nlohmann::json& request);
  /// The client has gone: its upload with it.
  void Drop(int client) { uploads_.erase(client); }

 private:
  struct Upload {
    std::string name;
    int64_t size = 0;
    std::vector<uint8_t> bytes;
  };
  std::map<int, Upload> uploads_;
};

/// RFC 4648 base64 (padding required, no line breaks) into `*bytes`; false if `text` is not that.
bool DecodeBase64(const std::string& text, std::vector<uint8_t>* bytes);

}  // namespace flagsim::gateway
