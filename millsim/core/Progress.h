#pragma once
// The long steps of loading a scene (reading a volume, classifying its
// tissues, measuring a lesson's regions), said as each starts and ends so that
// a front end can show what the user waits for: at 25 µm a lesson takes
// seconds to open. Heard on the loading thread; no listener, no cost.
#include <chrono>
#include <string>

namespace millsim {

class LoadProgress {
public:
  virtual ~LoadProgress() = default;
  virtual void started(const std::string& step) = 0;
  virtual void finished(const std::string& step, double seconds) = 0;
};

// One step: started when made, finished (with its wall time) when it goes
// out of scope, an exception included.
class ProgressStep {
public:
  ProgressStep(LoadProgress* listener, std::string step) : listener_(listener), step_(std::move(step)) {
    if (listener_) listener_->started(step_);
  }
  ~ProgressStep() {
    if (listener_)
      listener_->finished(step_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  }
  ProgressStep(const ProgressStep&) = delete;
  ProgressStep& operator=(const ProgressStep&) = delete;

private:
  LoadProgress* listener_;
  std::string step_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace millsim
