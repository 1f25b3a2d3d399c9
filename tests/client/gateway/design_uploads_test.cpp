// /flag/design's requests: a built-in design by name, an image in base64 parts in order, and
// every bad part refused with its reason, the upload dropped.
#include "client/gateway/design_uploads.hpp"

#include <gtest/gtest.h>

#include "tests/client/gateway/base64.hpp"
#include "tests/common/test_images.hpp"

namespace flagsim::gateway {
namespace {

using nlohmann::json;
using testing::Base64;

json Part(const std::vector<uint8_t>& file, size_t offset, size_t length, const std::string& name = "f.png") {
  const std::vector<uint8_t> part(file.begin() + long(offset), file.begin() + long(offset + length));
  return {{"name", name}, {"size", file.size()}, {"offset", offset}, {"data", Base64(part)}};
}

TEST(DecodeBase64, TakesTheStandardsVectorsAndRefusesTheRest) {
  // RFC 4648, section 10
  for (const auto& [text, plain] : std::vector<std::pair<std::string, std::string>>{{"", ""},
                                                                                    {"Zg==", "f"},
                                                                                    {"Zm8=", "fo"},
                                                                                    {"Zm9v", "foo"},
                                                                                    {"Zm9vYg==", "foob"},
                                                                                    {"Zm9vYmE=", "fooba"},
                                                                                    {"Zm9vYmFy", "foobar"}}) {
    std::vector<uint8_t> bytes;
    ASSERT_TRUE(DecodeBase64(text, &bytes)) << text;
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), plain);
  }
  std::vector<uint8_t> bytes;
  for (const std::string bad : {"Zg=", "Zg=a", "Z===", "Zm9v\n", "Zm-v", "=Zg="})
    EXPECT_FALSE(DecodeBase64(bad, &bytes)) << bad;
}

TEST(DesignUploads, ANameAloneIsABuiltInDesign) {
  DesignUploads uploads;
  const DesignUploads::Step step = uploads.Take(1, {{"name", "checker"}});
  EXPECT_EQ(step.problem, "");
  EXPECT_EQ(step.built_in, "checker");
  EXPECT_EQ(uploads.Take(1, json::array()).problem, "the request must be a JSON object");
  EXPECT_EQ(uploads.Take(1, {{"name", 3}}).problem,
            "name: required, a built-in design's name or the image file's name");
}

TEST(DesignUploads, PartsInOrderMakeTheCheckedFile) {
  const std::vector<uint8_t> file =
      flagsim::testing::PngBytes(30, 20, flagsim::testing::SolidRgba(30, 20, 1, 2, 3));
  DesignUploads uploads;
  DesignUploads::Step step = uploads.Take(7, Part(file, 0, 40));
  EXPECT_EQ(step.problem, "");
  EXPECT_FALSE(step.whole);
  EXPECT_EQ(step.held, 40);
  step = uploads.Take(7, Part(file, 40, file.size() - 40));
  EXPECT_EQ(step.problem, "");
  ASSERT_TRUE(step.whole);
  EXPECT_EQ(step.name, "f.png");
  EXPECT_EQ(step.bytes, file);
}

TEST(DesignUploads, BadPartsAreRefusedAndTheUploadDropped) {
  const std::vector<uint8_t> file =
      flagsim::testing::PngBytes(30, 20, flagsim::testing::SolidRgba(30, 20, 1, 2, 3));
  DesignUploads uploads;
  ASSERT_EQ(uploads.Take(1, Part(file, 0, 40)).problem, "");
  EXPECT_EQ(uploads.Take(1, Part(file, 50, 10)).problem,
            "offset: 50; the upload of f.png holds 40 bytes: send its parts in order, from offset 0");
  EXPECT_EQ(uploads.Take(1, Part(file, 40, 10)).problem,  // dropped: it must start again
            "offset: 40; no upload of f.png is under way: send its parts in order, from offset 0");
  json part = Part(file, 0, 40);
  part["data"] = "not base64!";
  EXPECT_EQ(uploads.Take(1, part).problem, "data: must be the part's bytes in base64");
  part = Part(file, 0, 40);
  part["size"] = 5 << 20;
  EXPECT_EQ(uploads.Take(1, part).problem, "size: required, an integer 0 .. 4194304");
  std::vector<uint8_t> big(DesignUploads::kMaxPartBytes + 3, 0);
  EXPECT_EQ(uploads.Take(1, Part(big, 0, big.size(), "big.png")).problem,
            "data: 147459 bytes at offset 0; allowed 1 .. 147456 bytes a part, within size 147459");
  std::vector<uint8_t> cut = file;
  cut.resize(cut.size() - 40);  // into its pixels (without its last chunk, IEND, a PNG still reads)
  const std::string problem = uploads.Take(2, Part(cut, 0, cut.size(), "cut.png")).problem;
  EXPECT_EQ(problem.rfind("cut.png: the PNG cannot be decoded", 0), 0u) << problem;
}

}  // namespace
}  // namespace flagsim::gateway
