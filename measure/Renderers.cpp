#include "measure/Renderers.h"

#include <stdexcept>

#include "measure/AnalyticScene.h"
#include "millsim/core/NodeRegistry.h"

namespace millsim::measure {

namespace {
const NodeRegistry& registry() {
  static const NodeRegistry r = builtinRegistry();
  return r;
}
}  // namespace

std::string RendererSpec::label() const {
  std::string s = type;
  for (const auto& [name, value] : fields) s += " " + name + "=" + value;
  return s;
}

std::vector<std::string> registeredRenderers() {
  std::vector<std::string> names;
  for (const NodeType* t : registry().all()) {
    auto probe = t->create();
    if (dynamic_cast<HapticsRendererNode*>(probe.get())) names.push_back(t->name);
  }
  return names;
}

bool isRegistered(const std::string& type) {
  for (const auto& n : registeredRenderers())
    if (n == type) return true;
  return false;
}

std::shared_ptr<HapticsRendererNode> makeRenderer(const RendererSpec& spec) {
  auto node = std::dynamic_pointer_cast<HapticsRendererNode>(
      registry().find(spec.type) ? registry().create(spec.type) : nullptr);
  if (!node) {
    std::string names;
    for (const auto& n : registeredRenderers()) names += (names.empty() ? "" : ", ") + n;
    throw std::runtime_error("unknown renderer type '" + spec.type + "' (registered: " + names + ")");
  }
  for (const auto& [name, value] : spec.fields) {
    Field* f = node->field(name);
    if (!f) throw std::runtime_error(spec.type + " has no field '" + name + "'");
    try {
      f->setFromString(value);
    } catch (const std::exception& e) {
      throw std::runtime_error(spec.type + "." + name + " = '" + value + "': " + e.what());
    }
  }
  return node;
}

RendererTraits rendererTraits(const std::string& type) { return makeRenderer({type, {}})->traits(); }

ToolGeometry standardTool() { return ToolGeometry{0.5e-3, 0.25e-3, 5e-3}; }

namespace {

// The flat surface (y = 0) the offset and stiffness probes press on.
std::unique_ptr<AnalyticScene> probeSurface(double h) {
  return voxelise(halfSpace({-3e-3, -2e-3, -3e-3}, {3e-3, 1e-3, 3e-3}), h);
}

double contactOffsetOn(const HapticsRendererNode& renderer, const ToolGeometry& tool, double h, AnalyticScene& surface) {
  VoxelScene& scene = *surface.scene;
  auto algorithm = renderer.compile(tool, scene);
  const double top = 2.0 * tool.tipRadius + 2.0 * h, step = 0.01 * h;
  algorithm->reset(Pose{{0.0, top, 0.0}, {1, 0, 0, 0}});
  for (double y = top; y > -tool.tipRadius; y -= step) {
    const HapticOutput out = algorithm->step(scene, HapticInput{Pose{{0.0, y, 0.0}, {1, 0, 0, 0}}, 1e-3});
    // Above a micronewton: a coupled renderer (#3) may report a round-off force in free space.
    if (glm::length(out.force) > 1e-6) return y;
  }
  return 0.0;
}

}  // namespace

double contactOffset(const HapticsRendererNode& renderer, const ToolGeometry& tool, double h) {
  return contactOffsetOn(renderer, tool, h, *probeSurface(h));
}

double renderedStiffness(const HapticsRendererNode& renderer, const ToolGeometry& tool, double h, double depth1,
                         double depth2) {
  auto s = probeSurface(h);
  const double yc = contactOffsetOn(renderer, tool, h, *s);
  auto algorithm = renderer.compile(tool, *s->scene);
  double y = yc + h;
  algorithm->reset(Pose{{0.0, y, 0.0}, {1, 0, 0, 0}});
  // Descend slowly to each depth and hold there until a coupled tool has settled.
  auto forceAt = [&](double depth) {
    HapticOutput out;
    for (; y > yc - depth; y -= 0.01 * h) out = algorithm->step(*s->scene, {Pose{{0.0, y, 0.0}, {1, 0, 0, 0}}, 1e-3});
    for (int i = 0; i < 500; ++i) out = algorithm->step(*s->scene, {Pose{{0.0, y, 0.0}, {1, 0, 0, 0}}, 1e-3});
    return out.force.y;
  };
  const double d1 = depth1 > 0.0 ? depth1 : 0.2 * h, d2 = depth2 > 0.0 ? depth2 : 0.6 * h;
  const double f1 = forceAt(d1), f2 = forceAt(d2);
  return (f2 - f1) / (d2 - d1);
}

}  // namespace millsim::measure
