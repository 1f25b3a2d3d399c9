// A person's image made into the flag's design: the texture (its size capped, filtered in
// linear light with premultiplied alpha), the width by its aspect, names, and scene files that
// name an image by its path.
#include "server/scene/design_file.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "server/scene/scene_file.hpp"
#include "tests/common/test_images.hpp"

namespace flagsim {
namespace {

using testing::PngBytes;
using testing::SolidRgba;

DesignFilePtr Made(int width, int height, const std::vector<uint8_t>& rgba,
                   const std::string& name = "f.png") {
  DesignFilePtr file;
  const std::string problem = MakeDesignFile(name, PngBytes(width, height, rgba), &file);
  EXPECT_EQ(problem, "");
  return file;
}

TEST(DesignFile, ASmallImageIsItsOwnTextureAndOpaqueHasNoAlpha) {
  const DesignFilePtr file = Made(30, 20, SolidRgba(30, 20, 10, 100, 200));
  ASSERT_TRUE(file);
  EXPECT_EQ(file->texture.width, 30);
  EXPECT_EQ(file->texture.height, 20);
  EXPECT_TRUE(file->texture.alpha.empty());
  EXPECT_EQ(file->texture.rgb[0], 10);
  EXPECT_EQ(file->texture.rgb[1], 100);
  EXPECT_EQ(file->texture.rgb[2], 200);
  EXPECT_EQ(file->digest.size(), 64u);
  EXPECT_DOUBLE_EQ(file->WidthFor(1.0), 1.5);
}

TEST(DesignFile, ALargeImageIsFilteredDownInLinearLight) {
  // 3000 x 1000, columns alternating black and white: a texel of the 1536 x 512 texture
  // covers about two columns, whose mean light is 1/2, sRGB 188 (not the 128 of a mean of bytes).
  const int width = 3000, height = 1000;
  std::vector<uint8_t> rgba = SolidRgba(width, height, 0, 0, 0);
  for (int y = 0; y < height; ++y)
    for (int x = 1; x < width; x += 2)
      for (int k = 0; k < 3; ++k) rgba[(size_t(y) * width + x) * 4 + size_t(k)] = 255;
  const DesignFilePtr file = Made(width, height, rgba);
  ASSERT_TRUE(file);
  EXPECT_EQ(file->texture.width, DesignFile::kMaxTexels);
  EXPECT_EQ(file->texture.height, 512);
  EXPECT_DOUBLE_EQ(file->WidthFor(1.0), 3.0);
  const uint8_t middle = file->texture.rgb[(256 * 1536 + 768) * 3];
  EXPECT_NEAR(middle, 188, 12);
}

TEST(DesignFile, TransparentPixelsLendNoColourToTheirNeighbours) {
  // Left half transparent red, right half opaque blue, 2001 px wide: texels across the edge are
  // part transparent, and wholly blue.
  const int width = 2001, height = 10;
  std::vector<uint8_t> rgba = SolidRgba(width, height, 0, 0, 255);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width / 2; ++x) {
      uint8_t* pixel = &rgba[(size_t(y) * width + x) * 4];
      pixel[0] = 255, pixel[2] = 0, pixel[3] = 0;
    }
  const DesignFilePtr file = Made(width, height, rgba);
  ASSERT_TRUE(file);
  const render::Texture& texture = file->texture;
  ASSERT_EQ(texture.alpha.size(), size_t(texture.width) * texture.height);
  EXPECT_EQ(texture.alpha[0], 0);
  EXPECT_EQ(texture.alpha[size_t(texture.width) - 1], 255);
  bool partly = false;
  for (int x = 0; x < texture.width; ++x) {
    const uint8_t alpha = texture.alpha[size_t(x)];
    if (alpha == 0) continue;
    partly |= alpha < 255;
    EXPECT_EQ(texture.rgb[size_t(x) * 3], 0) << x;
    EXPECT_EQ(texture.rgb[size_t(x) * 3 + 2], 255) << x;
  }
  EXPECT_TRUE(partly);
}

TEST(DesignFile, TheWidthFollowsTheAspectWithinTheParametersRange) {
  EXPECT_DOUBLE_EQ(Made(20, 10, SolidRgba(20, 10, 1, 1, 1))->WidthFor(0.8), 1.6);
  EXPECT_DOUBLE_EQ(Made(2000, 1, SolidRgba(2000, 1, 1, 1, 1))->WidthFor(1.0), 10.0);
  EXPECT_DOUBLE_EQ(Made(1, 2000, SolidRgba(1, 2000, 1, 1, 1))->WidthFor(1.0), 0.1);
}

TEST(DesignFile, ANameIsAFilesNameNotAPath) {
  DesignFilePtr file;
  const std::vector<uint8_t> png = PngBytes(2, 2, SolidRgba(2, 2, 0, 0, 0));
  EXPECT_EQ(MakeDesignFile("a/b.png", png, &file),
            "name: allowed printable characters without '/' (a file's name, not its path)");
  EXPECT_EQ(MakeDesignFile("", png, &file), "name: 0 characters; allowed 1 .. 128");
  EXPECT_FALSE(file);
}

class DesignInSceneFile : public ::testing::Test {
 protected:
  DesignInSceneFile()
      : folder_(std::filesystem::temp_directory_path() / ("flagsim_design_" + std::to_string(getpid()))) {
    std::filesystem::create_directories(folder_ / "art");
    const std::vector<uint8_t> png = PngBytes(40, 10, SolidRgba(40, 10, 200, 0, 0));
    std::ofstream(folder_ / "art" / "long.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  }
  ~DesignInSceneFile() override { std::filesystem::remove_all(folder_); }

  Scene Load(const std::string& text) {
    const std::filesystem::path path = folder_ / "scene.toml";
    std::ofstream(path) << text;
    return LoadScene(path.string());
  }

  std::filesystem::path folder_;
};

TEST_F(DesignInSceneFile, AnImageIsFoundBesideTheSceneFileAndSetsTheWidth) {
  const Scene scene = Load("design = \"art/long.png\"\n");
  EXPECT_EQ(scene.service.design, render::FlagDesign::kImage);
  ASSERT_TRUE(scene.service.design_file);
  EXPECT_EQ(scene.service.design_file->name, "long.png");
  EXPECT_DOUBLE_EQ(scene.sim.width, 4.0);  // 4 : 1 at the 1 m height
  EXPECT_TRUE(scene.service.width_follows_design);
}

TEST_F(DesignInSceneFile, AWidthTheSceneSetsStands) {
  const Scene scene = Load("design = \"art/long.png\"\n[parameters]\nwidth = 1.2\n");
  EXPECT_DOUBLE_EQ(scene.sim.width, 1.2);
  EXPECT_FALSE(scene.service.width_follows_design);
}

TEST_F(DesignInSceneFile, AMissingOrBadImageIsAClearError) {
  try {
    Load("design = \"art/none.png\"\n");
    FAIL() << "no error";
  } catch (const SceneError& error) {
    const std::string what = error.what();
    EXPECT_NE(
        what.find("design: 'art/none.png' is neither a built-in design (nordic_cross, tricolour, checker) "
                  "nor an image file: cannot read"),
        std::string::npos)
        << what;
  }
  std::ofstream(folder_ / "art" / "bad.png") << "not a picture";
  try {
    Load("design = \"art/bad.png\"\n");
    FAIL() << "no error";
  } catch (const SceneError& error) {
    EXPECT_NE(std::string(error.what()).find("neither a PNG nor a JPEG"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace flagsim
