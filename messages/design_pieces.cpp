#include "messages/design_pieces.hpp"

#include <algorithm>

namespace flagsim {

std::vector<design_piece_t> SplitDesignFile(const std::string& name, const std::string& digest,
                                            const std::vector<uint8_t>& bytes, const std::string& client_id,
                                            int64_t utime) {
  constexpr int64_t kPiece = design_piece_t::PIECE_BYTES;
  std::vector<design_piece_t> pieces;
  const int64_t total = int64_t(bytes.size());
  for (int64_t offset = 0; offset < total; offset += kPiece) {
    design_piece_t piece{};
    piece.utime = utime;
    piece.client_id = client_id;
    piece.name = name;
    piece.digest = digest;
    piece.total_bytes = int32_t(total);
    piece.offset = int32_t(offset);
    piece.num_bytes = int32_t(std::min(kPiece, total - offset));
    piece.data.assign(bytes.begin() + offset, bytes.begin() + offset + piece.num_bytes);
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

}  // namespace flagsim
