// Runs every file given (or every file in every folder given) through the fuzz target once, in
// any build and with any compiler: the seed corpus, and every crash reproducer added to it, thereby
// stays a regression test in plain `ctest`, not only when someone runs `make fuzz` with clang.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const fs::path arg = argv[i];
    if (fs::is_directory(arg)) {
      for (const auto& entry : fs::directory_iterator(arg))
        if (entry.is_regular_file()) files.push_back(entry.path());
    } else if (fs::is_regular_file(arg)) {
      files.push_back(arg);
    } else {
      std::fprintf(stderr, "replay: %s: no such file or folder\n", arg.c_str());
      return 1;
    }
  }
  // An empty or mistyped corpus path must not pass as "all inputs handled".
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR_OR_FILE...  (found no input files)\n", argv[0]);
    return 1;
  }
  std::sort(files.begin(), files.end());  // same order on every run, so a failure reproduces
  for (const auto& file : files) {
    // Printed before running: after a crash the last name shown is the reproducer.
    std::fprintf(stderr, "replay: %s\n", file.c_str());
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    try {
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "replay: %s: escaped exception (not an InputError): %s\n", file.c_str(), e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "replay: %zu inputs, all handled\n", files.size());
  return 0;
}
