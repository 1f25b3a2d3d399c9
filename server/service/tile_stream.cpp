#include "server/service/tile_stream.hpp"

#include <xxhash.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "messages/tile_prediction.hpp"
#include "server/parallel/worker_pool.hpp"

namespace flagsim {
namespace {

struct ZstdContextDeleter {
  void operator()(ZSTD_CCtx* context) const { ZSTD_freeCCtx(context); }
};

/// This thread's compression context, kept for its life: a new one per tile or frame would
/// allocate (and fault in) its working memory each time, which cost a keyframe several ms.
ZSTD_CCtx* ThreadCompressor() {
  thread_local const std::unique_ptr<ZSTD_CCtx, ZstdContextDeleter> context(ZSTD_createCCtx());
  return context.get();
}

/// tile_t with the pixels of `box`: zstd of their row residuals (tile_prediction.hpp) when that
/// is smaller, else raw. The working buffers are this thread's, kept: allocating a keyframe's
/// worth afresh (and the heap handing it back between keyframes) cost several ms of page faults.
tile_t EncodeTile(const render::Framebuffer& image, const TileBox& box) {
  thread_local std::vector<uint8_t> pixels, residuals, compressed;
  TilePixels(image, box, &pixels);
  PredictRows(pixels, box.width, &residuals);
  compressed.resize(ZSTD_compressBound(residuals.size()));
  const size_t size = ZSTD_compressCCtx(ThreadCompressor(), compressed.data(), compressed.size(),
                                        residuals.data(), residuals.size(), TileStream::kCompressionLevel);
  tile_t tile{};
  if (!ZSTD_isError(size) && size < pixels.size()) {
    tile.encoding = tile_t::ZSTD_UP_RGB8;
    tile.data.assign(compressed.begin(), compressed.begin() + std::ptrdiff_t(size));
  } else {
    tile.encoding = tile_t::RAW_RGB8;
    tile.data = pixels;
  }
  tile.num_bytes = static_cast<int32_t>(tile.data.size());
  return tile;
}

/// XXH3-64 of the tile's rows copied out back to back (TilePixels, into this thread's kept
/// buffer): one pass of the one-shot hash over the tile instead of the streaming hash fed
/// 192-byte rows (with the hash inlined, a frame's encoding takes about half the time:
/// bench/tile_bench.cpp, docs/benchmarks.md).
uint64_t TileHash(const render::Framebuffer& image, const TileBox& box) {
  thread_local std::vector<uint8_t> pixels;
  TilePixels(image, box, &pixels);
  return XXH3_64bits(pixels.data(), pixels.size());
}

}  // namespace

TileBox TileStream::TileRect(int t) const {
  TileBox box;
  box.x = (t % tiles_x_) * tile_size_;
  box.y = (t / tiles_x_) * tile_size_;
  box.width = std::min(tile_size_, width_ - box.x);
  box.height = std::min(tile_size_, height_ - box.y);
  return box;
}

int64_t ImageHash(const uint8_t* data, size_t size) { return static_cast<int64_t>(XXH3_64bits(data, size)); }

void TilePixels(const render::Framebuffer& image, const TileBox& box, std::vector<uint8_t>* pixels) {
  const size_t row_bytes = size_t(box.width) * 3;
  pixels->resize(row_bytes * box.height);
  for (int row = 0; row < box.height; ++row) {
    const uint8_t* source = image.Pixel(box.x, box.y + row);
    std::copy(source, source + row_bytes, pixels->begin() + std::ptrdiff_t(row * row_bytes));
  }
}

void TileStream::RequestKeyframe(int64_t request_id) {
  keyframe_requested_ = true;
  request_id_ = request_id;
}

// image => per-tile hashes => the tiles to send (changed, keyframe, rolling) => compressed => manifest
EncodedFrame TileStream::Encode(const render::Framebuffer& image, const FrameInfo& info, int threads) {
  if (image.width != width_ || image.height != height_) Resize(image.width, image.height);
  const bool keyframe =
      keyframe_requested_ || std::find(ever_sent_.begin(), ever_sent_.end(), false) != ever_sent_.end();
  const std::vector<uint64_t> hashes = HashTiles(image, threads);
  EncodedFrame frame;
  std::vector<int32_t> chosen = Choose(hashes, keyframe, RollingTiles(info.frame_rate));
  frame.tiles = Compress(image, info, chosen, hashes, threads);
  for (const tile_t& tile : frame.tiles) frame.encoded_bytes += tile.data.size();
  frame.manifest = Manifest(image, info, keyframe, std::move(chosen));
  if (keyframe) keyframe_requested_ = false;
  return frame;
}

// A new size: every tile is new, so the next frame is a keyframe.
void TileStream::Resize(int width, int height) {
  width_ = width;
  height_ = height;
  tiles_x_ = (width_ + tile_size_ - 1) / tile_size_;
  tiles_y_ = (height_ + tile_size_ - 1) / tile_size_;
  sent_hash_.assign(size_t(tiles_x_) * tiles_y_, 0);
  ever_sent_.assign(sent_hash_.size(), false);
  rolling_next_ = 0;
}

// Every tile's pixel hash, where it lies in the image.
std::vector<uint64_t> TileStream::HashTiles(const render::Framebuffer& image, int threads) const {
  const int tiles = tiles_x_ * tiles_y_;
  std::vector<uint64_t> hashes(tiles);
  ParallelFor(tiles, threads, [&](int t) { hashes[t] = TileHash(image, TileRect(t)); });
  return hashes;
}

// Tiles per frame that take the rolling refresh round the image in kRefreshSeconds of frames
// (frame rate 0, frames only when asked for: each is a keyframe anyway).
int TileStream::RollingTiles(double frame_rate) const {
  const int tiles = tiles_x_ * tiles_y_;
  const double frames = frame_rate * kRefreshSeconds;
  const int rolling = frames >= 1 ? int(std::ceil(tiles / frames)) : kMinRollingRefresh;
  return std::clamp(rolling, std::min(kMinRollingRefresh, tiles), tiles);
}

// The tiles to send: all of a keyframe, else those changed since they were last sent and the
// rolling refresh's next `rolling`. They count as sent from here.
std::vector<int32_t> TileStream::Choose(const std::vector<uint64_t>& hashes, bool keyframe, int rolling) {
  const int tiles = static_cast<int>(hashes.size());
  std::vector<int32_t> chosen;
  for (int t = 0; t < tiles; ++t) {
    const bool refresh = (size_t(t) + tiles - rolling_next_) % tiles < size_t(rolling);
    if (keyframe || refresh || hashes[t] != sent_hash_[t]) chosen.push_back(t);
  }
  rolling_next_ = (rolling_next_ + rolling) % tiles;
  for (const int32_t t : chosen) {
    sent_hash_[t] = hashes[t];
    ever_sent_[t] = true;
  }
  return chosen;
}

// The chosen tiles' messages, each compressed on its own.
std::vector<tile_t> TileStream::Compress(const render::Framebuffer& image, const FrameInfo& info,
                                         const std::vector<int32_t>& chosen,
                                         const std::vector<uint64_t>& hashes, int threads) const {
  std::vector<tile_t> tiles(chosen.size());
  const int count = static_cast<int>(chosen.size());
  ParallelFor(count, threads, [&](int i) {
    const int t = chosen[i];
    const TileBox box = TileRect(t);
    tile_t& tile = tiles[i];
    tile = EncodeTile(image, box);
    tile.utime = info.utime;
    tile.frame_id = next_frame_id_;
    tile.tile_index = t;
    tile.x = static_cast<int16_t>(box.x);
    tile.y = static_cast<int16_t>(box.y);
    tile.width = static_cast<int16_t>(box.width);
    tile.height = static_cast<int16_t>(box.height);
    tile.pixel_hash = static_cast<int64_t>(hashes[t]);
  });
  return tiles;
}

// The FRAME message that closes the frame: its tiles, the whole image's hash and the camera.
frame_t TileStream::Manifest(const render::Framebuffer& image, const FrameInfo& info, bool keyframe,
                             std::vector<int32_t> chosen) {
  frame_t manifest{};
  manifest.utime = info.utime;
  manifest.frame_id = next_frame_id_++;
  manifest.step = info.step;
  manifest.sim_time = info.sim_time;
  manifest.width = width_;
  manifest.height = height_;
  manifest.tile_size = tile_size_;
  manifest.keyframe = keyframe;
  manifest.request_id = keyframe && keyframe_requested_ ? request_id_ : -1;
  manifest.frame_hash = ImageHash(image.rgb.data(), image.rgb.size());
  manifest.tile_indices = std::move(chosen);
  manifest.num_tiles = static_cast<int32_t>(manifest.tile_indices.size());
  for (int k = 0; k < 16; ++k) {
    manifest.view[k] = info.view.data()[k];  // Eigen is column-major, as the message says
    manifest.projection[k] = info.projection.data()[k];
  }
  for (int k = 0; k < 3; ++k) {
    manifest.camera_eye[k] = info.camera_eye[k];
    manifest.camera_target[k] = info.camera_target[k];
  }
  manifest.camera_fov = info.camera_fov;
  return manifest;
}

}  // namespace flagsim
