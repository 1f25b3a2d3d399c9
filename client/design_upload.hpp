// A person's image sent to a server as the flag's design: checked here first (the limits and a
// whole decode, as the server will), then its pieces one after another on DESIGN, each resent
// until answered (CommandClient). The last piece's answer says whether the server shows it.
//
//   file => checked => SHA-256 => pieces (design_pieces.hpp) => each sent, ACK awaited => outcome
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "client/command_client.hpp"

namespace flagsim {

/// "" if `bytes` make a design the server will take (common/design_image.hpp), else what is
/// wrong and the limits; the server checks again all the same.
std::string CheckDesignFile(const std::vector<uint8_t>& bytes);

/// Sends `bytes`, named `name`, piece by piece; stops at the first piece refused or unanswered
/// and returns that outcome, else the last piece's (accepted: the design is shown from its
/// step). `progress(bytes sent, total)` after each piece, if given.
CommandOutcome SendDesignFile(CommandClient& client, const std::string& channel, const std::string& name,
                              const std::vector<uint8_t>& bytes,
                              const std::function<void(int64_t, int64_t)>& progress = nullptr);

}  // namespace flagsim
