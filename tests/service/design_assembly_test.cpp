// Pieces of design files held until whole: any order, retries, the digest checked, bad pieces
// refused with their reason, and no more than kMaxFiles files held at once.
#include "server/service/design_assembly.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "common/design_image.hpp"
#include "messages/design_pieces.hpp"
#include "tests/common/test_images.hpp"

namespace flagsim {
namespace {

/// A PNG of some 150 KB (noise does not compress): four pieces, the last short.
std::vector<uint8_t> NoisyPng(uint32_t seed) {
  std::mt19937 random(seed);
  std::vector<uint8_t> rgba(size_t(220) * 170 * 4);
  for (uint8_t& byte : rgba) byte = uint8_t(random());
  return testing::PngBytes(220, 170, rgba);
}

std::vector<design_piece_t> Pieces(const std::vector<uint8_t>& bytes, const std::string& name = "noise.png") {
  return SplitDesignFile(name, Sha256Hex(bytes.data(), bytes.size()), bytes, "test", 0);
}

TEST(DesignAssembly, PiecesInAnyOrderWithRetriesMakeTheWholeFile) {
  const std::vector<uint8_t> bytes = NoisyPng(1);
  std::vector<design_piece_t> pieces = Pieces(bytes);
  ASSERT_EQ(pieces.size(), 4u);
  std::reverse(pieces.begin(), pieces.end());
  DesignAssembly assembly;
  int64_t held = 0;
  for (size_t i = 0; i + 1 < pieces.size(); ++i) {
    for (int again = 0; again < 2; ++again) {  // each retried once: held once
      const DesignAssembly::Outcome outcome = assembly.Add(pieces[i]);
      EXPECT_EQ(outcome.problem, "");
      EXPECT_FALSE(outcome.whole);
      EXPECT_EQ(outcome.held, held + pieces[i].num_bytes);
    }
    held += pieces[i].num_bytes;
  }
  const DesignAssembly::Outcome last = assembly.Add(pieces.back());
  EXPECT_EQ(last.problem, "");
  ASSERT_TRUE(last.whole);
  EXPECT_EQ(last.bytes, bytes);
}

TEST(DesignAssembly, ADamagedPieceFailsTheDigestAndTheFileIsSentAgain) {
  const std::vector<uint8_t> bytes = NoisyPng(2);
  std::vector<design_piece_t> pieces = Pieces(bytes);
  design_piece_t damaged = pieces[1];
  damaged.data[100] ^= 1;
  DesignAssembly assembly;
  assembly.Add(pieces[0]);
  assembly.Add(damaged);
  assembly.Add(pieces[2]);
  const DesignAssembly::Outcome outcome = assembly.Add(pieces[3]);
  EXPECT_FALSE(outcome.whole);
  EXPECT_NE(outcome.problem.find("noise.png: the whole file's SHA-256 is "), std::string::npos)
      << outcome.problem;
  EXPECT_NE(outcome.problem.find("send the file again"), std::string::npos);
  DesignAssembly::Outcome again;
  for (const design_piece_t& piece : pieces) again = assembly.Add(piece);  // from the start
  EXPECT_TRUE(again.whole) << again.problem;
}

TEST(DesignAssembly, BadPiecesAreRefusedWithTheirReason) {
  const std::vector<uint8_t> bytes = NoisyPng(3);
  const design_piece_t good = Pieces(bytes)[1];
  const auto problem = [](design_piece_t piece) { return DesignAssembly().Add(piece).problem; };
  design_piece_t piece = good;
  piece.offset = 1000;
  EXPECT_EQ(problem(piece),
            "offset: 1000; allowed multiples of 49152 below total_bytes " + std::to_string(bytes.size()));
  piece = good;
  piece.num_bytes = 10;
  piece.data.resize(10);
  EXPECT_EQ(problem(piece), "num_bytes: 10; the piece at offset 49152 of a file of " +
                                std::to_string(bytes.size()) + " bytes holds 49152");
  piece = good;
  piece.total_bytes = 5 << 20;
  EXPECT_EQ(problem(piece).rfind("total_bytes: 5242880; allowed: a PNG or JPEG file of 1 byte .. 4 MiB", 0),
            0u);
  piece = good;
  piece.digest = "XYZ";
  EXPECT_EQ(problem(piece), "digest: allowed the file's SHA-256 as 64 lowercase hex digits");
  piece = good;
  piece.name = "../x.png";
  EXPECT_EQ(problem(piece), "name: allowed printable characters without '/' (a file's name, not its path)");
  DesignAssembly assembly;  // the same digest with another size
  ASSERT_EQ(assembly.Add(good).problem, "");
  piece = Pieces(bytes)[0];
  piece.name = "other.png";
  EXPECT_NE(assembly.Add(piece).problem.find("earlier pieces with its digest said noise.png"),
            std::string::npos);
}

TEST(DesignAssembly, AFifthFileDropsTheOneTouchedLongestAgo) {
  DesignAssembly assembly;
  std::vector<std::vector<design_piece_t>> files;
  for (uint32_t seed = 10; seed < 15; ++seed) files.push_back(Pieces(NoisyPng(seed)));
  for (const auto& pieces : files) assembly.Add(pieces[0]);  // the fifth drops the first
  DesignAssembly::Outcome outcome;
  for (size_t k = 1; k < 4; ++k) outcome = assembly.Add(files[0][k]);
  EXPECT_FALSE(outcome.whole);  // its first piece was dropped: the rest are held anew
  EXPECT_EQ(outcome.held, files[0][0].total_bytes - files[0][0].num_bytes);
  for (size_t k = 1; k < 4; ++k) outcome = assembly.Add(files[4][k]);
  EXPECT_TRUE(outcome.whole) << outcome.problem;
}

TEST(DesignLibrary, KeepsWholeFilesByDigest) {
  const std::vector<uint8_t> bytes = NoisyPng(4);
  DesignLibrary library;
  const std::vector<design_piece_t> pieces = Pieces(bytes);
  for (const design_piece_t& piece : pieces) EXPECT_EQ(library.Add(piece), "");
  const DesignFilePtr file = library.Find(pieces[0].digest);
  ASSERT_TRUE(file);
  EXPECT_EQ(file->bytes, bytes);
  EXPECT_EQ(file->width, 220);
  EXPECT_FALSE(library.Find(std::string(64, '0')));
}

}  // namespace
}  // namespace flagsim
