#pragma once
// Shared by the file-reading fuzz targets: kasha's readers take paths, so each input is written
// to a file in a directory of this process's own (removed at exit) before it is read.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace kasha::fuzz {

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
