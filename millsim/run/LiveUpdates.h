#pragma once
// LiveUpdates: the live part of the scene graph during a run. The haptic
// thread never reads fields, so the scene thread watches (FieldWatch) the
// fields that may change while running — set by the window's keys, by routes, or by a plugin
// — and hands each change over wait-free:
//   device enabled, forceLimit, torqueLimit → HapticLoop::setLive
//   VolumeObject millable                    → VoxelScene::Volume::millable
//   device hapticsRenderer, MillTool fields  → RendererPool (when there is one:
//                                              followDeviceField, followTool)
// Everything else a run compiled (Transforms, Barbic's parameters, the rate)
// takes effect at the next run; docs/nodes.md says so per field.
#include <string>
#include <vector>

#include "millsim/core/FieldWatch.h"

namespace millsim {

class HapticLoop;
struct CompiledRun;

class LiveUpdates {
public:
  LiveUpdates(CompiledRun& run, HapticLoop& loop);
  // Scene thread, every tick: applies what changed; returns a notice for the
  // user (empty when nothing changed).
  std::string poll();

private:
  CompiledRun& run_;
  HapticLoop& loop_;
  FieldWatch enabled_, forceLimit_, torqueLimit_;
  std::vector<FieldWatch> millable_;  // per volume of the run (empty for one without a node)
};

}  // namespace millsim
