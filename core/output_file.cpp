#include "core/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/error.h"
#include "core/input_file.h"

namespace kasha {
namespace {

namespace fs = std::filesystem;

std::string directoryOf(const std::string& path) {
  const fs::path dir = fs::path(path).parent_path();
  return dir.empty() ? "." : dir.string();
}

// The permissions an ordinary open(…, 0666) would give: mkstemp creates files 0600.
mode_t defaultMode() {
  static const mode_t mode = [] {
    const mode_t mask = ::umask(0);  // read it: umask can only be read by setting it
    ::umask(mask);
    return mode_t(0666 & ~mask);
  }();
  return mode;
}

void syncDirectory(const std::string& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the rename itself is atomic
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  const fs::path name = fs::path(path_).filename();
  tmp_ = (fs::path(directoryOf(path_)) / ("." + name.string() + ".XXXXXX")).string();
  defaultMode();  // before the file exists: reading the umask changes it for a moment
  fd_ = ::mkostemp(tmp_.data(), O_CLOEXEC);
  if (fd_ < 0) {
    const int e = errno;
    tmp_.clear();
    fail("cannot create a temporary file beside it", e);
  }
}

OutputFile::~OutputFile() {
  if (committed_) return;
  if (fd_ >= 0) ::close(fd_);
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
}

void OutputFile::fail(const std::string& what, int error) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!tmp_.empty()) ::unlink(tmp_.c_str());
  tmp_.clear();
  throw OutputError(path_, what + " (" + std::strerror(error) + ")");
}

void OutputFile::write(const void* data, size_t n) {
  if (fd_ < 0) throw OutputError(path_, "the file is closed");
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = ::write(fd_, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) fail("write failed", w < 0 ? errno : ENOSPC);
    p += w, n -= size_t(w), position_ += uint64_t(w);
  }
}

void OutputFile::seek(uint64_t position) {
  if (fd_ < 0) throw OutputError(path_, "the file is closed");
  if (::lseek(fd_, off_t(position), SEEK_SET) < 0) fail("seek failed", errno);
  position_ = position;
}

void OutputFile::commit() {
  if (fd_ < 0) throw OutputError(path_, "the file is closed");
  if (::fchmod(fd_, defaultMode()) != 0) fail("cannot set its permissions", errno);
  // On disk before the rename, so that after a crash the name holds the old or the new file.
  if (::fsync(fd_) != 0) fail("fsync failed", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("close failed", errno);
  if (::rename(tmp_.c_str(), path_.c_str()) != 0) fail("cannot rename the temporary file '" + tmp_ + "' to it", errno);
  committed_ = true;
  syncDirectory(directoryOf(path_));
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
  OutputFile f(path);
  f.write(bytes.data(), bytes.size());
  f.commit();
}

void checkOutputs(const std::vector<OutputTarget>& outputs, const std::vector<std::string>& laterInputs) {
  std::vector<fs::path> seen;
  for (const OutputTarget& o : outputs) {
    const auto fail = [&](const std::string& reason) { throw UsageError(o.path, o.option, reason); };
    if (o.path.empty()) fail("is empty");
    if (!o.extension.empty() && fs::path(o.path).extension() != o.extension)
      fail("must end in " + o.extension + " (the file is written in that format)");
    std::error_code ec;
    if (fs::is_directory(o.path, ec)) fail("is a directory");
    const std::string dir = directoryOf(o.path);
    if (!fs::is_directory(dir, ec)) fail("directory '" + dir + "' does not exist");
    // access(W_OK) is not proof: root passes it everywhere, and /proc, sysfs or a read-only mount
    // refuse new files anyway. Creating (and removing) the temporary file the write will create is.
    try {
      OutputFile probe(o.path);
    } catch (const OutputError& e) {
      fail("directory '" + dir + "' is not writable: " + e.reason());
    }
    if (fs::exists(o.path, ec) && !fs::is_regular_file(o.path, ec)) fail("exists and is not a regular file");
    const auto same = [&](const std::string& p) { return !p.empty() && fs::exists(p, ec) && fs::equivalent(p, o.path, ec); };
    bool input = wasReadAsInput(o.path);
    for (const std::string& p : laterInputs) input = input || same(p);
    if (input && !same(o.mayReplace)) fail("is one of the inputs; it would be overwritten");
    // Two outputs are the same file if their absolute, normalised paths are (neither need exist yet).
    const fs::path key = fs::weakly_canonical(fs::absolute(o.path), ec);
    for (size_t k = 0; k < seen.size(); ++k)
      if (seen[k] == key) fail("is also the output of " + outputs[k].option + "; each output needs its own file");
    seen.push_back(key);
  }
}

}  // namespace kasha
