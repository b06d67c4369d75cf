#pragma once
// Shared by the fuzz targets: promises that abort when broken, and, since kasha's readers take
// paths, a directory of the process's own (removed at exit) to write each input to before it is read.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace kasha::fuzz {

// A promise of the code under test: aborts (a libFuzzer finding) with `what` if it is broken.
inline void require(bool ok, const char* target, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "%s: broken promise: %s\n", target, what);
    std::abort();
  }
}

// The process's scratch directory, created on first use; data files of tests/fuzz/data are
// linked into it, so that inputs can name them by relative paths.
inline const std::string& scratchDirectory() {
  static const std::string dir = [] {
    namespace fs = std::filesystem;
    const fs::path d = fs::temp_directory_path() / ("kasha_fuzz." + std::to_string(getpid()));
    fs::create_directories(d);
    for (const auto& e : fs::directory_iterator(KASHA_FUZZ_DATA_DIR)) {
      std::error_code ec;
      fs::create_symlink(e.path(), d / e.path().filename(), ec);
    }
    static const std::string removeAtExit = d.string();
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(removeAtExit, ec);
    });
    return d.string();
  }();
  return dir;
}

// Writes the input to `name` in the scratch directory; returns its path.
inline std::string writeInput(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = scratchDirectory() + "/" + name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

}  // namespace kasha::fuzz
