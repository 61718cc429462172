#pragma once
// What the window thread and the scene thread of `millsim run` share: the HUD
// numbers (scene thread → window), the window's commands and keys (window →
// scene thread) and whether the user closed the window. (A new view of the
// scene goes through RunGraphics::publishView, wait-free.) A mutex guards it: neither
// side is the haptic thread, and each holds it only to copy a few fields.
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "millsim/window/AppWindow.h"

namespace millsim {

class RunControls {
public:
  void setHud(const HudState& hud) {
    std::lock_guard lock(mutex_);
    hud_ = hud;
  }
  HudState hud() const {
    std::lock_guard lock(mutex_);
    return hud_;
  }
  void post(const std::vector<WindowCommand>& commands) {
    if (commands.empty()) return;
    std::lock_guard lock(mutex_);
    commands_.insert(commands_.end(), commands.begin(), commands.end());
  }
  std::vector<WindowCommand> take() {
    std::lock_guard lock(mutex_);
    return std::exchange(commands_, {});
  }
  void close() {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  bool closed() const {
    std::lock_guard lock(mutex_);
    return closed_;
  }

private:
  mutable std::mutex mutex_;
  HudState hud_;
  std::vector<WindowCommand> commands_;
  bool closed_ = false;
};

}  // namespace millsim
