#pragma once
// Whole-scene checks of the device (registered with NodeRegistry::addSceneCheck
// by registerBuiltinNodes, so the loader runs them for every verb):
// - several devices: an error naming each (a run drives one device);
// - a device inside a Transform: an error naming the Transform (a device's
//   frame is the world; its calibration fields place it);
// - the burr larger than a volume: a warning with both sizes;
// - a renderer whose estimated frame cost exceeds the device's frame budget
//   (1/desiredHapticsRate): a warning naming the estimate (RendererTraits).
// Per-node problems (no MillTool, no renderer, no trajectory url) are warned
// about by the device nodes themselves when they are read.
namespace millsim {

class Scene;
class DiagnosticSink;

void checkDevices(const Scene& scene, DiagnosticSink& sink);

}  // namespace millsim
