#include "server/service/tile_stream.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tests/messages/message_fixtures.hpp"

namespace flagsim {
namespace {

/// A 200 x 130 image (4 x 3 tiles of 64, the edge ones cut) filled with a smooth gradient.
render::Framebuffer Gradient() {
  render::Framebuffer image;
  image.Resize(200, 130);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      uint8_t* p = image.Pixel(x, y);
      p[0] = uint8_t(x);
      p[1] = uint8_t(y);
      p[2] = uint8_t(x + y);
    }
  }
  return image;
}

std::vector<int32_t> All(int n) {
  std::vector<int32_t> indices(n);
  for (int i = 0; i < n; ++i) indices[i] = i;
  return indices;
}

TEST(TileStream, FirstFrameIsAKeyframeOfEveryTile) {
  TileStream stream(64);
  const EncodedFrame frame = stream.Encode(Gradient(), FrameInfo{}, 1);
  EXPECT_TRUE(frame.manifest.keyframe);
  EXPECT_EQ(frame.manifest.tile_indices, All(12));
  EXPECT_EQ(frame.manifest.width, 200);
  EXPECT_EQ(frame.tiles[3].width, 200 - 3 * 64);  // the right edge tile is cut
  EXPECT_EQ(frame.tiles[11].height, 130 - 2 * 64);
  const render::Framebuffer image = Gradient();
  EXPECT_EQ(frame.manifest.frame_hash, ImageHash(image.rgb.data(), image.rgb.size()));
}

TEST(TileStream, TheManifestCarriesTheFramesCamera) {
  FrameInfo info;
  info.step = 17;
  info.view(0, 3) = -2.5;
  info.projection(3, 2) = -1;
  info.camera_eye = Eigen::Vector3d(1, 2, 3);
  info.camera_target = Eigen::Vector3d(-4, 5, -6);
  info.camera_fov = 47.5;
  TileStream stream(64);
  const frame_t manifest = stream.Encode(Gradient(), info, 1).manifest;
  EXPECT_EQ(manifest.step, 17);
  EXPECT_EQ(manifest.view[12], -2.5);  // column-major: column 3, row 0
  EXPECT_EQ(manifest.projection[11], -1);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(manifest.camera_eye[k], info.camera_eye[k]);
    EXPECT_EQ(manifest.camera_target[k], info.camera_target[k]);
  }
  EXPECT_EQ(manifest.camera_fov, 47.5);
}

TEST(TileStream, UnchangedTilesAreNotSentAgainBarTheRollingRefresh) {
  TileStream stream(64);
  render::Framebuffer image = Gradient();
  stream.Encode(image, FrameInfo{}, 1);
  EncodedFrame frame = stream.Encode(image, FrameInfo{}, 1);
  EXPECT_FALSE(frame.manifest.keyframe);
  EXPECT_EQ(frame.manifest.num_tiles, TileStream::kMinRollingRefresh);
  image.Pixel(130, 70)[0] ^= 1;  // one pixel of tile (2, 1) = index 6
  frame = stream.Encode(image, FrameInfo{}, 1);
  EXPECT_NE(std::find(frame.manifest.tile_indices.begin(), frame.manifest.tile_indices.end(), 6),
            frame.manifest.tile_indices.end());
  EXPECT_EQ(frame.manifest.num_tiles,
            TileStream::kMinRollingRefresh + 1 - (frame.manifest.tile_indices[0] == 6));
}

TEST(TileStream, TheRollingRefreshComesRoundEveryTile) {
  TileStream stream(64);
  const render::Framebuffer image = Gradient();
  stream.Encode(image, FrameInfo{}, 1);
  std::vector<int> seen(12, 0);
  for (int i = 0; i < 6; ++i) {
    for (const int32_t t : stream.Encode(image, FrameInfo{}, 1).manifest.tile_indices) ++seen[t];
  }
  for (const int count : seen) EXPECT_EQ(count, 1);
}

// At a frame rate, the rolling refresh sends every tile within kRefreshSeconds of frames, however
// still the picture: a recorder that joins mid-stream has the whole picture by then.
TEST(TileStream, AtAFrameRateEveryTileGoesOutWithinTheRefreshTime) {
  for (const double frame_rate : {1.0, 7.0, 30.0, 60.0}) {
    TileStream stream;
    render::Framebuffer image;
    image.Resize(1280, 720);
    FrameInfo info;
    info.frame_rate = frame_rate;
    const int tiles = stream.Encode(image, info, 1).manifest.num_tiles;  // the first: a keyframe
    std::vector<int> seen(tiles, 0);
    const int frames = int(frame_rate * TileStream::kRefreshSeconds);
    for (int i = 0; i < frames; ++i) {
      const EncodedFrame frame = stream.Encode(image, info, 1);
      EXPECT_FALSE(frame.manifest.keyframe);
      for (const int32_t t : frame.manifest.tile_indices) ++seen[t];
    }
    for (int t = 0; t < tiles; ++t) ASSERT_GE(seen[t], 1) << "tile " << t << " at " << frame_rate << " Hz";
  }
}

TEST(TileStream, ARequestMakesTheNextFrameAKeyframe) {
  TileStream stream(64);
  const render::Framebuffer image = Gradient();
  stream.Encode(image, FrameInfo{}, 1);
  stream.RequestKeyframe(41);
  stream.RequestKeyframe(42);  // coalesced: one keyframe answers the latest
  const EncodedFrame frame = stream.Encode(image, FrameInfo{}, 1);
  EXPECT_TRUE(frame.manifest.keyframe);
  EXPECT_EQ(frame.manifest.request_id, 42);
  EXPECT_EQ(frame.manifest.num_tiles, 12);
  EXPECT_FALSE(stream.Encode(image, FrameInfo{}, 1).manifest.keyframe);
}

TEST(TileStream, EveryTileFitsOneDatagramEvenAsNoise) {
  render::Framebuffer noise;
  noise.Resize(256, 128);
  std::mt19937 random(9);
  for (uint8_t& byte : noise.rgb) byte = uint8_t(random());
  TileStream stream;  // the stream's own tile size
  for (const tile_t& tile : stream.Encode(noise, FrameInfo{}, 1).tiles) {
    EXPECT_EQ(tile.encoding, tile_t::RAW_RGB8);  // incompressible: sent raw
    EXPECT_LT(testing::Encode(tile).size(), 64u * 1024);
  }
}

TEST(TileStream, TheSameMessagesAtAnyThreadCount) {
  render::Framebuffer image = Gradient();
  TileStream one(64), two(64);
  const EncodedFrame a = one.Encode(image, FrameInfo{}, 1), b = two.Encode(image, FrameInfo{}, 2);
  ASSERT_EQ(a.tiles.size(), b.tiles.size());
  for (size_t i = 0; i < a.tiles.size(); ++i)
    EXPECT_EQ(testing::Encode(a.tiles[i]), testing::Encode(b.tiles[i]));
  EXPECT_EQ(testing::Encode(a.manifest), testing::Encode(b.manifest));
}

}  // namespace
}  // namespace flagsim
