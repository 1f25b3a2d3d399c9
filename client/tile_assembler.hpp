// Turning the TILE and FRAME streams back into pictures. Tiles are decoded on arrival
// (each on its own) and written into the image; a FRAME manifest then says which tiles its
// frame sent and the hash of the whole image, so the assembler knows when its picture is
// exactly the server's. Losses heal as tiles change, on the rolling refresh, or on a keyframe.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "flagsim/frame_t.hpp"
#include "flagsim/tile_t.hpp"

namespace flagsim {

class TileAssembler {
 public:
  /// px: larger frames are refused. The server draws none larger (render::CameraMove's limits).
  static constexpr int kMaxWidth = 3840, kMaxHeight = 2160;
  /// Tiles in a frame's grid: a manifest asking for more is refused (the server's tiles are 128 px,
  /// 510 of them at the largest size), so that a few bytes never claim gigabytes of tile records.
  static constexpr int kMaxTiles = 8192;
  static constexpr size_t kMaxKept = kMaxTiles;  ///< tiles kept of the latest frame

  /// Decodes `tile` into the image. Returns "" or why it was refused (undecodable, wrong size,
  /// pixel hash mismatch): then the image is unchanged. The latest frame's tiles are also
  /// kept until its manifest comes, which may bring a new image size they belong to.
  std::string AddTile(const tile_t& tile);

  enum class FrameResult {
    kComplete,    ///< the image now equals the server's frame, hash checked
    kIncomplete,  ///< some tiles are missing or stale: wait for more, or ask for a keyframe
    kRefused,     ///< the manifest makes no sense (size or tile count out of range)
  };
  /// Checks the image against a manifest (and adopts its size, if new).
  FrameResult AddManifest(const frame_t& manifest);

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<uint8_t>& image() const { return image_; }  ///< RGB8, rows top to bottom
  int64_t last_complete_frame() const { return last_complete_frame_; }
  /// Per tile index (row-major): the tile whose pixels are in the image, as it came
  /// (compressed); frame_id -1 where none came yet. A complete frame's tiles, resent as they are.
  const std::vector<tile_t>& placed_tiles() const { return placed_; }

 private:
  void Resize(int width, int height, int tile_size);
  std::string Place(const tile_t& tile);

  int width_ = 0, height_ = 0, tile_size_ = 0;
  std::vector<uint8_t> image_;
  std::vector<tile_t> placed_;  ///< per tile: the one whose pixels the image holds
  std::vector<tile_t> latest_;  ///< the tiles of the newest frame seen
  int64_t latest_frame_ = -1;
  int64_t last_complete_frame_ = -1;
};

}  // namespace flagsim
