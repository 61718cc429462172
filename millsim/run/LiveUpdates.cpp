#include "millsim/run/LiveUpdates.h"

#include <sstream>

#include "millsim/devices/HapticsDevice.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/run/RunSetup.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelScene.h"

namespace millsim {

LiveUpdates::LiveUpdates(CompiledRun& run, HapticLoop& loop)
    : run_(run),
      loop_(loop),
      enabled_(run.settings.enabled),
      forceLimit_(run.settings.limits.forceLimit),
      torqueLimit_(run.settings.limits.torqueLimit) {
  for (std::size_t i = 0; i < run.scene->volumeCount(); ++i) millable_.push_back(run.scene->volume(i).millable.load());
}

std::string LiveUpdates::poll() {
  std::ostringstream notice;
  const HapticsDevice& d = *run_.device;
  const bool enabled = d.enabled.get();
  const double force = d.forceLimit.get(), torque = d.torqueLimit.get();
  if (enabled != enabled_ || force != forceLimit_ || torque != torqueLimit_) {
    if (enabled != enabled_) notice << "force output " << (enabled ? "on" : "off") << "  ";
    if (force != forceLimit_) notice << "forceLimit " << force << " N  ";
    if (torque != torqueLimit_) notice << "torqueLimit " << torque << " N·m  ";
    enabled_ = enabled, forceLimit_ = force, torqueLimit_ = torque;
    loop_.setLive(enabled, force, torque);
  }
  for (std::size_t i = 0; i < millable_.size(); ++i) {
    VoxelScene::Volume& v = run_.scene->volume(i);
    if (!v.node) continue;
    const bool millable = v.node->millable.get();
    if (millable == millable_[i]) continue;
    millable_[i] = millable;
    v.millable.store(millable, std::memory_order_relaxed);
    notice << (v.node->defName().empty() ? "volume " + std::to_string(i) : v.node->defName())
           << (millable ? " millable" : " not millable") << "  ";
  }
  std::string s = notice.str();
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace millsim
