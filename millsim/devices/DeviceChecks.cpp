#include "millsim/devices/DeviceChecks.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "millsim/core/Scene.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/Trajectory.h"
#include "millsim/devices/TrajectoryUnits.h"
#include "millsim/std/Transform.h"
#include "millsim/volume/PlacedVolumes.h"
#include "millsim/volume/PointShell.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim {

namespace {

struct FoundDevice {
  HapticsDevice* device;
  const TransformingNode* transform;  // the innermost Transform around it, or null
};

std::string describe(const Node& n) {
  return n.typeName() + (n.defName().empty() ? std::string() : " '" + n.defName() + "'") + " at " +
         n.location().str();
}

void findDevices(Node& n, const TransformingNode* around, std::vector<FoundDevice>& out) {
  if (auto* d = dynamic_cast<HapticsDevice*>(&n)) {
    const bool seen = std::any_of(out.begin(), out.end(), [&](const FoundDevice& f) { return f.device == d; });
    if (!seen) out.push_back({d, around});
    else if (around)
      for (auto& f : out)
        if (f.device == d && !f.transform) f.transform = around;  // a USE of it inside a Transform
    return;  // a device's own node fields hold its tool and renderer, never another device
  }
  if (auto* t = dynamic_cast<const TransformingNode*>(&n)) around = t;
  for (Field* f : n.fields())
    if (auto* nf = dynamic_cast<NodeFieldBase*>(f))
      for (const auto& child : nf->nodes()) findDevices(*child, around, out);
}

std::string mm(double metres) { return formatNumber(std::round(metres * 1e4) / 10.0); }

struct WorldBox {
  glm::dvec3 lo, hi;
  const VolumeObject* node;
};

// Each loaded volume's box in the world (centred on its local origin, as X3D's VolumeData).
std::vector<WorldBox> volumeBoxes(const std::vector<PlacedVolume>& volumes) {
  std::vector<WorldBox> boxes;
  for (const PlacedVolume& v : volumes) {
    const glm::dvec3 half = v.node->size() * 0.5;
    WorldBox b{glm::dvec3(INFINITY), glm::dvec3(-INFINITY), v.node};
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 local((c & 1) ? half.x : -half.x, (c & 2) ? half.y : -half.y, (c & 4) ? half.z : -half.z);
      const glm::dvec3 w(v.localToWorld * glm::dvec4(local, 1.0));
      b.lo = glm::min(b.lo, w), b.hi = glm::max(b.hi, w);
    }
    boxes.push_back(b);
  }
  return boxes;
}

// The least distance from any of the trajectory's positions, times `scale`
// and then placed by the device's calibration, to any box.
double nearest(const Trajectory& trajectory, const HapticsDevice* device, const std::vector<WorldBox>& boxes,
               double scale, const VolumeObject** which) {
  double best = INFINITY;
  for (const TrajectorySample& s : trajectory.samples())
    for (const WorldBox& b : boxes) {
      const Pose raw{s.pose.position * scale, s.pose.orientation};
      const glm::dvec3 p = device ? device->calibrate(raw).position : raw.position;
      const double d = glm::length(glm::max(glm::dvec3(0.0), glm::max(b.lo - p, p - b.hi)));
      if (d < best) best = d, *which = b.node;
    }
  return best;
}

// A frame that cuts also stamps the burr into the volume (VoxelScene::mill,
// on the haptic thread). A stamp reads about 15 (r/h)² densities, every voxel
// of its surface's ramp (milling_bench BM_Stamp's read_p50: 600, 2 150 and
// 8 100 for a 0.6 mm burr at 100, 50 and 25 µm voxels), at about 15 ns each
// on the development machine (10, 33 and 120 µs); a VolumeObject's
// millingBudget caps what one frame reads (docs/algorithms.md, "Milling at
// fine voxels"), a row more at most. The costliest millable volume's stamp.
struct StampCost {
  double seconds = 0.0;
  double densities = 0.0;
  const VolumeObject* volume = nullptr;
};
constexpr double kStampReadsPerRadiusSquared = 15.0, kNanosecondsPerStampRead = 15.0;

StampCost stampCost(const std::vector<PlacedVolume>& volumes, const ToolGeometry& tool) {
  StampCost worst;
  const double r = tool.head().boundingRadius();
  for (const PlacedVolume& v : volumes) {
    const double h = v.node->voxelEdge();
    if (!v.node->millable.get() || !(h > 0.0) || !(r > 0.0)) continue;
    double reads = kStampReadsPerRadiusSquared * (r / h) * (r / h);
    if (const int budget = v.node->millingBudget.get(); budget > 0) reads = std::min(reads, double(budget) + 2.0 * r / h);
    const double seconds = reads * kNanosecondsPerStampRead * 1e-9;
    if (seconds > worst.seconds) worst = {seconds, reads, v.node};
  }
  return worst;
}

const HapticsDevice* firstDevice(const Scene& scene) {
  std::vector<FoundDevice> devices;
  findDevices(*scene.root, nullptr, devices);
  return devices.empty() ? nullptr : devices.front().device;
}

}  // namespace

void checkDevices(const Scene& scene, DiagnosticSink& sink) {
  std::vector<FoundDevice> devices;
  findDevices(*scene.root, nullptr, devices);
  if (devices.empty()) return;

  // One device per scene: the run drives one haptic thread and one device.
  if (devices.size() > 1) {
    std::string others;
    for (std::size_t i = 1; i < devices.size(); ++i) others += (i > 1 ? ", " : "") + describe(*devices[i].device);
    sink.error(devices[1].device->location(),
               "the scene has " + std::to_string(devices.size()) + " devices (" + describe(*devices[0].device) +
                   ", then " + others + "); MillSim runs one device per scene: keep one, or put each in its own scene");
  }
  for (const FoundDevice& f : devices)
    if (f.transform)
      sink.error(f.device->location(),
                 f.device->typeName() + " is inside the " + describe(*f.transform) +
                     "; a device is not placed by Transforms (its poses are world coordinates): move it out of the "
                     "Transform and use positionCalibration/orientationCalibration to offset it");

  // The burr against every volume: a burr larger than the volume is almost
  // always a unit mistake (tipRadius is in metres; file spacings in millimetres).
  // Else, a burr feels nothing smaller than a voxel: where a voxel edge is
  // longer than its radius it feels the voxels' steps (and #3's point shell,
  // a point a voxel, can let it slip between points): a clinical CT read at
  // its own spacing, or a coarse scan (docs/lessons.md, "A real CT").
  const HapticsDevice& device = *devices[0].device;
  MillTool defaultTool;
  const MillTool& tool = device.tool.get() ? *device.tool.get() : defaultTool;
  const double burr = 2.0 * tool.tipRadius.get();
  const Node& burrNode = device.tool.get() ? static_cast<const Node&>(tool) : device;
  const std::string whichBurr = device.tool.get() ? "" : "the default MillTool's ";
  const std::vector<PlacedVolume> volumes = placedVolumes(scene);
  for (const PlacedVolume& v : volumes) {
    glm::dvec3 world, voxel;
    for (int a = 0; a < 3; ++a) {
      const double scale = glm::length(glm::dvec3(v.localToWorld[a]));
      world[a] = v.node->size()[a] * scale, voxel[a] = v.node->voxelEdges()[a] * scale;
    }
    const double longestEdge = std::max({voxel.x, voxel.y, voxel.z});
    if (burr > std::min({world.x, world.y, world.z}))
      sink.warning(burrNode.location(),
                   "the burr (" + whichBurr + "tipRadius " + formatNumber(tool.tipRadius.get()) + " m, " + mm(burr) +
                       " mm across) is larger than the " + describe(*v.node) + " (" + mm(world.x) + " x " +
                       mm(world.y) + " x " + mm(world.z) +
                       " mm); check tipRadius (metres) and the volume's voxel size (millimetres in files)");
    else if (longestEdge > tool.tipRadius.get())
      sink.warning(burrNode.location(),
                   "the voxels of the " + describe(*v.node) + " are " + mm(longestEdge) +
                       " mm along their longest edge, longer than the burr's radius (" + whichBurr + "tipRadius " +
                       mm(tool.tipRadius.get()) + " mm): the burr will feel the voxels' steps, not the shape; give "
                       "the VolumeObject a smaller voxelSize (docs/lessons.md, \"A real CT\") or use a finer scan");
  }

  if (const auto trajectory = device.trajectory()) {
    const std::string warning = trajectoryReachWarning(scene, *trajectory, "its trajectory");
    if (!warning.empty()) sink.warning(device.location(), device.typeName() + ": " + warning);
  }

  // The renderer's estimated frame cost against the device's frame budget.
  const HapticsRendererNode* renderer = device.hapticsRenderer.get().get();
  if (!renderer) return;
  // A burr the renderer cannot carry: `millsim run` would refuse it.
  if (const std::string why = renderer->cannotCarry(tool.geometry()); !why.empty())
    sink.error(renderer->location(), why + " (the burr: " + describe(burrNode) + ")");
  FrameCostContext context;
  context.tool = tool.geometry();
  for (const PlacedVolume& v : volumes) {
    const double edge = v.node->voxelEdge();
    if (edge > 0.0 && (context.voxelSize == 0.0 || edge < context.voxelSize)) context.voxelSize = edge;
  }
  context.shellPoints = [&volumes](int scale) {
    std::size_t n = 0;
    for (const PlacedVolume& v : volumes) n += v.node->pointShell(scale).size();
    return n;
  };
  const FrameCostEstimate cost = renderer->estimateFrameCost(context);
  const StampCost stamp = stampCost(volumes, tool.geometry());
  const double budget = 1.0 / double(device.desiredHapticsRate.get());
  auto us = [](double seconds) { return formatNumber(std::round(seconds * 1e7) / 10.0) + " us"; };
  if (cost.seconds + stamp.seconds > budget) {
    // Which part to lower: the renderer's, the milling stamp's, or both.
    std::string model = cost.seconds > 0.0 ? cost.model : "", advice;
    if (stamp.seconds > 0.0)
      model += std::string(model.empty() ? "" : "; ") + "a milling frame adds a stamp of the burr into the " +
               describe(*stamp.volume) + ", about " + formatNumber(std::round(stamp.densities)) + " densities x " +
               formatNumber(kNanosecondsPerStampRead) + " ns";
    if (cost.seconds > 0.5 * budget) advice = cost.advice;
    if (stamp.seconds > 0.5 * budget)
      advice += std::string(advice.empty() ? "" : "; ") +
                "a stamp reads about " + formatNumber(kStampReadsPerRadiusSquared) +
                " (r/h)^2 densities: give the VolumeObject a larger voxelSize, use a smaller "
                "burr, or set its millingBudget (docs/algorithms.md, \"Milling at fine voxels\")";
    if (advice.empty()) advice = cost.advice;
    sink.warning(renderer->location(),
                 renderer->typeName() + " cannot keep up with " + device.typeName() + "'s desiredHapticsRate " +
                     std::to_string(device.desiredHapticsRate.get()) + " Hz: its estimated frame cost is " +
                     us(cost.seconds + stamp.seconds) + " (" + model + "), over the frame budget of " + us(budget) +
                     "; " + advice + ", or lower desiredHapticsRate");
  }
}

std::string trajectoryReachWarning(const Scene& scene, const Trajectory& trajectory, const std::string& label) {
  const std::vector<WorldBox> boxes = volumeBoxes(placedVolumes(scene));
  if (boxes.empty() || trajectory.samples().empty()) return {};
  const HapticsDevice* device = firstDevice(scene);
  const MillTool defaultTool;
  const MillTool& tool = device && device->tool.get() ? *device->tool.get() : defaultTool;
  const double reach = double(tool.tipRadius.get()) + double(tool.shaftLength.get());
  const VolumeObject* which = nullptr;
  const double distance = nearest(trajectory, device, boxes, 1.0, &which);
  if (distance <= reach) return {};
  std::string sentence = label + " never comes within the tool's reach (" + mm(reach) + " mm) of a volume: its " +
                         "nearest position is " + mm(distance) + " mm from the " + describe(*which) +
                         "; positions are read in metres";
  for (const TrajectoryLengthUnit& u : kTrajectoryLengthUnits) {
    const VolumeObject* near = nullptr;
    if (u.metres == 1.0 || nearest(trajectory, device, boxes, u.metres, &near) > reach) continue;
    const std::string name(u.name);
    return sentence + ". Read in " + name + " it would reach the " + describe(*near) + ": if the file is in " + name +
           ", say so in its header (t,x_" + name + ",y_" + name + ",z_" + name + ",qw,qx,qy,qz,button)";
  }
  return sentence + "; check its positions against the volume's place (a Transform above the VolumeObject moves it)";
}

}  // namespace millsim
