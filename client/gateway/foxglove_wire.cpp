#include "client/gateway/foxglove_wire.hpp"

namespace flagsim::gateway {
namespace {

uint32_t ReadU32(std::string_view bytes, size_t at) {
  uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = (value << 8) | static_cast<uint8_t>(bytes[at + k]);
  return value;
}

template <class Unsigned>
void AppendLittleEndian(std::string* out, Unsigned value) {
  for (size_t k = 0; k < sizeof(Unsigned); ++k) out->push_back(static_cast<char>((value >> (8 * k)) & 0xff));
}

}  // namespace

void AppendU16(std::string* out, uint16_t value) { AppendLittleEndian(out, value); }
void AppendU32(std::string* out, uint32_t value) { AppendLittleEndian(out, value); }
void AppendU64(std::string* out, uint64_t value) { AppendLittleEndian(out, value); }

std::string MessageDataHead(uint32_t subscription, uint64_t timestamp_ns) {
  std::string head(1, static_cast<char>(kMessageData));
  AppendU32(&head, subscription);
  AppendU64(&head, timestamp_ns);
  return head;
}

std::string ServiceCallResponse(uint32_t service, uint32_t call, std::string_view encoding,
                                std::string_view payload) {
  std::string frame(1, static_cast<char>(kServiceCallResponse));
  AppendU32(&frame, service);
  AppendU32(&frame, call);
  AppendU32(&frame, static_cast<uint32_t>(encoding.size()));
  frame.append(encoding);
  frame.append(payload);
  return frame;
}

std::optional<ClientBinary> ParseClientBinary(std::string_view frame, std::string* error) {
  ClientBinary message;
  if (frame.empty()) {
    *error = "an empty binary message";
    return std::nullopt;
  }
  message.opcode = static_cast<uint8_t>(frame[0]);
  if (message.opcode == kClientMessageData) {
    if (frame.size() < 5) {
      *error = "Client Message Data of " + std::to_string(frame.size()) + " bytes; at least 5 needed";
      return std::nullopt;
    }
    message.channel = ReadU32(frame, 1);
    message.payload = frame.substr(5);
    return message;
  }
  if (message.opcode == kServiceCallRequest) {
    if (frame.size() < 13) {
      *error = "Service Call Request of " + std::to_string(frame.size()) + " bytes; at least 13 needed";
      return std::nullopt;
    }
    message.service = ReadU32(frame, 1);
    message.call = ReadU32(frame, 5);
    const uint32_t length = ReadU32(frame, 9);
    if (length > frame.size() - 13) {
      *error = "Service Call Request's encoding claims " + std::to_string(length) + " bytes; " +
               std::to_string(frame.size() - 13) + " follow";
      return std::nullopt;
    }
    message.encoding = frame.substr(13, length);
    message.payload = frame.substr(13 + length);
    return message;
  }
  *error = "binary opcode " + std::to_string(message.opcode) +
           " is not a client's; allowed 1 (Client Message Data), 2 (Service Call Request)";
  return std::nullopt;
}

}  // namespace flagsim::gateway
