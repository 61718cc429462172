#pragma once
// The haptic renderer interface. A renderer node (LineProxyRenderer,
// SurfacePointRenderer, BarbicRenderer, or a plugin's) sits in a device's
// `hapticsRenderer` field; swapping that one element switches the algorithm.
//
// The node holds parameters as fields. For a run, it compiles them, with the
// tool's geometry, into a HapticAlgorithm: parameters fixed, state of its own.
// One step is a function of (the scene view, algorithm state, device pose, dt),
// so replays are bit-reproducible.
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "millsim/core/Node.h"
#include "millsim/haptics/MillTool.h"
#include "millsim/haptics/RendererTraits.h"
#include "millsim/math/Pose.h"

namespace millsim {

class HapticScene;

struct HapticInput {
  Pose device;       // burr centre and tool orientation, world frame
  double dt = 1e-3;  // seconds since the previous step
  bool milling = false;  // the burr spins this frame (the device's main button)
};

struct HapticOutput {
  glm::dvec3 force{0.0};   // N, world frame, on the user's hand
  glm::dvec3 torque{0.0};  // N·m, world frame, about the burr centre
  Pose drawnTool;          // where graphics should draw the tool
  int contacts = 0;        // colliding vertices / points this frame
  bool hasIntersection = false;
  glm::dvec3 intersection{0.0};  // Algorithm #1's shaft intersection point
  bool hasProxy = false;
  glm::dvec3 proxy{0.0};  // the constrained tip (or coupled tool) position
  std::uint32_t flags = 0;  // see HapticFlags
  // Where the burr cuts when milling is on, and whether it may cut this frame.
  // Renderers set this to the burr they draw (see docs/algorithms.md, Milling position).
  bool burrCuts = true;
  glm::dvec3 burrCentre{0.0};
  // The hardness of the tissue at the burr's leading point while it cuts (1
  // otherwise): what the feed was divided by, and what the sound grinds.
  double cutHardness = 1.0;
};

// Events worth logging, as bits of HapticOutput::flags.
enum HapticFlags : std::uint32_t {
  kFlagNonFiniteSuppressed = 1u << 0,  // the algorithm produced NaN/Inf; output zeroed
  kFlagHeldForce = 1u << 1,            // a hold rule (paper eq. 17/19) applied
  kFlagCoarseFallback = 1u << 2,       // the time/contact budget forced a coarser level
};

class HapticAlgorithm {
public:
  virtual ~HapticAlgorithm() = default;
  // Forget all history; the next step starts from this device pose.
  virtual void reset(const Pose& device) = 0;
  virtual HapticOutput step(HapticScene& scene, const HapticInput& in) = 0;
  virtual std::string name() const = 0;
  // Called after reset() when this algorithm takes over from `previous` in a
  // live swap: an algorithm of the same kind (a field was changed and the
  // renderer compiled again) takes over its contact history — a proxy inside
  // the tooth, the held forces of a burr centre past the surface — so the
  // hand feels the new parameters, not a release. Default: nothing carried.
  virtual void carryOver(const HapticAlgorithm& previous) { (void)previous; }
};

// What a renderer's frame-cost estimate may look at (`millsim check`, millsim/devices/DeviceChecks.cpp).
struct FrameCostContext {
  ToolGeometry tool;
  double voxelSize = 0.0;  // the finest voxel edge of the scene's volumes (m); 0 without volumes
  // Points of all volumes' point shells at an integer scale (built on demand; may be costly).
  std::function<std::size_t(int scale)> shellPoints;
};

// A simple cost model: the work of the worst frame (points or vertices
// sampled) times a measured time per unit on the development machine.
struct FrameCostEstimate {
  double seconds = 0.0;  // 0: the renderer declares no model
  std::string model;     // how it was estimated, e.g. "13800 points x 92 ns"
  std::string advice;    // what lowers it, e.g. "lower sphereVertices, slices or verticesPerSlice"
};

class HapticsRendererNode : public Node {
public:
  static constexpr std::string_view kindName = "a haptics renderer (LineProxyRenderer, SurfacePointRenderer, ...)";
  virtual std::unique_ptr<HapticAlgorithm> compile(const ToolGeometry& tool, HapticScene& scene) const = 0;
  // What measure/ and the tests need to know about this type (RendererTraits.h).
  // The default, for renderers that declare nothing: no stiffness field, no
  // resolution sweeps, the Coupling reference, not constraining the tool.
  virtual RendererTraits traits() const { return {}; }
  // Estimated compute time of this configuration's worst frame; `millsim
  // check` warns when it exceeds the device's frame budget (1/desiredHapticsRate).
  virtual FrameCostEstimate estimateFrameCost(const FrameCostContext&) const { return {}; }
  // Why this renderer cannot carry `tool` (a burr head it cannot represent),
  // or empty when it can: compile() refuses such a tool with this sentence,
  // and `millsim check` reports it at the renderer's line before a run would.
  virtual std::string cannotCarry(const ToolGeometry& tool) const {
    (void)tool;
    return {};
  }
};

// Replaces NaN/Inf in an output with zero force and torque and flags it: no
// non-finite value ever leaves a renderer.
void sanitize(HapticOutput& out, const Pose& device);

}  // namespace millsim
