#pragma once
// A test fixture with a fresh directory of its own, removed afterwards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace kasha::test {

class TempDirTest : public ::testing::Test {
 protected:
  // `name` tells the tests apart in the temporary directory.
  explicit TempDirTest(const std::string& name)
      : dir((std::filesystem::path(::testing::TempDir()) / ("kasha_" + name + "." + std::to_string(getpid()))).string()) {}
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }

  const std::string dir;
};

}  // namespace kasha::test
