// Node types from outside MillSim, loaded by <ImportLibrary url='"libmillsim_sample_plugin.so"'/>.
// They use only MillSim's public headers and the two plugin entry points: a
// scene node (Landmark) and a haptics renderer (SpherePenaltyRenderer), which
// follows the built-in renderers' pattern: fields compiled once into named
// Params, per-frame State a plain struct (a reset is a fresh one, a
// cross-fade's carry-over a copy).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <millsim/core/NodeKinds.h>
#include <millsim/core/NodeRegistry.h>
#include <millsim/core/Plugin.h>
#include <millsim/haptics/HapticScene.h>
#include <millsim/haptics/HapticsRenderer.h>

namespace sample {

// Marks a point of interest on the tooth (e.g. for a lesson's instructions).
class Landmark : public millsim::ChildNode {
public:
  static const millsim::NodeType& type() {
    static const millsim::NodeType t = millsim::makeNodeType<Landmark>(
        "Landmark", "children", "Sample plugin", "A named point of interest.");
    return t;
  }
  const millsim::NodeType& nodeType() const override { return type(); }

  millsim::SFString label{this, "label", millsim::Access::InputOutput, "", "Name shown to the student."};
  millsim::SFVec3f position{this, "position", millsim::Access::InputOutput, glm::vec3(0.f), "Where it is (m)."};
  millsim::SFFloat radius{this, "radius", millsim::Access::InputOutput, 0.001f, "Marker size (m).",
                          millsim::Range::positive()};
};

// A penalty on points spread over the burr's sphere: each point inside
// material pushes out along the surface normal by its depth (the field over
// its gradient's length, a first-order distance) times the stiffness, and the
// pushes are averaged. Force only, about the burr centre: a 3-DOF renderer,
// as simple as a renderer can be and still mill a tooth.
class SpherePenaltyAlgorithm final : public millsim::HapticAlgorithm {
public:
  struct Params {
    double stiffness = 500.0;  // N/m
    double radius = 0.0006;    // m: the burr's
    int points = 64;
    long nanFrom = -1;  // frame from which the force is NaN (the device tests' fault); -1: never
  };
  struct State {
    millsim::Pose lastDrawn;
    int contacts = 0;
    long frames = 0;
  };

  explicit SpherePenaltyAlgorithm(const Params& p) : p_(p) {
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < p.points; ++i) {
      const double y = 1.0 - 2.0 * (i + 0.5) / p.points;
      const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
      sphere_.push_back(p.radius * glm::dvec3(r * std::cos(golden * i), y, r * std::sin(golden * i)));
    }
  }
  std::string name() const override { return "SpherePenaltyRenderer"; }
  void reset(const millsim::Pose& device) override { s_ = State{device, 0, 0}; }
  void carryOver(const millsim::HapticAlgorithm& previous) override {
    if (const auto* p = dynamic_cast<const SpherePenaltyAlgorithm*>(&previous)) s_ = p->s_;
  }
  millsim::HapticOutput step(millsim::HapticScene& scene, const millsim::HapticInput& in) override {
    millsim::HapticOutput out;
    const glm::dvec3 c = in.device.position;
    scene.focus(c, p_.radius + 2.0 * scene.voxelSize());
    glm::dvec3 push(0.0);
    s_.contacts = 0;
    for (const glm::dvec3& offset : sphere_) {
      const glm::dvec3 q = c + offset;
      const double s = scene.field(q);
      if (!(s > 0.0)) continue;
      const glm::dvec3 g = scene.gradient(q);
      const double gl = glm::length(g);
      if (!(gl > 0.0)) continue;
      push += (s / gl) * (-g / gl);  // the gradient points into material
      ++s_.contacts;
    }
    out.force = p_.stiffness * push / double(sphere_.size());
    if (p_.nanFrom >= 0 && s_.frames++ >= p_.nanFrom) out.force.x = std::numeric_limits<double>::quiet_NaN();
    out.contacts = s_.contacts;
    out.drawnTool = in.device;
    out.burrCentre = c;
    out.burrCuts = true;
    s_.lastDrawn = in.device;
    return out;
  }

private:
  Params p_;
  std::vector<glm::dvec3> sphere_;
  State s_;
};

class SpherePenaltyRenderer : public millsim::HapticsRendererNode {
public:
  static const millsim::NodeType& type() {
    static const millsim::NodeType t = millsim::makeNodeType<SpherePenaltyRenderer>(
        "SpherePenaltyRenderer", "hapticsRenderer", "Sample plugin",
        "A plugin's renderer: a penalty force from points on the burr's sphere.");
    return t;
  }
  const millsim::NodeType& nodeType() const override { return type(); }

  millsim::SFFloat stiffness{this, "stiffness", millsim::Access::InputOutput, 500.f,
                             "Contact stiffness (N/m).", millsim::Range::closed(1, 1e5)};
  millsim::SFInt32 points{this, "points", millsim::Access::InitializeOnly, 64, "Points on the burr's sphere.",
                          millsim::Range::closed(4, 4096)};
  millsim::SFInt32 nanFromFrame{this, "nanFromFrame", millsim::Access::InitializeOnly, -1,
                                "A fault for the device tests: from this frame on the force is NaN, which the "
                                "safety layer must never send; -1: never.",
                                millsim::Range::closed(-1, 100000000)};

  std::unique_ptr<millsim::HapticAlgorithm> compile(const millsim::ToolGeometry& tool,
                                                    millsim::HapticScene&) const override {
    return std::make_unique<SpherePenaltyAlgorithm>(SpherePenaltyAlgorithm::Params{
        .stiffness = double(stiffness.get()), .radius = tool.tipRadius, .points = points.get(),
        .nanFrom = nanFromFrame.get()});
  }
  millsim::RendererTraits traits() const override {
    millsim::RendererTraits t;
    t.stiffnessField = "stiffness";
    t.reference = millsim::ReferenceKind::Penalty;
    t.compilesWithoutScene = true;
    return t;
  }
};

}  // namespace sample

extern "C" int millsim_plugin_abi_version() { return millsim::kPluginAbiVersion; }
extern "C" void millsim_register_nodes(millsim::NodeRegistry& registry) {
  registry.add(sample::Landmark::type());
  registry.add(sample::SpherePenaltyRenderer::type());
}
