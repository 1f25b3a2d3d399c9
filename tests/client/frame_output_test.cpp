#include "client/frame_output.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/png_file.hpp"
#include "client/video_output.hpp"

namespace flagsim {
namespace {

TEST(OutputKindOf, ByTheNameAndWhatIsThere) {
  std::string error;
  EXPECT_EQ(OutputKindOf("frames/", &error), OutputKind::kPngDirectory);
  EXPECT_EQ(OutputKindOf(::testing::TempDir(), &error), OutputKind::kPngDirectory);  // exists
  EXPECT_EQ(OutputKindOf("run.mp4", &error), OutputKind::kMp4);
  EXPECT_EQ(OutputKindOf("out/run.gif", &error), OutputKind::kGif);
  EXPECT_EQ(error, "");
  EXPECT_EQ(OutputKindOf("run.avi", &error), std::nullopt);
  EXPECT_NE(error.find("'run.avi'"), std::string::npos) << error;
  EXPECT_NE(error.find("NAME.mp4 or NAME.gif"), std::string::npos) << error;
  EXPECT_EQ(OutputKindOf("frames", &error), std::nullopt) << "not a directory yet, no slash";
}

TEST(FrameOutput, PngsAreNumberedInTheirDirectory) {
  const std::string directory =
      std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_pngs/deeper";
  const auto output = MakeFrameOutput(OutputKind::kPngDirectory, directory, 30);
  std::vector<uint8_t> rgb(5 * 3 * 3);
  for (int i = 0; i < 3; ++i) {
    std::fill(rgb.begin(), rgb.end(), uint8_t(40 * i));
    EXPECT_EQ(output->Write(rgb.data(), 5, 3), "");
  }
  EXPECT_EQ(output->Finish(), "");
  EXPECT_EQ(output->frames(), 3);
  int width = 0, height = 0;
  std::vector<uint8_t> read;
  ASSERT_EQ(ReadPng(directory + "/frame_000002.png", &width, &height, &read), "");
  EXPECT_EQ(read, rgb);
  EXPECT_EQ(PngFramePath(directory, 2), directory + "/frame_000002.png");
  std::filesystem::remove_all(std::filesystem::path(directory).parent_path());
}

TEST(VideoOutput, FfmpegGetsTheSizeRateAndAFileNameThatIsNoOption) {
  const std::vector<std::string> mp4 = VideoOutput::Arguments(VideoFormat::kMp4, "-i.mp4", 201, 115, 12.5);
  const auto has = [](const std::vector<std::string>& arguments, const std::string& argument) {
    return std::find(arguments.begin(), arguments.end(), argument) != arguments.end();
  };
  EXPECT_TRUE(has(mp4, "201x115"));
  EXPECT_TRUE(has(mp4, "12.5"));
  EXPECT_TRUE(has(mp4, "libx264"));
  EXPECT_TRUE(has(mp4, "yuv420p"));
  EXPECT_TRUE(has(mp4, "pad=ceil(iw/2)*2:ceil(ih/2)*2")) << "yuv420p needs even sizes";
  EXPECT_EQ(mp4.back(), "file:-i.mp4");
  const std::vector<std::string> gif = VideoOutput::Arguments(VideoFormat::kGif, "a b.gif", 8, 8, 30);
  EXPECT_TRUE(has(gif, "gif"));
  EXPECT_EQ(gif.back(), "file:a b.gif");
}

// A video keeps the first frame's size: a later frame of another size is fitted to it, and
// counted, rather than ending the video.
TEST(VideoOutput, AFrameOfAnotherSizeIsFittedToTheFirst) {
  const std::string path = std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_size.mp4";
  if (FindOnPath("ffmpeg").empty()) GTEST_SKIP() << "ffmpeg is not installed (scripts/install-deps.sh)";
  VideoOutput video(path, VideoFormat::kMp4, 10);
  std::vector<uint8_t> rgb(16 * 16 * 3, 100);
  ASSERT_EQ(video.Write(rgb.data(), 16, 16), "");
  EXPECT_EQ(video.Write(rgb.data(), 8, 16), "");
  EXPECT_EQ(video.Write(rgb.data(), 16, 16), "");
  EXPECT_EQ(video.Finish(), "");
  EXPECT_EQ(video.frames(), 3);
  EXPECT_EQ(video.fitted(), 1);
  std::filesystem::remove(path);
}

TEST(CheckOutputPath, TheDirectoryMustBeThereToWriteIn) {
  const std::string scratch = ::testing::TempDir();
  EXPECT_EQ(CheckOutputPath(OutputKind::kMp4, scratch + "/run.mp4"), "");
  EXPECT_EQ(CheckOutputPath(OutputKind::kGif, "run.gif"), "");                       // here
  EXPECT_EQ(CheckOutputPath(OutputKind::kPngDirectory, scratch + "/not/yet/"), "");  // made when written
  EXPECT_EQ(CheckOutputPath(OutputKind::kPngDirectory, "frames/"), "");
  EXPECT_EQ(CheckOutputPath(OutputKind::kMp4, "/nonexistent/out.mp4"),
            "cannot write /nonexistent/out.mp4: there is no directory /nonexistent");
  EXPECT_EQ(CheckOutputPath(OutputKind::kMp4, scratch), "cannot write " + scratch + ": it is a directory");
}

// flagctl snapshot's picture, checked before the server is asked: the file's directory must be
// there, and the file, if it is there, one we may write.
TEST(CheckOutputFile, ThePictureMustBeOneWeMayWrite) {
  const std::string scratch = ::testing::TempDir();
  EXPECT_EQ(CheckOutputFile(scratch + "/flag.png"), "");
  EXPECT_EQ(CheckOutputFile("flag.jpg"), "");  // here
  EXPECT_EQ(CheckOutputFile("/nonexistent/flag.png"),
            "cannot write /nonexistent/flag.png: there is no directory /nonexistent");
  EXPECT_EQ(CheckOutputFile(scratch), "cannot write " + scratch + ": it is a directory");
  const std::string file = scratch + "/" + std::to_string(getpid()) + "_flag.png";
  std::ofstream(file) << "x";
  EXPECT_EQ(CheckOutputFile(file + "/flag.png"),
            "cannot write " + file + "/flag.png: there is no directory " + file);
  std::filesystem::permissions(file, std::filesystem::perms::owner_read);
  if (geteuid() != 0)  // the superuser may write any file
    EXPECT_EQ(CheckOutputFile(file), "cannot write " + file + ": Permission denied");
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace flagsim
