#include "client/tile_assembler.hpp"

#include <gtest/gtest.h>

#include <random>

#include "server/render/camera_moves.hpp"
#include "server/service/tile_stream.hpp"

namespace flagsim {
namespace {

render::Framebuffer Picture(int seed) {
  render::Framebuffer image;
  image.Resize(200, 130);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      uint8_t* p = image.Pixel(x, y);
      p[0] = uint8_t(x * seed);
      p[1] = uint8_t(y + seed);
      p[2] = uint8_t((x / 16 + y / 16) % 2 * 200);
    }
  }
  return image;
}

TileAssembler::FrameResult Deliver(const EncodedFrame& frame, TileAssembler* assembler,
                                   const std::vector<bool>* lost = nullptr) {
  for (size_t i = 0; i < frame.tiles.size(); ++i) {
    if (lost == nullptr || !(*lost)[i]) {
      EXPECT_EQ(assembler->AddTile(frame.tiles[i]), "");
    }
  }
  return assembler->AddManifest(frame.manifest);
}

TEST(TileAssembler, AKeyframeAloneGivesTheServersImage) {
  TileStream stream(64);
  const render::Framebuffer image = Picture(3);
  TileAssembler assembler;
  EXPECT_EQ(Deliver(stream.Encode(image, FrameInfo{}, 1), &assembler), TileAssembler::FrameResult::kComplete);
  EXPECT_EQ(assembler.image(), image.rgb);
  EXPECT_EQ(assembler.width(), 200);
}

TEST(TileAssembler, IncrementsKeepItExact) {
  TileStream stream(64);
  TileAssembler assembler;
  render::Framebuffer image = Picture(3);
  Deliver(stream.Encode(image, FrameInfo{}, 1), &assembler);
  for (int frame = 0; frame < 10; ++frame) {
    for (int i = 0; i < 50; ++i) image.rgb[(frame * 7919 + i * 131) % image.rgb.size()] ^= 0x5a;
    EXPECT_EQ(Deliver(stream.Encode(image, FrameInfo{}, 1), &assembler),
              TileAssembler::FrameResult::kComplete);
    EXPECT_EQ(assembler.image(), image.rgb);
  }
}

TEST(TileAssembler, LostTilesHealByTheRollingRefresh) {
  TileStream stream(64);
  TileAssembler assembler;
  const render::Framebuffer image = Picture(5);
  std::vector<bool> lost(12, false);
  lost[4] = lost[9] = true;
  EXPECT_EQ(Deliver(stream.Encode(image, FrameInfo{}, 1), &assembler, &lost),
            TileAssembler::FrameResult::kIncomplete);
  int frames = 0;
  while (Deliver(stream.Encode(image, FrameInfo{}, 1), &assembler) != TileAssembler::FrameResult::kComplete) {
    ASSERT_LT(++frames, 12 / TileStream::kMinRollingRefresh + 1) << "the refresh must come round";
  }
  EXPECT_EQ(assembler.image(), image.rgb);
}

TEST(TileAssembler, BadTilesAreRefusedAndChangeNothing) {
  TileStream stream(64);
  TileAssembler assembler;
  const EncodedFrame frame = stream.Encode(Picture(2), FrameInfo{}, 1);
  Deliver(frame, &assembler);
  const std::vector<uint8_t> before = assembler.image();
  tile_t tile = frame.tiles[5];
  tile.frame_id += 1;
  tile_t wrong_hash = tile;
  wrong_hash.pixel_hash ^= 1;
  EXPECT_NE(assembler.AddTile(wrong_hash), "");
  tile_t garbage = tile;
  garbage.encoding = tile_t::ZSTD_RGB8;
  garbage.data.assign(40, 0xee);
  garbage.num_bytes = 40;
  EXPECT_NE(assembler.AddTile(garbage), "");
  tile_t short_raw = tile;
  short_raw.encoding = tile_t::RAW_RGB8;
  short_raw.data.resize(10);
  EXPECT_NE(assembler.AddTile(short_raw), "");
  tile_t unknown = tile;
  unknown.encoding = 9;
  EXPECT_NE(assembler.AddTile(unknown), "");
  EXPECT_EQ(assembler.image(), before);
  frame_t huge = frame.manifest;
  huge.width = 100000;
  EXPECT_EQ(assembler.AddManifest(huge), TileAssembler::FrameResult::kRefused);
  EXPECT_EQ(assembler.image(), before);
}

// A manifest of a few hundred bytes could ask for millions of tiny tiles (each a record the
// assembler keeps): more than kMaxTiles is refused, and the picture stays.
TEST(TileAssembler, AManifestOfTooManyTilesIsRefused) {
  static_assert(TileAssembler::kMaxWidth == render::CameraMove::kMaxWidth &&
                TileAssembler::kMaxHeight == render::CameraMove::kMaxHeight);
  TileStream stream(64);
  TileAssembler assembler;
  const EncodedFrame frame = stream.Encode(Picture(3), FrameInfo{}, 1);
  Deliver(frame, &assembler);
  const std::vector<uint8_t> before = assembler.image();
  frame_t tiny_tiles = frame.manifest;
  tiny_tiles.width = TileAssembler::kMaxWidth;
  tiny_tiles.height = TileAssembler::kMaxHeight;
  tiny_tiles.tile_size = 1;
  EXPECT_EQ(assembler.AddManifest(tiny_tiles), TileAssembler::FrameResult::kRefused);
  EXPECT_EQ(assembler.image(), before);
  tiny_tiles.tile_size = 32;  // 120 x 68 tiles: within the limit
  EXPECT_NE(assembler.AddManifest(tiny_tiles), TileAssembler::FrameResult::kRefused);
}

TEST(TileAssembler, FollowsANewImageSize) {
  TileStream stream(64);
  TileAssembler assembler;
  Deliver(stream.Encode(Picture(1), FrameInfo{}, 1), &assembler);
  render::Framebuffer small;
  small.Resize(70, 40);
  std::fill(small.rgb.begin(), small.rgb.end(), 77);
  EXPECT_EQ(Deliver(stream.Encode(small, FrameInfo{}, 1), &assembler), TileAssembler::FrameResult::kComplete);
  EXPECT_EQ(assembler.image(), small.rgb);
}

}  // namespace
}  // namespace flagsim
