// The newest whole frame of the bus, kept as the server's own compressed tiles, and what each
// client needs to catch up with it.
//
//   TILE, FRAME ==> TileAssembler (hash-checked) ==> MirroredFrame (per tile: pixel hash and
//   the tile's record, encoded once) ==> per client: the records whose hash differs from the
//   ones that client was last sent (its ClientTiles), in one flagsim.TileUpdate
//
// A client that takes every update has exactly the server's frame; a slow one skips frames
// but never lags, since each update takes it straight to the newest (docs/live-view.md).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "client/tile_assembler.hpp"
#include "flagsim/frame_t.hpp"
#include "flagsim/tile_t.hpp"

namespace flagsim::gateway {

struct MirroredFrame {
  uint64_t sequence = 0;  ///< 1, 2, ...: the whole frames this mirror has made
  int64_t utime = 0;      ///< server time of the manifest, us since the Unix epoch
  int64_t frame_id = -1;
  int64_t step = 0;
  double sim_time = 0;                                           ///< s
  int width = 0, height = 0, tile_size = 0;                      ///< px
  uint64_t frame_hash = 0;                                       ///< XXH3-64 of the RGB8 image
  std::vector<uint64_t> tile_hashes;                             ///< per tile index
  std::vector<std::shared_ptr<const std::string>> tile_records;  ///< per tile: its TileUpdate record
  std::shared_ptr<const std::vector<uint8_t>> image;             ///< RGB8, only while images are wanted
};

/// What one client was last sent: the frame (by the mirror's sequence: frame ids start again
/// with a new server) and each tile's pixel hash.
struct ClientTiles {
  uint64_t sequence = 0;
  int width = 0, height = 0, tile_size = 0;
  std::vector<uint64_t> hashes;
  /// Forget everything: the next update is a keyframe.
  void Reset() { *this = ClientTiles{}; }
};

class FrameMirror {
 public:
  /// The assembler's verdict on a manifest, for the caller's counters.
  enum class Result { kComplete, kIncomplete, kRefused };

  void AddTile(const tile_t& tile) { assembler_.AddTile(tile); }
  Result AddManifest(const frame_t& manifest);

  /// The newest whole frame; null before the first.
  std::shared_ptr<const MirroredFrame> latest() const { return latest_; }
  /// Whether frames keep a copy of their image (for the JPEG channel).
  void KeepImages(bool keep) { keep_images_ = keep; }
  /// A new server on the bus: its frame ids start again from 0, so the tiles and the frame of
  /// the old one are forgotten (else the new one's would be taken for older and skipped, until
  /// its ids passed the old one's), and nothing is mirrored until its first whole frame.
  void ServerRestarted();

 private:
  void Mirror(const frame_t& manifest);

  TileAssembler assembler_;
  std::shared_ptr<const MirroredFrame> latest_;
  uint64_t frames_ = 0;
  bool keep_images_ = false;
};

/// The flagsim.TileUpdate that takes `client` to `frame`, updating `client`; null if it
/// has this frame already.
std::shared_ptr<const std::string> TileUpdateFor(const MirroredFrame& frame, ClientTiles* client);

/// One tile's record in a TileUpdate (docs/live-view.md).
std::string TileRecord(int index, const tile_t& tile);

}  // namespace flagsim::gateway
