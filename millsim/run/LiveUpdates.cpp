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
      enabled_({&run.device->enabled}),
      forceLimit_({&run.device->forceLimit}),
      torqueLimit_({&run.device->torqueLimit}) {
  for (std::size_t i = 0; i < run.scene->volumeCount(); ++i) {
    VolumeObject* node = run.scene->volume(i).node;
    millable_.push_back(node ? FieldWatch({&node->millable}) : FieldWatch());
  }
}

std::string LiveUpdates::poll() {
  std::ostringstream notice;
  const HapticsDevice& d = *run_.device;
  const bool enabled = enabled_.changed(), force = forceLimit_.changed(), torque = torqueLimit_.changed();
  if (enabled || force || torque) {
    if (enabled) notice << "force output " << (d.enabled.get() ? "on" : "off") << "  ";
    if (force) notice << "forceLimit " << d.forceLimit.get() << " N  ";
    if (torque) notice << "torqueLimit " << d.torqueLimit.get() << " N·m  ";
    enabled_.mark(), forceLimit_.mark(), torqueLimit_.mark();
    loop_.setLive(d.enabled.get(), d.forceLimit.get(), d.torqueLimit.get());
  }
  for (std::size_t i = 0; i < millable_.size(); ++i) {
    if (!millable_[i].changed()) continue;
    millable_[i].mark();
    VoxelScene::Volume& v = run_.scene->volume(i);
    const bool millable = v.node->millable.get();
    v.millable.store(millable, std::memory_order_relaxed);
    notice << (v.node->defName().empty() ? "volume " + std::to_string(i) : v.node->defName())
           << (millable ? " millable" : " not millable") << "  ";
  }
  std::string s = notice.str();
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace millsim
