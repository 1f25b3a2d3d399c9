// The binary frames of the Foxglove WebSocket protocol (foxglove.websocket.v1): a one-byte
// opcode, then little-endian fields. The server's frames are built here; the client's are
// parsed here with every length checked against the bytes received.
//
//   server  0x01 Message Data           u32 subscription, u64 timestamp (ns), payload
//           0x03 Service Call Response  u32 service, u32 call, u32 n, encoding[n], payload
//   client  0x01 Client Message Data    u32 channel, payload
//           0x02 Service Call Request   u32 service, u32 call, u32 n, encoding[n], payload
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace flagsim::gateway {

enum ServerOpcode : uint8_t { kMessageData = 1, kServiceCallResponse = 3 };
enum ClientOpcode : uint8_t { kClientMessageData = 1, kServiceCallRequest = 2 };

/// The 13 bytes that precede a payload in a Message Data frame.
std::string MessageDataHead(uint32_t subscription, uint64_t timestamp_ns);

/// A whole Service Call Response frame.
std::string ServiceCallResponse(uint32_t service, uint32_t call, std::string_view encoding,
                                std::string_view payload);

/// A client's binary frame, parsed; the views point into the frame.
struct ClientBinary {
  uint8_t opcode = 0;
  uint32_t channel = 0;       ///< Client Message Data: the client's channel id
  uint32_t service = 0;       ///< Service Call Request
  uint32_t call = 0;          ///< Service Call Request: the client's call id
  std::string_view encoding;  ///< Service Call Request
  std::string_view payload;
};

/// Parses a client's binary frame; nullopt with *error (what was wrong, in bytes) if it is not one.
std::optional<ClientBinary> ParseClientBinary(std::string_view frame, std::string* error);

/// Appends `value` little-endian.
void AppendU16(std::string* out, uint16_t value);
void AppendU32(std::string* out, uint32_t value);
void AppendU64(std::string* out, uint64_t value);

}  // namespace flagsim::gateway
