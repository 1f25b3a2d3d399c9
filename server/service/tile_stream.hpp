// The frame stream: each frame is cut into square tiles; the tiles whose pixels changed since
// they were last sent are compressed one by one (zstd of their row residuals, or raw when that
// is smaller) and sent, then a FRAME manifest that lists them and hashes the whole image.
//
//   keyframe         every tile: on request (REFRESH, coalesced), and the first frame of a size
//   rolling refresh  some tiles each frame whether changed or not, round the image in
//                    kRefreshSeconds of frames: a subscriber that joins without asking (a
//                    recorder), or lost tiles and all its requests, has the whole picture by then
//
// Every tile decodes on its own (no state shared between messages), so losing one loses
// that tile only, until it changes or the rolling refresh comes round. Periodic keyframes
// would add nothing the rolling refresh does not give, and stall the stream while they go out.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "flagsim/frame_t.hpp"
#include "flagsim/tile_t.hpp"
#include "server/render/framebuffer.hpp"

namespace flagsim {

/// What a frame's manifest says besides its tiles: when, and the camera it was drawn with.
struct FrameInfo {
  int64_t utime = 0;                                         ///< microseconds since the Unix epoch
  int64_t step = 0;                                          ///< the simulation step drawn
  double sim_time = 0;                                       ///< s
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();        ///< world -> camera
  Eigen::Matrix4d projection = Eigen::Matrix4d::Identity();  ///< camera -> clip
  Eigen::Vector3d camera_eye = Eigen::Vector3d::Zero();      ///< m
  Eigen::Vector3d camera_target = Eigen::Vector3d::Zero();   ///< m, the point looked at
  double camera_fov = 0;                                     ///< degrees, vertical field of view
  double frame_rate = 0;  ///< Hz of simulated time the frames come at; 0: only when asked for
};

/// A tile's place in the image, px.
struct TileBox {
  int x = 0, y = 0, width = 0, height = 0;
};

/// One frame's messages, in publishing order: tiles, then the manifest.
struct EncodedFrame {
  std::vector<tile_t> tiles;
  frame_t manifest{};
  size_t encoded_bytes = 0;  ///< tile payloads, compressed
};

class TileStream {
 public:
  static constexpr double kRefreshSeconds = 1;  ///< s of frames the rolling refresh goes round in
  static constexpr int kMinRollingRefresh = 2;  ///< tiles per frame at the least
  static constexpr int kCompressionLevel = 1;   ///< zstd: fast

  /// px, the side of the stream's square tiles. 128: a 1280 x 720 keyframe is 60 messages (15 ms
  /// at PublishPacing's 4,000 a second; 64 px took 240 and 60 ms), while a frame's changed tiles
  /// compress to about the same bytes (36 KB at 128 px against 35.9 KB at 64 px on the default
  /// breeze: the unchanged sky inside a tile costs next to nothing after row prediction). A raw
  /// tile, 48 KB, still fits one datagram.
  static constexpr int kTileSize = 128;

  explicit TileStream(int tile_size = kTileSize) : tile_size_(tile_size) {}

  /// Makes the next frame a keyframe answering `request_id` (the latest one, if several).
  void RequestKeyframe(int64_t request_id);
  bool keyframe_requested() const { return keyframe_requested_; }

  /// The messages for `image`. Hashing and compression run on `threads` threads; the result
  /// does not depend on how many.
  EncodedFrame Encode(const render::Framebuffer& image, const FrameInfo& info, int threads);

  int tile_size() const { return tile_size_; }
  int64_t frames() const { return next_frame_id_; }

 private:
  TileBox TileRect(int tile_index) const;
  void Resize(int width, int height);
  std::vector<uint64_t> HashTiles(const render::Framebuffer& image, int threads) const;
  int RollingTiles(double frame_rate) const;
  std::vector<int32_t> Choose(const std::vector<uint64_t>& hashes, bool keyframe, int rolling);
  std::vector<tile_t> Compress(const render::Framebuffer& image, const FrameInfo& info,
                               const std::vector<int32_t>& chosen, const std::vector<uint64_t>& hashes,
                               int threads) const;
  frame_t Manifest(const render::Framebuffer& image, const FrameInfo& info, bool keyframe,
                   std::vector<int32_t> chosen);

  int tile_size_;
  int width_ = 0, height_ = 0, tiles_x_ = 0, tiles_y_ = 0;
  std::vector<uint64_t> sent_hash_;  ///< per tile: the pixel hash last sent
  std::vector<bool> ever_sent_;
  int64_t next_frame_id_ = 0;
  size_t rolling_next_ = 0;
  bool keyframe_requested_ = false;
  int64_t request_id_ = -1;
};

/// A tile's pixels as RGB8 rows, width * 3 bytes each, copied out of the image.
void TilePixels(const render::Framebuffer& image, const TileBox& box, std::vector<uint8_t>* pixels);

/// XXH3-64 of bytes, as the messages carry it.
int64_t ImageHash(const uint8_t* data, size_t size);

}  // namespace flagsim
