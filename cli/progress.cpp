#include "cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace kasha {

ProgressBar::ProgressBar(std::string label) : label_(std::move(label)), tty_(isatty(STDERR_FILENO) != 0) {}

void ProgressBar::update(int spp, double seconds, double totalSeconds) {
  if (!tty_) return;
  const double frac = totalSeconds > 0.0 ? std::clamp(seconds / totalSeconds, 0.0, 1.0) : 0.0;
  const int width = 30, filled = int(frac * width + 0.5);
  std::string bar(size_t(filled), '#');
  bar.resize(size_t(width), '.');
  std::fprintf(stderr, "\r%s [%s] %3d%%  %d spp  %.1fs  ETA %.1fs   ", label_.c_str(), bar.c_str(), int(frac * 100.0 + 0.5),
               spp, seconds, std::max(0.0, totalSeconds - seconds));
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (tty_ && drawn_) std::fprintf(stderr, "\n");
}

}  // namespace kasha
