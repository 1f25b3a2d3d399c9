// Key files: what keygen writes reads back, loose permissions and malformed lines are refused
// with the file, the line and what is allowed, and nothing is ever overwritten.
#include "messages/command_key.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace flagsim {
namespace {

class CommandKeyTest : public ::testing::Test {
 protected:
  CommandKeyTest()
      : directory_(std::filesystem::temp_directory_path() /
                   ("command_key_test_" + std::to_string(getpid()))) {
    std::filesystem::create_directories(directory_);
  }
  ~CommandKeyTest() override { std::filesystem::remove_all(directory_); }

  std::string Path(const std::string& name) const { return (directory_ / name).string(); }

  /// A file with `text` and mode `mode`.
  std::string WriteFile(const std::string& name, const std::string& text, mode_t mode = 0600) const {
    const std::string path = Path(name);
    std::ofstream(path) << text;
    chmod(path.c_str(), mode);
    return path;
  }

  /// The message ReadKeyFile throws for `path` ("" if it does not throw).
  static std::string ReadError(const std::string& path) {
    try {
      ReadKeyFile(path);
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    return "";
  }

  std::filesystem::path directory_;
};

const std::string kHex(64, 'a');

TEST_F(CommandKeyTest, ANewKeyIsPrivateAndReadsBack) {
  const std::string path = Path("ops.key");
  const CommandKey written = WriteNewKeyFile(path, "ops");
  struct stat info {};
  ASSERT_EQ(stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600u);
  const std::vector<CommandKey> read = ReadKeyFile(path);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].name, "ops");
  EXPECT_EQ(read[0].secret, written.secret);
  EXPECT_NE(WriteNewKeyFile(Path("other.key"), "ops").secret, written.secret);  // random, not fixed
}

TEST_F(CommandKeyTest, ANewKeyNeverOverwritesAFile) {
  const std::string path = WriteFile("existing", "precious\n");
  try {
    WriteNewKeyFile(path, "ops");
    FAIL() << "overwrote " << path;
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("exists"), std::string::npos) << error.what();
  }
  std::ifstream in(path);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "precious");
}

TEST_F(CommandKeyTest, SeveralNamedKeysAndCommentsRead) {
  const std::string path =
      WriteFile("two.key", "# a comment\n\nops " + kHex + "\nlab-2 " + std::string(64, '0') + "\n");
  const std::vector<CommandKey> keys = ReadKeyFile(path);
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0].name, "ops");
  EXPECT_EQ(keys[0].secret[31], 0xaa);
  EXPECT_EQ(keys[1].name, "lab-2");
  EXPECT_EQ(keys[1].secret[0], 0);
}

TEST_F(CommandKeyTest, AFileOthersCanReadIsRefusedWithItsModeAndTheFix) {
  for (const mode_t mode : {0644, 0640, 0602}) {
    const std::string path = WriteFile("loose.key", "ops " + kHex + "\n", mode);
    const std::string error = ReadError(path);
    EXPECT_NE(error.find(path), std::string::npos) << error;
    EXPECT_NE(error.find("owner only"), std::string::npos) << error;
    EXPECT_NE(error.find("chmod 600"), std::string::npos) << error;
  }
}

TEST_F(CommandKeyTest, MalformedFilesNameTheLineAndWhatIsAllowed) {
  EXPECT_NE(
      ReadError(WriteFile("a", "ops " + kHex.substr(2) + "\n")).find("line 1: allowed: NAME and 64 hex"),
      std::string::npos);
  EXPECT_NE(ReadError(WriteFile("b", "\nops " + std::string(63, 'a') + "g\n")).find("line 2:"),
            std::string::npos);
  EXPECT_NE(ReadError(WriteFile("c", "ops " + kHex + " extra\n")).find("line 1:"), std::string::npos);
  EXPECT_NE(ReadError(WriteFile("d", "o/ps " + kHex + "\n")).find("allowed letters, digits"),
            std::string::npos);
  EXPECT_NE(ReadError(WriteFile("e", "ops " + kHex + "\nops " + kHex + "\n")).find("line 2: key 'ops' again"),
            std::string::npos);
  EXPECT_NE(ReadError(WriteFile("f", "# nothing\n")).find("no key in it"), std::string::npos);
  EXPECT_NE(ReadError(Path("missing")).find("No such file"), std::string::npos);
  EXPECT_NE(ReadError(directory_.string()).find("not a regular file"), std::string::npos);
}

TEST_F(CommandKeyTest, KeyNamesAreChecked) {
  EXPECT_EQ(CheckKeyName("ops.lab_2-x"), "");
  EXPECT_NE(CheckKeyName(""), "");
  EXPECT_NE(CheckKeyName(std::string(33, 'a')), "");
  EXPECT_NE(CheckKeyName("a b"), "");
}

}  // namespace
}  // namespace flagsim
