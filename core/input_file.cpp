#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>
#include <utility>

#include "core/checkpoint.h"
#include "core/error.h"
#include "core/memory_budget.h"

namespace kasha {
namespace {

// (device, inode) of every file opened as an input.
std::mutex gInputsMutex;
std::set<std::pair<dev_t, ino_t>> gInputs;

thread_local InputDigest* tRecording = nullptr;  // RecordInputs

const char* fileKind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

InputFile::InputFile(std::string path, const std::string& what, uint64_t maxBytes)
    : path_(std::move(path)), what_(what) {
  do {
    fd_ = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  } while (fd_ < 0 && errno == EINTR);
  if (fd_ < 0) throw InputError(path_, "", "cannot open " + what_ + " (" + std::strerror(errno) + ")");
  struct stat st {};
  const bool statted = ::fstat(fd_, &st) == 0;
  if (!statted || !S_ISREG(st.st_mode)) {
    const std::string why = statted ? fileKind(st.st_mode) : std::strerror(errno);
    ::close(fd_);
    throw InputError(path_, "", "cannot open " + what_ + " (" + why + ", not a regular file)");
  }
  size_ = uint64_t(st.st_size);
  if (size_ > maxBytes) {
    ::close(fd_);
    throw InputError(path_, "", what_ + " is " + formatBytes(size_) + ", more than the " + formatBytes(maxBytes) +
                                    " allowed");
  }
  const std::lock_guard<std::mutex> lock(gInputsMutex);
  gInputs.emplace(st.st_dev, st.st_ino);
}

InputFile::~InputFile() { ::close(fd_); }

void InputFile::read(void* data, size_t n) {
  char* p = static_cast<char*>(data);
  while (n > 0) {
    const ssize_t got = ::read(fd_, p, n);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw InputError(path_, "", "cannot read " + what_ + " (" + std::strerror(errno) + ")");
    if (got == 0) throw InputError(path_, "", what_ + " is truncated");
    p += got, n -= size_t(got), position_ += uint64_t(got);
  }
  // Chained per read call, so the digest depends on the bytes and the reader's calls alone.
  if (tRecording) tRecording->value_ = hashBytes(data, size_t(p - static_cast<char*>(data)), tRecording->value_);
}

RecordInputs::RecordInputs(InputDigest& digest) : previous_(tRecording) { tRecording = &digest; }

RecordInputs::~RecordInputs() { tRecording = previous_; }

std::string InputFile::readRest() {
  // The size was capped at opening; a file that grows meanwhile is read up to that size.
  std::string bytes(size_ - std::min(position_, size_), '\0');
  read(bytes.data(), bytes.size());
  return bytes;
}

std::string readInputFile(const std::string& path, const std::string& what, uint64_t maxBytes) {
  InputFile f(path, what, maxBytes);
  return f.readRest();
}

bool wasReadAsInput(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return false;
  const std::lock_guard<std::mutex> lock(gInputsMutex);
  return gInputs.count({st.st_dev, st.st_ino}) > 0;
}

}  // namespace kasha
