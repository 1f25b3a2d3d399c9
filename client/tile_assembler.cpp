#include "client/tile_assembler.hpp"

#include <xxhash.h>
#include <zstd.h>

#include <algorithm>
#include <memory>

#include "messages/tile_prediction.hpp"

namespace flagsim {
namespace {

struct ZstdDecoderDeleter {
  void operator()(ZSTD_DCtx* context) const { ZSTD_freeDCtx(context); }
};

/// This thread's decompression context, kept for its life: ZSTD_decompress would allocate (and
/// fault in) a new one for every tile.
ZSTD_DCtx* ThreadDecompressor() {
  thread_local const std::unique_ptr<ZSTD_DCtx, ZstdDecoderDeleter> context(ZSTD_createDCtx());
  return context.get();
}

}  // namespace

void TileAssembler::Resize(int width, int height, int tile_size) {
  width_ = width;
  height_ = height;
  tile_size_ = tile_size;
  image_.assign(size_t(width) * height * 3, 0);
  const int tiles = ((width + tile_size - 1) / tile_size) * ((height + tile_size - 1) / tile_size);
  tile_t none{};
  none.frame_id = -1;
  placed_.assign(tiles, none);
}

std::string TileAssembler::AddTile(const tile_t& tile) {
  if (tile.x < 0 || tile.y < 0 || tile.width <= 0 || tile.height <= 0) return "tile of no size";
  if (tile.frame_id > latest_frame_) {
    latest_.clear();
    latest_frame_ = tile.frame_id;
  }
  if (tile.frame_id == latest_frame_ && latest_.size() < kMaxKept) latest_.push_back(tile);
  return Place(tile);
}

// A tile that does not fit the current grid exactly may belong to a new size: it stays in
// latest_ until the manifest says.
std::string TileAssembler::Place(const tile_t& tile) {
  if (width_ == 0 || tile.x % tile_size_ != 0 || tile.y % tile_size_ != 0 || tile.x >= width_ ||
      tile.y >= height_ || tile.width != std::min(tile_size_, width_ - tile.x) ||
      tile.height != std::min(tile_size_, height_ - tile.y)) {
    return "";
  }
  const int tiles_x = (width_ + tile_size_ - 1) / tile_size_;
  const int index = (tile.y / tile_size_) * tiles_x + tile.x / tile_size_;
  if (tile.frame_id < placed_[index].frame_id) return "";  // older than what we have: skip

  const size_t size = size_t(tile.width) * tile.height * 3;
  thread_local std::vector<uint8_t> pixels;  // kept: a new buffer per tile faults in fresh pages
  pixels.resize(size);
  if (tile.encoding == tile_t::RAW_RGB8) {
    if (tile.data.size() != size) return "raw tile of the wrong size";
    pixels = tile.data;
  } else if (tile.encoding == tile_t::ZSTD_RGB8 || tile.encoding == tile_t::ZSTD_UP_RGB8) {
    const size_t got =
        ZSTD_decompressDCtx(ThreadDecompressor(), pixels.data(), size, tile.data.data(), tile.data.size());
    if (ZSTD_isError(got) || got != size) return "tile does not decompress to its size";
    if (tile.encoding == tile_t::ZSTD_UP_RGB8) UnpredictRows(tile.width, &pixels);
  } else {
    return "unknown tile encoding " + std::to_string(tile.encoding);
  }
  if (static_cast<int64_t>(XXH3_64bits(pixels.data(), size)) != tile.pixel_hash)
    return "tile pixel hash mismatch";
  for (int row = 0; row < tile.height; ++row) {
    std::copy_n(&pixels[size_t(row) * tile.width * 3], size_t(tile.width) * 3,
                &image_[(size_t(tile.y + row) * width_ + tile.x) * 3]);
  }
  placed_[index] = tile;
  return "";
}

TileAssembler::FrameResult TileAssembler::AddManifest(const frame_t& manifest) {
  if (manifest.width <= 0 || manifest.height <= 0 || manifest.width > kMaxWidth ||
      manifest.height > kMaxHeight || manifest.tile_size <= 0 || manifest.tile_size > 4096) {
    return FrameResult::kRefused;
  }
  const int64_t columns = (manifest.width + manifest.tile_size - 1) / manifest.tile_size;
  const int64_t rows = (manifest.height + manifest.tile_size - 1) / manifest.tile_size;
  if (columns * rows > kMaxTiles) return FrameResult::kRefused;
  if (manifest.width != width_ || manifest.height != height_ || manifest.tile_size != tile_size_) {
    Resize(manifest.width, manifest.height, manifest.tile_size);
    for (const tile_t& tile : latest_) {
      if (tile.frame_id == manifest.frame_id) Place(tile);  // this frame's tiles came first
    }
  }
  if (static_cast<int64_t>(XXH3_64bits(image_.data(), image_.size())) != manifest.frame_hash) {
    return FrameResult::kIncomplete;
  }
  last_complete_frame_ = manifest.frame_id;
  return FrameResult::kComplete;
}

}  // namespace flagsim
