#include "common/picture_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/png_file.hpp"

namespace flagsim {
namespace {

std::string Scratch(const std::string& name) {
  return std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_" + name;
}

std::vector<uint8_t> Bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

TEST(PictureFormatOf, TheExtensionSaysTheFormat) {
  std::string error;
  EXPECT_EQ(PictureFormatOf("frame.png", &error), PictureFormat::kPng);
  EXPECT_EQ(PictureFormatOf("out/frame.JPG", &error), PictureFormat::kJpeg);
  EXPECT_EQ(PictureFormatOf("frame.jpeg", &error), PictureFormat::kJpeg);
  EXPECT_EQ(error, "");
  for (const char* path : {"frame.bmp", "frame", "jpg"}) {
    EXPECT_EQ(PictureFormatOf(path, &error), std::nullopt) << path;
    EXPECT_NE(error.find(std::string("'") + path + "'"), std::string::npos) << error;
    EXPECT_NE(error.find("allowed NAME.png or NAME.jpg"), std::string::npos) << error;
  }
}

// What the name says is what the file holds: a PNG's signature, a JPEG's start-of-image marker.
TEST(WritePicture, WritesTheFormatTheNameSays) {
  std::vector<uint8_t> rgb(32 * 24 * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i % 251);
  const std::string jpeg = Scratch("frame.jpg"), png = Scratch("frame.png");
  ASSERT_EQ(WritePicture(jpeg, PictureFormat::kJpeg, 32, 24, rgb.data()), "");
  ASSERT_EQ(WritePicture(png, PictureFormat::kPng, 32, 24, rgb.data()), "");
  const std::vector<uint8_t> jpeg_bytes = Bytes(jpeg);
  ASSERT_GE(jpeg_bytes.size(), 4u);
  EXPECT_EQ(jpeg_bytes[0], 0xFF);
  EXPECT_EQ(jpeg_bytes[1], 0xD8);  // start of image
  EXPECT_EQ(jpeg_bytes[jpeg_bytes.size() - 2], 0xFF);
  EXPECT_EQ(jpeg_bytes.back(), 0xD9);  // end of image
  int width = 0, height = 0;
  std::vector<uint8_t> read;
  ASSERT_EQ(ReadPng(png, &width, &height, &read), "");
  EXPECT_EQ(read, rgb);
  std::remove(jpeg.c_str());
  std::remove(png.c_str());
}

// The size comes from the header: a file claiming more pixels than the limit is refused before
// memory is taken for them.
TEST(ReadPng, APictureOverTheSizeLimitIsRefusedByItsHeader) {
  const std::string png = Scratch("wide.png");
  const std::vector<uint8_t> rgb(size_t(kMaxPngSide + 1) * 3, 128);
  ASSERT_EQ(WritePng(png, kMaxPngSide + 1, 1, rgb.data()), "");
  int width = 0, height = 0;
  std::vector<uint8_t> read;
  const std::string problem = ReadPng(png, &width, &height, &read);
  EXPECT_NE(problem.find("8193 x 1 px; allowed up to 8192 x 8192"), std::string::npos) << problem;
  EXPECT_TRUE(read.empty());
  std::remove(png.c_str());
}

TEST(WritePicture, AFileThatCannotBeWrittenIsNamedWithTheReason) {
  const std::vector<uint8_t> rgb(4 * 4 * 3, 0);
  EXPECT_EQ(WritePicture("/nonexistent/frame.jpg", PictureFormat::kJpeg, 4, 4, rgb.data()),
            "cannot open /nonexistent/frame.jpg for writing: No such file or directory");
  EXPECT_EQ(WritePicture("/nonexistent/frame.png", PictureFormat::kPng, 4, 4, rgb.data()),
            "cannot open /nonexistent/frame.png for writing: No such file or directory");
}

}  // namespace
}  // namespace flagsim
