// Writing outputs (core/output_file.h): a unique temporary file beside the target, renamed over it
// only when everything was written; nothing left behind on failure; every output path checked
// before any work.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_file.h"
#include "core/output_file.h"
#include "tests/expect_contains.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

class OutputFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = (fs::path(::testing::TempDir()) / ("kasha_output_file." + std::to_string(getpid())) / info->name()).string();
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(fs::path(dir).parent_path());
  }
  std::vector<std::string> entries() const {
    std::vector<std::string> v;
    for (const auto& e : fs::directory_iterator(dir)) v.push_back(e.path().filename().string());
    std::sort(v.begin(), v.end());
    return v;
  }
  static std::string read(const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  }
  std::string usageError(const std::vector<OutputTarget>& outputs, const std::vector<std::string>& later = {}) const {
    try {
      checkOutputs(outputs, later);
    } catch (const UsageError& e) {
      return e.what();
    }
    return "no error";
  }
  std::string dir;
};

TEST_F(OutputFiles, NothingUnderTheNameUntilCommitted) {
  const std::string p = dir + "/out.txt";
  std::ofstream(p) << "old";
  {
    OutputFile f(p);
    f.write("new text", 8);
    EXPECT_EQ(read(p), "old");  // still the old file
    EXPECT_EQ(entries().size(), 2u);  // and the temporary beside it
    f.commit();
  }
  EXPECT_EQ(read(p), "new text");
  EXPECT_EQ(entries(), std::vector<std::string>{"out.txt"});
  EXPECT_EQ(fs::status(p).permissions() & fs::perms::owner_read, fs::perms::owner_read);
}

TEST_F(OutputFiles, AnAbandonedFileLeavesNothing) {
  const std::string p = dir + "/out.exr";
  {
    OutputFile f(p);
    f.write("partial", 7);
  }  // an exception before commit() ends here
  EXPECT_TRUE(entries().empty());
}

TEST_F(OutputFiles, TwoWritersOfOneNameNeverShareATemporaryFile) {
  const std::string p = dir + "/same.exr";
  OutputFile a(p), b(p);
  a.write("first writer", 12);
  b.write("second", 6);
  EXPECT_EQ(entries().size(), 2u);
  b.commit();
  a.commit();
  EXPECT_EQ(read(p), "first writer");  // the last rename wins, whole
  EXPECT_EQ(entries(), std::vector<std::string>{"same.exr"});
}

TEST_F(OutputFiles, SeekRewritesInPlace) {
  const std::string p = dir + "/table.bin";
  OutputFile f(p);
  f.write("aaaaaa", 6);
  f.seek(2);
  f.write("XY", 2);
  EXPECT_EQ(f.tell(), 4u);
  f.commit();
  EXPECT_EQ(read(p), "aaXYaa");
}

// A full disk, as the file size limit: write() fails with EFBIG (SIGXFSZ ignored). In a child
// process, so the limit does not outlive the test.
TEST_F(OutputFiles, AFailedWriteIsAnErrorAndLeavesNothing) {
  const std::string p = dir + "/big.bin";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit lim{4096, 4096};
    setrlimit(RLIMIT_FSIZE, &lim);
    try {
      writeFileAtomically(p, std::string(10000, 'x'));
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      _exit(msg.find("cannot write '" + p + "': write failed (File too large)") == 0 ? 3 : 4);
    }
    _exit(5);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3) << "4: another message, 5: no error";
  EXPECT_TRUE(entries().empty());
}

TEST_F(OutputFiles, OutputPathsAreCheckedBeforeAnyWork) {
  const std::string exr = dir + "/a.exr";
  EXPECT_EQ(usageError({{exr, "-o", ".exr", ""}}), "no error");
  EXPECT_EQ(usageError({{dir + "/a.png", "-o", ".exr", ""}}),
            dir + "/a.png: -o: must end in .exr (the file is written in that format)");
  fs::create_directories(dir + "/folder.exr");
  EXPECT_EQ(usageError({{dir + "/folder.exr", "-o", ".exr", ""}}), dir + "/folder.exr: -o: is a directory");
  EXPECT_EQ(usageError({{dir + "/none/a.exr", "-o", ".exr", ""}}),
            dir + "/none/a.exr: -o: directory '" + dir + "/none' does not exist");
  EXPECT_EQ(usageError({{exr, "-o", ".exr", ""}, {dir + "/./a.exr", "--png", "", ""}}),
            dir + "/./a.exr: --png: is also the output of -o; each output needs its own file");
  EXPECT_EQ(usageError({{"/dev/null", "--checkpoint", "", ""}}), "/dev/null: --checkpoint: exists and is not a regular file");
  // An input: read by this process, or still to be read; a checkpoint may replace the one it resumes.
  const std::string csv = dir + "/input.csv";
  std::ofstream(csv) << "x";
  readInputFile(csv, "spectrum file", 100);
  EXPECT_EQ(usageError({{csv, "--png", "", ""}}), csv + ": --png: is one of the inputs; it would be overwritten");
  const std::string ckpt = dir + "/r.ckpt";
  std::ofstream(ckpt) << "x";
  EXPECT_EQ(usageError({{ckpt, "-o", "", ""}}, {ckpt}), ckpt + ": -o: is one of the inputs; it would be overwritten");
  EXPECT_EQ(usageError({{ckpt, "--resume", "", ckpt}}, {ckpt}), "no error");
}

}  // namespace
}  // namespace kasha
