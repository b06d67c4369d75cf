#pragma once
// A progress bar with ETA on stderr, drawn only when stderr is a terminal.
#include <string>

namespace kasha {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  void update(int spp, double seconds, double totalSeconds);
  void finish();

 private:
  std::string label_;
  bool tty_;
  bool drawn_ = false;
};

}  // namespace kasha
