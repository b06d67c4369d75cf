#pragma once
// Writing output files so that a failure never leaves a half file or a stray temporary behind,
// and checking every output path before a render starts.
//
// OutputFile writes to a unique temporary file in the target's directory (mkstemp
// ".NAME.XXXXXX", so two processes writing the same name never share one), checks every write,
// the fsync and the close, and renames it over the target last (then syncs the directory). Until
// commit() nothing exists under the target name; if commit() is not reached (an exception, a
// failed write) the destructor removes the temporary file.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace kasha {

// A failure to write an output: "cannot write 'path': reason".
class OutputError : public std::runtime_error {
 public:
  OutputError(const std::string& path, const std::string& reason)
      : std::runtime_error("cannot write '" + path + "': " + reason), reason_(reason) {}
  const std::string& reason() const { return reason_; }

 private:
  std::string reason_;
};

class OutputFile {
 public:
  // Creates the temporary file. Throws OutputError.
  explicit OutputFile(std::string path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& path() const { return path_; }
  // Writes n bytes at the current position (all of them, or throws).
  void write(const void* data, size_t n);
  uint64_t tell() const { return position_; }
  void seek(uint64_t position);
  // fsync, close, rename over path(), fsync of the directory. Throws on any failure, removing
  // the temporary file.
  void commit();

 private:
  [[noreturn]] void fail(const std::string& what, int error);
  std::string path_, tmp_;
  int fd_ = -1;
  uint64_t position_ = 0;
  bool committed_ = false;
};

// `bytes` to `path` through an OutputFile.
void writeFileAtomically(const std::string& path, const std::string& bytes);

// One output a command will write: its path, the option that named it (for messages), the
// extension it must have ("" for any) and the one input it may replace ("" for none; a
// checkpoint replaces the one it resumes).
struct OutputTarget {
  std::string path, option, extension, mayReplace;
};

// Checks, before any work, that every output can be written: its directory exists and takes a
// new file (one is created and removed, as OutputFile would), the path is not a directory, has its extension, is not an input (a file this process
// has read, input_file.h — the scene and the CSV, OBJ, texture and material files it names — or
// one of `laterInputs`, still to be read), and no two outputs name the same file. Throws
// UsageError naming the option and the path.
void checkOutputs(const std::vector<OutputTarget>& outputs, const std::vector<std::string>& laterInputs = {});

}  // namespace kasha
