#pragma once
// Opening the files a user names — scene, material file, spectrum or matrix CSV, OBJ or PLY mesh,
// texture or measured OpenEXR, checkpoint, the images of `kasha metrics` — by one rule:
// - regular files only: a FIFO, a device (/dev/zero), a socket or a directory is refused at once.
//   The file is opened with O_NONBLOCK (opening a FIFO cannot block) and checked with fstat on
//   the opened descriptor, so what is checked is what is read;
// - a size cap per kind of file, checked before anything is read;
// - every error is an InputError naming the file.
// Each file opened this way is remembered by device and inode, so that an output can be refused
// when it would overwrite one of the process's inputs (wasReadAsInput).
#include <cstdint>
#include <string>

namespace kasha {

// Caps on input sizes. A scene or material file is hand-written JSON; 64 MiB is far beyond any.
constexpr uint64_t kMaxJsonFileBytes = uint64_t(64) << 20;
// An image file (PNG, OpenEXR); what it decodes to is checked against the memory limit from its
// header (core/image_input.h).
constexpr uint64_t kMaxImageFileBytes = uint64_t(2) << 30;

// An opened input file: regular, at most maxBytes long. Reads are checked.
class InputFile {
 public:
  // `what` names the kind of file in messages, e.g. "scene file" → "a.json: cannot open scene
  // file (No such file or directory)". Throws InputError.
  InputFile(std::string path, const std::string& what, uint64_t maxBytes);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::string& path() const { return path_; }
  // The size of the opened file (fstat), not of whatever the name points to by now.
  uint64_t size() const { return size_; }
  // Reads exactly n bytes; a short read is an InputError "<what> is truncated".
  void read(void* data, size_t n);
  // The bytes from the current position to the end.
  std::string readRest();
  // Whether everything has been read.
  bool atEnd() const { return position_ == size_; }

 private:
  std::string path_, what_;
  int fd_ = -1;
  uint64_t size_ = 0, position_ = 0;
};

// The content of the input files read on one thread while a RecordInputs for it lives, as one
// digest: what a scene was loaded from besides its own text (meshes, spectra, textures, material
// and included files), so that checkpoints and MPI ranks tell apart scenes whose files differ.
class InputDigest {
 public:
  uint64_t value() const { return value_; }

 private:
  friend class InputFile;
  uint64_t value_ = 0;
};

// Every InputFile read on this thread while it lives goes into `digest` (nested: the innermost).
class RecordInputs {
 public:
  explicit RecordInputs(InputDigest& digest);
  ~RecordInputs();
  RecordInputs(const RecordInputs&) = delete;
  RecordInputs& operator=(const RecordInputs&) = delete;

 private:
  InputDigest* previous_;
};

// The whole file as bytes (InputFile's rules).
std::string readInputFile(const std::string& path, const std::string& what, uint64_t maxBytes);

// Whether `path` names a file (the same device and inode) this process has opened as an input.
bool wasReadAsInput(const std::string& path);

}  // namespace kasha
