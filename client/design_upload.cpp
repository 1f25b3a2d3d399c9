#include "client/design_upload.hpp"

#include "common/design_image.hpp"
#include "messages/design_pieces.hpp"

namespace flagsim {

std::string CheckDesignFile(const std::vector<uint8_t>& bytes) {
  RgbaImage image;
  return DecodeDesignImage(bytes.data(), bytes.size(), &image);
}

CommandOutcome SendDesignFile(CommandClient& client, const std::string& channel, const std::string& name,
                              const std::vector<uint8_t>& bytes,
                              const std::function<void(int64_t, int64_t)>& progress) {
  const std::string digest = Sha256Hex(bytes.data(), bytes.size());
  CommandOutcome outcome;
  int64_t sent = 0;
  for (const design_piece_t& piece : SplitDesignFile(name, digest, bytes, client.client_id(), 0)) {
    outcome = client.Send(channel, piece);
    if (outcome.result != CommandOutcome::kAccepted) return outcome;
    sent += piece.num_bytes;
    if (progress) progress(sent, int64_t(bytes.size()));
  }
  return outcome;
}

}  // namespace flagsim
