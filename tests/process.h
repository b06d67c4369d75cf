#pragma once
// Running the kasha binary from tests as a child process (posix_spawn): start it, signal it, wait
// for it with a timeout, read what it printed.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace kasha::test {

inline const std::string kKashaBinary = KASHA_BINARY_DIR "/kasha";

inline std::string readTextFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// A started kasha process; stdout and stderr go to files.
struct Child {
  pid_t pid = -1;
  std::string out, err;  // paths of the captured streams
};

// Starts `kasha args...` with stdout/stderr redirected to `prefix`.stdout/.stderr.
inline Child spawnKasha(const std::vector<std::string>& args, const std::string& prefix) {
  Child c;
  c.out = prefix + ".stdout";
  c.err = prefix + ".stderr";
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, c.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, c.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<std::string> all = {kKashaBinary};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  if (posix_spawn(&c.pid, kKashaBinary.c_str(), &fa, nullptr, argv.data(), environ) != 0) c.pid = -1;
  posix_spawn_file_actions_destroy(&fa);
  return c;
}

// Waits up to `seconds` for the child; returns its wait status, or -1 on timeout (the child is
// then killed, so no test leaves a render running).
inline int waitChild(const Child& c, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (true) {
    const pid_t r = waitpid(c.pid, &status, WNOHANG);
    if (r == c.pid) return status;
    if (r < 0) return -1;
    if (std::chrono::steady_clock::now() > deadline) {
      kill(c.pid, SIGKILL);
      waitpid(c.pid, &status, 0);
      return -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

struct Finished {
  int status = -1;  // wait status
  int code = -1;    // exit code, or -1 if it did not exit normally
  std::string out, err;
};

// Runs `kasha args...` to completion (at most `seconds`).
inline Finished runKasha(const std::vector<std::string>& args, const std::string& prefix, double seconds = 600.0) {
  const Child c = spawnKasha(args, prefix);
  Finished f;
  if (c.pid < 0) return f;
  f.status = waitChild(c, seconds);
  f.code = (f.status != -1 && WIFEXITED(f.status)) ? WEXITSTATUS(f.status) : -1;
  f.out = readTextFile(c.out);
  f.err = readTextFile(c.err);
  return f;
}

// The lines of a text.
inline std::vector<std::string> textLines(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}

}  // namespace kasha::test
