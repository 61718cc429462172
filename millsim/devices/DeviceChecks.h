#pragma once
// Whole-scene checks of the device (registered with NodeRegistry::addSceneCheck
// by registerBuiltinNodes, so the loader runs them for every verb):
// - several devices: an error naming each (a run drives one device);
// - a device inside a Transform: an error naming the Transform (a device's
//   frame is the world; its calibration fields place it);
// - the burr larger than a volume: a warning with both sizes;
// - a renderer whose estimated frame cost exceeds the device's frame budget
//   (1/desiredHapticsRate): a warning naming the estimate (RendererTraits);
// - a renderer that cannot carry the burr: an error (run would refuse it);
// - the device's trajectory out of the tool's reach of every volume: a warning
//   naming the unit it would fit (trajectoryReachWarning).
// Per-node problems (no MillTool, no renderer, no trajectory url) are warned
// about by the device nodes themselves when they are read.
#include <string>

namespace millsim {

class Scene;
class Trajectory;
class DiagnosticSink;

void checkDevices(const Scene& scene, DiagnosticSink& sink);

// Empty when some position of `trajectory` (named `label` in the sentence)
// comes within the scene's device's tool (burr radius plus shaft length) of a
// loaded volume's box; else a sentence saying how far its nearest position is
// and, when its numbers read in mm, cm or um would come near, that unit. Empty
// too for a scene without volumes. `millsim run`, `replay` and `render` print
// it for a --trajectory; check warns with it for a device's url.
std::string trajectoryReachWarning(const Scene& scene, const Trajectory& trajectory, const std::string& label);

}  // namespace millsim
