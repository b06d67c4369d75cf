#pragma once
// A test fixture with a fresh directory of its own, removed afterwards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace kasha::test {

class TempDirTest : public ::testing::Test {
 protected:
  // `name` tells the tests apart in the temporary directory.
  explicit TempDirTest(const std::string& name)
      : dir((std::filesystem::path(::testing::TempDir()) / ("kasha_" + name + "." + std::to_string(getpid()))).string()) {}
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
  // Writes `bytes` to the file `name` in the directory; returns its path.
  std::string writeFile(const std::string& name, const std::string& bytes) const {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  const std::string dir;
};

}  // namespace kasha::test
