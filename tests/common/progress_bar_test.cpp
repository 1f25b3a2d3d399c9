#include "common/progress_bar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace flagsim {
namespace {

/// Everything written to `file` so far.
std::string Contents(std::FILE* file) {
  std::fflush(file);
  std::rewind(file);
  std::string text;
  for (int c = std::fgetc(file); c != EOF; c = std::fgetc(file)) text += char(c);
  return text;
}

TEST(BarText, FillsInProportionAndClamps) {
  EXPECT_EQ(BarText(0, 10), "[..........]   0%");
  EXPECT_EQ(BarText(0.45, 10), "[####......]  45%");
  EXPECT_EQ(BarText(1, 10), "[##########] 100%");
  EXPECT_EQ(BarText(7, 4), "[####] 100%");
  EXPECT_EQ(BarText(-1, 4), "[....]   0%");
  EXPECT_EQ(BarText(std::nan(""), 4), "[....]   0%");
}

TEST(ProgressBar, OffATerminalOnlyTheFinalLine) {
  std::FILE* file = std::tmpfile();
  ProgressBar bar(file, false);
  for (int i = 0; i <= 100; ++i) bar.Update(i / 100.0, "working");
  bar.Finish("done: 100 frames");
  EXPECT_EQ(Contents(file), "done: 100 frames\n");
  std::fclose(file);
}

TEST(ProgressBar, OnATerminalRedrawsInPlaceThenClears) {
  std::FILE* file = std::tmpfile();
  ProgressBar bar(file, true);
  bar.Update(0.5, "frame 5");
  bar.Update(0.6, "frame 6");  // too soon after: not drawn
  bar.Finish("done");
  const std::string expected =
      "\r" + BarText(0.5, ProgressBar::kWidth) + "  frame 5\x1b[K" + "\r\x1b[K" + "done\n";
  EXPECT_EQ(Contents(file), expected);
  std::fclose(file);
}

}  // namespace
}  // namespace flagsim
