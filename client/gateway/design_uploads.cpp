#include "client/gateway/design_uploads.hpp"

#include <array>

#include "client/design_upload.hpp"
#include "common/design_image.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;

/// "" and the request's name, or what is wrong with it.
std::string NameOf(const json& request, std::string* name) {
  if (!request.is_object()) return "the request must be a JSON object";
  const auto found = request.find("name");
  if (found == request.end() || !found->is_string() || found->get<std::string>().empty())
    return "name: required, a built-in design's name or the image file's name";
  *name = found->get<std::string>();
  return "";
}

/// An integer field 0 .. max; "" or what is wrong.
std::string Integer(const json& request, const char* field, int64_t max, int64_t* value) {
  const auto found = request.find(field);
  if (found == request.end() || !found->is_number_integer() || found->get<int64_t>() < 0 ||
      found->get<int64_t>() > max)
    return std::string(field) + ": required, an integer 0 .. " + std::to_string(max);
  *value = found->get<int64_t>();
  return "";
}

}  // namespace

bool DecodeBase64(const std::string& text, std::vector<uint8_t>* bytes) {
  static const std::array<int8_t, 256> kValue = [] {
    std::array<int8_t, 256> value{};
    value.fill(-1);
    const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < alphabet.size(); ++i) value[uint8_t(alphabet[i])] = int8_t(i);
    return value;
  }();
  if (text.size() % 4 != 0) return false;
  bytes->clear();
  bytes->reserve(text.size() / 4 * 3);
  for (size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    const int pad = last ? (text[i + 3] == '=') + (text[i + 2] == '=') : 0;
    uint32_t group = 0;
    for (int k = 0; k < 4; ++k) {
      const int8_t value = k >= 4 - pad ? 0 : kValue[uint8_t(text[i + size_t(k)])];
      if (value < 0) return false;
      group = group << 6 | uint32_t(value);
    }
    bytes->push_back(uint8_t(group >> 16));
    if (pad < 2) bytes->push_back(uint8_t(group >> 8));
    if (pad < 1) bytes->push_back(uint8_t(group));
  }
  return true;
}

DesignUploads::Step DesignUploads::Take(int client, const json& request) {
  Step step;
  std::string name;
  step.problem = NameOf(request, &name);
  if (!step.problem.empty()) return step;
  if (!request.contains("data")) {  // a built-in design, by name
    step.built_in = name;
    return step;
  }
  int64_t size = 0, offset = 0;
  step.problem = Integer(request, "size", int64_t(kMaxDesignFileBytes), &size);
  if (step.problem.empty()) step.problem = Integer(request, "offset", size, &offset);
  std::vector<uint8_t> part;
  if (step.problem.empty() &&
      (!request["data"].is_string() || !DecodeBase64(request["data"].get<std::string>(), &part)))
    step.problem = "data: must be the part's bytes in base64";
  if (step.problem.empty() &&
      (part.empty() || part.size() > kMaxPartBytes || offset + int64_t(part.size()) > size))
    step.problem = "data: " + std::to_string(part.size()) + " bytes at offset " + std::to_string(offset) +
                   "; allowed 1 .. " + std::to_string(kMaxPartBytes) + " bytes a part, within size " +
                   std::to_string(size);
  if (step.problem.empty() && offset == 0) uploads_[client] = {name, size, {}};
  const auto found = uploads_.find(client);
  if (step.problem.empty() && found == uploads_.end())
    step.problem = "offset: " + std::to_string(offset) + "; no upload of " + name +
                   " is under way: send its parts in order, from offset 0";
  if (step.problem.empty() && (found->second.name != name || found->second.size != size ||
                               int64_t(found->second.bytes.size()) != offset))
    step.problem = "offset: " + std::to_string(offset) + "; the upload of " + found->second.name + " holds " +
                   std::to_string(found->second.bytes.size()) +
                   " bytes: send its parts in order, from offset 0";
  if (!step.problem.empty()) {
    uploads_.erase(client);
    return step;
  }
  Upload& upload = found->second;
  upload.bytes.insert(upload.bytes.end(), part.begin(), part.end());
  step.held = int64_t(upload.bytes.size());
  step.size = size;
  if (step.held < size) return step;
  step.problem = CheckDesignFile(upload.bytes);
  if (step.problem.empty()) {
    step.whole = true;
    step.name = upload.name;
    step.bytes = std::move(upload.bytes);
  } else {
    step.problem = name + ": " + step.problem;
  }
  uploads_.erase(client);
  return step;
}

}  // namespace flagsim::gateway
