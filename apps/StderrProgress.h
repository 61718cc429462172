#pragma once
// The load's long steps on standard error (millsim/core/Progress.h): on a
// terminal the step being done stands on one line until it ends; any step
// that took a second or more is then said with its time, terminal or not, so
// a log shows where a slow lesson's opening went.
#include <unistd.h>

#include <cstdio>
#include <string>

#include "millsim/core/Progress.h"

namespace millsim::app {

class StderrProgress final : public LoadProgress {
public:
  void started(const std::string& step) override {
    if (terminal_) std::fprintf(stderr, "\r\033[Kmillsim: %s ...", step.c_str());
  }
  void finished(const std::string& step, double seconds) override {
    if (terminal_) std::fprintf(stderr, "\r\033[K");
    if (seconds >= 1.0) std::fprintf(stderr, "millsim: %s: %.1f s\n", step.c_str(), seconds);
    std::fflush(stderr);
  }

private:
  bool terminal_ = isatty(STDERR_FILENO) == 1;
};

}  // namespace millsim::app
