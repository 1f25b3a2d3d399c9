// The frame mirror: what it sends each client takes that client exactly to the server's newest
// frame, however many frames it skipped, with only the tiles that differ.
#include "client/gateway/frame_mirror.hpp"

#include <gtest/gtest.h>

#include "server/service/tile_stream.hpp"
#include "tests/client/gateway/tile_update_reader.hpp"

namespace flagsim::gateway {
namespace {

render::Framebuffer Picture(int width, int height, int seed) {
  render::Framebuffer image;
  image.Resize(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      uint8_t* p = image.Pixel(x, y);
      p[0] = uint8_t(x * 3 + seed);
      p[1] = uint8_t(y * 5);
      p[2] = uint8_t((x / 16 + y / 16) % 2 * 200);
    }
  }
  return image;
}

/// The server's side: encodes `image` as the next frame and hands its messages to `mirror`.
FrameMirror::Result Broadcast(TileStream& stream, const render::Framebuffer& image, FrameMirror* mirror) {
  const EncodedFrame frame = stream.Encode(image, FrameInfo{}, 1);
  for (const tile_t& tile : frame.tiles) mirror->AddTile(tile);
  return mirror->AddManifest(frame.manifest);
}

/// Changes a small patch of `image` (one or two tiles).
void Scribble(render::Framebuffer* image, int frame) {
  for (int y = 10; y < 30; ++y) {
    for (int x = 70 + frame; x < 90 + frame; ++x) image->Pixel(x, y)[0] ^= 0x55;
  }
}

TEST(FrameMirror, AJoiningClientGetsAKeyframeOfTheNewestFrame) {
  TileStream stream(64);
  FrameMirror mirror;
  const render::Framebuffer image = Picture(200, 130, 1);
  ASSERT_EQ(Broadcast(stream, image, &mirror), FrameMirror::Result::kComplete);
  ClientTiles client;
  testing::TileUpdateReader reader;
  const auto update = TileUpdateFor(*mirror.latest(), &client);
  ASSERT_NE(update, nullptr);
  EXPECT_EQ(reader.Apply(*update), "");
  EXPECT_TRUE(reader.keyframe());
  EXPECT_EQ(reader.tiles(), 4u * 3u);  // 200 x 130 in 64 px tiles
  EXPECT_EQ(reader.image(), image.rgb);
  EXPECT_EQ(TileUpdateFor(*mirror.latest(), &client), nullptr) << "nothing new for a client that has it";
}

TEST(FrameMirror, IncrementsCarryOnlyTheChangedTilesAndStayExact) {
  TileStream stream(64);
  FrameMirror mirror;
  render::Framebuffer image = Picture(200, 130, 1);
  Broadcast(stream, image, &mirror);
  ClientTiles client;
  testing::TileUpdateReader reader;
  ASSERT_EQ(reader.Apply(*TileUpdateFor(*mirror.latest(), &client)), "");
  for (int frame = 1; frame <= 5; ++frame) {
    Scribble(&image, frame);
    ASSERT_EQ(Broadcast(stream, image, &mirror), FrameMirror::Result::kComplete);
    ASSERT_EQ(reader.Apply(*TileUpdateFor(*mirror.latest(), &client)), "");
    EXPECT_FALSE(reader.keyframe());
    EXPECT_LE(reader.tiles(), 2u)
        << "the patch spans at most two tiles; the rolling refresh resends unchanged ones";
    EXPECT_EQ(reader.image(), image.rgb);
  }
}

TEST(FrameMirror, ASlowClientSkipsToTheNewestFrameExactly) {
  TileStream stream(64);
  FrameMirror mirror;
  render::Framebuffer image = Picture(200, 130, 1);
  Broadcast(stream, image, &mirror);
  ClientTiles slow;
  testing::TileUpdateReader reader;
  ASSERT_EQ(reader.Apply(*TileUpdateFor(*mirror.latest(), &slow)), "");
  for (int frame = 1; frame <= 20; ++frame) {  // twenty frames pass while it is busy
    Scribble(&image, frame * 3);
    Broadcast(stream, image, &mirror);
  }
  ASSERT_EQ(reader.Apply(*TileUpdateFor(*mirror.latest(), &slow)), "");
  EXPECT_EQ(reader.image(), image.rgb);
  EXPECT_EQ(reader.frame_id(), mirror.latest()->frame_id);
  EXPECT_EQ(mirror.latest()->sequence, 21u);
}

TEST(FrameMirror, ANewImageSizeIsAKeyframe) {
  TileStream stream(64);
  FrameMirror mirror;
  Broadcast(stream, Picture(200, 130, 1), &mirror);
  ClientTiles client;
  testing::TileUpdateReader reader;
  ASSERT_EQ(reader.Apply(*TileUpdateFor(*mirror.latest(), &client)), "");
  const render::Framebuffer larger = Picture(300, 100, 2);
  ASSERT_EQ(Broadcast(stream, larger, &mirror), FrameMirror::Result::kComplete);
  ASSERT_EQ(reader.Apply(*TileUpdateFor(*mirror.latest(), &client)), "");
  EXPECT_TRUE(reader.keyframe());
  EXPECT_EQ(reader.image(), larger.rgb);
}

TEST(FrameMirror, AFrameWithLostTilesIsNotMirrored) {
  TileStream stream(64);
  FrameMirror mirror;
  const render::Framebuffer image = Picture(200, 130, 1);
  const EncodedFrame frame = stream.Encode(image, FrameInfo{}, 1);
  for (size_t i = 1; i < frame.tiles.size(); ++i) mirror.AddTile(frame.tiles[i]);  // tile 0 lost
  EXPECT_EQ(mirror.AddManifest(frame.manifest), FrameMirror::Result::kIncomplete);
  EXPECT_EQ(mirror.latest(), nullptr);
}

TEST(FrameMirror, ImagesAreKeptOnlyWhenWanted) {
  TileStream stream(64);
  FrameMirror mirror;
  const render::Framebuffer image = Picture(200, 130, 1);
  Broadcast(stream, image, &mirror);
  EXPECT_EQ(mirror.latest()->image, nullptr);
  mirror.KeepImages(true);
  Broadcast(stream, image, &mirror);
  ASSERT_NE(mirror.latest()->image, nullptr);
  EXPECT_EQ(*mirror.latest()->image, image.rgb);
}

}  // namespace
}  // namespace flagsim::gateway
