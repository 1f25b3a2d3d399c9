#include "client/child_process.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace flagsim {
namespace {

TEST(ChildProcess, FeedsItsInputThroughThePipe) {
  const std::string path = std::string(::testing::TempDir()) + "/" + std::to_string(getpid()) + "_child.txt";
  ChildProcess child;
  // The file name reaches the child as one argument: no shell reads it.
  ASSERT_EQ(child.Start("dd", {"status=none", "of=" + path}), "");
  const std::string text = "frames; rm -rf /\n$(reboot)\n";
  EXPECT_EQ(child.Write(reinterpret_cast<const uint8_t*>(text.data()), text.size()), "");
  EXPECT_EQ(child.Finish(), "");
  std::ifstream file(path);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(file), {}), text);
  std::remove(path.c_str());
}

TEST(ChildProcess, AMissingProgramIsNamed) {
  ChildProcess child;
  EXPECT_EQ(child.Start("no-such-program-here", {}),
            "no-such-program-here is not installed (not found on PATH)");
  EXPECT_FALSE(child.running());
  EXPECT_NE(child.Write(reinterpret_cast<const uint8_t*>("x"), 1), "");
}

TEST(ChildProcess, AChildThatStopsReadingIsAnErrorNotASignal) {
  ChildProcess child;
  ASSERT_EQ(child.Start("sh", {"-c", "exit 3"}), "");
  const std::vector<uint8_t> frame(1 << 20, 7);  // more than a pipe holds
  std::string problem;
  for (int i = 0; i < 8 && problem.empty(); ++i) problem = child.Write(frame.data(), frame.size());
  EXPECT_EQ(problem, "sh stopped reading its input");
  EXPECT_EQ(child.Finish(), "sh failed (exit code 3)");
}

TEST(FindOnPath, FindsProgramsAndNotOthers) {
  EXPECT_NE(FindOnPath("sh"), "");
  EXPECT_EQ(FindOnPath("no-such-program-here"), "");
}

}  // namespace
}  // namespace flagsim
