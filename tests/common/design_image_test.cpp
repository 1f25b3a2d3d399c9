// A person's image checked and decoded: PNG and JPEG, and every kind of bad file refused with
// its reason and the limits, the oversized ones by their header, before any pixel is decoded.
#include "common/design_image.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <string>
#include <vector>

#include "tests/common/test_images.hpp"

namespace flagsim {
namespace {

using testing::JpegBytes;
using testing::PngBytes;
using testing::SolidRgba;

std::string Problem(const std::vector<uint8_t>& bytes) {
  RgbaImage image;
  return DecodeDesignImage(bytes.data(), bytes.size(), &image);
}

void ExpectHas(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << text << "' lacks '" << part << "'";
}

/// A PNG whose header claims width x height px (its IHDR rewritten, with its CRC), and whose
/// pixels are a 2 x 2 image's: only a reader that trusts the header would allocate for it.
std::vector<uint8_t> PngClaiming(uint32_t width, uint32_t height) {
  std::vector<uint8_t> png = PngBytes(2, 2, SolidRgba(2, 2, 1, 2, 3));
  // signature (8), IHDR length (4), "IHDR" (4), width (4), height (4) ...; the CRC covers the
  // type and the 13 data bytes.
  const auto put = [&png](size_t at, uint32_t value) {
    for (int k = 0; k < 4; ++k) png[at + size_t(k)] = uint8_t(value >> (24 - 8 * k));
  };
  put(16, width);
  put(20, height);
  put(29, uint32_t(crc32(0, png.data() + 12, 17)));
  return png;
}

TEST(DesignImage, APngIsDecodedWithItsAlpha) {
  std::vector<uint8_t> rgba = SolidRgba(3, 2, 200, 10, 20);
  rgba[3] = 0;        // the first pixel transparent
  rgba[4 + 3] = 128;  // the second half
  const std::vector<uint8_t> png = PngBytes(3, 2, rgba);
  ImageHeader header;
  ASSERT_EQ(InspectDesignImage(png.data(), png.size(), &header), "");
  EXPECT_EQ(header.format, ImageFormat::kPng);
  EXPECT_EQ(header.width, 3);
  EXPECT_EQ(header.height, 2);
  RgbaImage image;
  ASSERT_EQ(DecodeDesignImage(png.data(), png.size(), &image), "");
  EXPECT_EQ(image.width, 3);
  EXPECT_EQ(image.height, 2);
  EXPECT_EQ(image.rgba, rgba);
  EXPECT_TRUE(image.HasTransparency());
}

TEST(DesignImage, AJpegIsDecodedOpaque) {
  const std::vector<uint8_t> jpeg = JpegBytes(40, 24, 30, 120, 220);
  RgbaImage image;
  ASSERT_EQ(DecodeDesignImage(jpeg.data(), jpeg.size(), &image), "");
  ASSERT_EQ(image.width, 40);
  ASSERT_EQ(image.height, 24);
  EXPECT_FALSE(image.HasTransparency());
  const uint8_t* middle = &image.rgba[(12 * 40 + 20) * 4];
  EXPECT_NEAR(middle[0], 30, 3);  // JPEG is lossy: a flat colour comes back within a few levels
  EXPECT_NEAR(middle[1], 120, 3);
  EXPECT_NEAR(middle[2], 220, 3);
}

TEST(DesignImage, AnEmptyFileIsRefusedWithTheLimits) {
  const std::string problem = Problem({});
  ExpectHas(problem, "the file is empty");
  ExpectHas(problem, "a PNG or JPEG file of 1 byte .. 4 MiB, 1 .. 8192 px a side and at most 16 Mpx");
}

TEST(DesignImage, AFileOverTheByteLimitIsRefusedBySize) {
  std::vector<uint8_t> big = PngBytes(2, 2, SolidRgba(2, 2, 0, 0, 0));
  big.resize(kMaxDesignFileBytes + 1);
  ExpectHas(Problem(big), "the file is 4194305 bytes; allowed: a PNG or JPEG file");
}

TEST(DesignImage, AHeaderClaimingTooManyPixelsIsRefusedBeforeDecoding) {
  ExpectHas(Problem(PngClaiming(9000, 10)), "the image is 9000 x 10 px; allowed:");
  ExpectHas(Problem(PngClaiming(5000, 5000)), "the image is 5000 x 5000 px; allowed:");  // 25 Mpx
  ImageHeader header;
  const std::vector<uint8_t> claims = PngClaiming(5000, 5000);
  ExpectHas(InspectDesignImage(claims.data(), claims.size(), &header), "5000 x 5000 px");
}

TEST(DesignImage, ATruncatedPngOrJpegIsRefused) {
  std::vector<uint8_t> png = PngBytes(64, 64, SolidRgba(64, 64, 9, 9, 9));
  png.resize(png.size() - 20);
  ExpectHas(Problem(png), "the PNG cannot be decoded");
  std::vector<uint8_t> jpeg = JpegBytes(64, 64, 9, 200, 9);
  jpeg.resize(jpeg.size() / 2);
  ExpectHas(Problem(jpeg), "the JPEG cannot be decoded");
}

TEST(DesignImage, WhatIsNeitherPngNorJpegIsRefused) {
  const std::string text = "GIF89a is not taken";
  ExpectHas(Problem(std::vector<uint8_t>(text.begin(), text.end())),
            "the file is neither a PNG nor a JPEG (by its first bytes); allowed:");
  std::vector<uint8_t> header_only = PngBytes(2, 2, SolidRgba(2, 2, 0, 0, 0));
  header_only.resize(12);
  ExpectHas(Problem(header_only), "the PNG's header cannot be read");
}

TEST(DesignImage, Sha256HexMatchesTheStandardsVector) {
  const std::string abc = "abc";  // FIPS 180-2, appendix B.1
  EXPECT_EQ(Sha256Hex(reinterpret_cast<const uint8_t*>(abc.data()), abc.size()),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

}  // namespace
}  // namespace flagsim
