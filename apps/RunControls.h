#pragma once
// What the window thread and the scene thread of `millsim run` share: the HUD
// numbers and the scene's cut planes when a route changed them (scene thread →
// window), the window's commands (window → scene thread) and whether the user
// closed the window. A mutex guards it: neither
// side is the haptic thread, and each holds it only to copy a few fields.
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "millsim/graphics/SceneView.h"
#include "millsim/window/AppWindow.h"

namespace millsim::app {

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
  // The scene's cut planes, new while running (scene thread → window).
  void setSceneCuts(SceneView cuts) {
    std::lock_guard lock(mutex_);
    cuts_ = std::move(cuts);
  }
  std::optional<SceneView> takeSceneCuts() {
    std::lock_guard lock(mutex_);
    return std::exchange(cuts_, std::nullopt);
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
  std::optional<SceneView> cuts_;
  bool closed_ = false;
};

}  // namespace millsim::app
