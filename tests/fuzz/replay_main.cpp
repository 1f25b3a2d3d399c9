// The fuzz targets' main without libFuzzer (the normal build, any compiler): runs every file of
// the directories given (and any file given) through LLVMFuzzerTestOneInput once, as libFuzzer's
// -runs=0 would, so that CTest replays each target's seed corpus and its regressions with no
// clang. A directory that does not exist is skipped with a note (a target with no regressions
// has none); no input at all is an error, since a target always has its corpus.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

namespace fs = std::filesystem;

/// The regular files at `path`: itself, or a directory's, in name order.
std::vector<fs::path> InputsAt(const fs::path& path) {
  if (!fs::is_directory(path)) return {path};
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(path)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  size_t inputs = 0;
  for (int i = 1; i < argc; ++i) {
    const fs::path path = argv[i];
    if (!fs::exists(path)) {
      std::printf("%s: not there, skipped\n", argv[i]);
      continue;
    }
    for (const fs::path& file : InputsAt(path)) {
      std::ifstream stream(file, std::ios::binary);
      const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(stream)),
                                       std::istreambuf_iterator<char>());
      if (!stream.good() && !stream.eof()) {
        std::fprintf(stderr, "%s: cannot be read\n", file.c_str());
        return 1;
      }
      std::printf("%s (%zu bytes)\n", file.c_str(), bytes.size());
      std::fflush(stdout);  // a crash names the input it died on
      LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
      ++inputs;
    }
  }
  if (inputs == 0) {
    std::fprintf(stderr, "no inputs: give the target's corpus directory (and its regressions)\n");
    return 1;
  }
  std::printf("%zu inputs ran\n", inputs);
  return 0;
}
