#include "millsim/lesson/RegionAccounting.h"

#include <algorithm>
#include <bit>
#include <bitset>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include <glm/gtc/quaternion.hpp>
#include <nanoflann.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <openvdb/tools/FastSweeping.h>
#include <glm/common.hpp>
#include <glm/matrix.hpp>
#include <glm/vector_relational.hpp>

#include "millsim/core/Scene.h"
#include "millsim/lesson/ForbiddenRegion.h"
#include "millsim/lesson/MillingTarget.h"
#include "millsim/std/Box.h"
#include "millsim/std/Cylinder.h"
#include "millsim/std/Group.h"
#include "millsim/std/SceneWalk.h"
#include "millsim/std/Shape.h"
#include "millsim/std/Sphere.h"
#include "millsim/std/Transform.h"
#include "millsim/volume/PlacedVolumes.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

namespace {
// Blocks a volume's channel holds before the publisher keeps the rest pending
// (2048 blocks of 2 KiB: a second of heavy milling).
constexpr std::size_t kChannelBlocks = 2048;
// Removed volume, in voxels, below which a forbidden region counts as untouched:
// float rounding of φ, never a cut.
constexpr double kViolationVoxels = 1e-3;
}  // namespace

struct RegionAccounting::Shape {
  enum class Kind { Box, Sphere, Cylinder } kind;
  glm::dmat4 worldToShape;
  glm::dvec3 size;  // Box: full size; Sphere: radius in x; Cylinder: radius in x, height in y
  bool contains(const glm::dvec3& world) const {
    const glm::dvec3 p = glm::dvec3(worldToShape * glm::dvec4(world, 1.0));
    switch (kind) {
      case Kind::Box: return std::abs(p.x) <= 0.5 * size.x && std::abs(p.y) <= 0.5 * size.y && std::abs(p.z) <= 0.5 * size.z;
      case Kind::Sphere: return p.x * p.x + p.y * p.y + p.z * p.z <= size.x * size.x;
      case Kind::Cylinder: return std::abs(p.y) <= 0.5 * size.y && p.x * p.x + p.z * p.z <= size.x * size.x;
    }
    return false;
  }
};

struct RegionAccounting::Region {
  AssessmentRegion* node;
  std::vector<Shape> shapes;
  std::vector<std::vector<int>> labels;  // per volume: the TissueMap entries that are in the region
  bool contains(std::size_t volume, const glm::dvec3& world, int label) const {
    for (int l : labels[volume])
      if (l == label) return true;
    for (const Shape& s : shapes)
      if (s.contains(world)) return true;
    return false;
  }
};

struct RegionAccounting::Volume {
  const VoxelVolume* live;
  std::unique_ptr<VoxelVolume> start;  // the densities before milling (a copy, when counting a run)
  const VoxelVolume* origin;           // the densities before milling: the copy, or the live volume before any is
  glm::dmat4 localToWorld, worldToLocal;
  const TissueMap* tissues;
  double air, iso, phiScale, voxelVolume;
  BlockChannel channel{kChannelBlocks};
  // What is kept of a block once it has been counted. Its voxels' regions and
  // tissue do not change while milling, and a voxel once cut through stays
  // so (densities only fall), and the deepest cut and the thinnest wall only
  // grow or shrink with new ones. At 25 µm a block the burr creeps through is
  // counted again every tick: finding these again for each of its voxels was
  // 40 % of a §8.2 replay's CPU time.
  struct Block {
    std::vector<double> contribution;    // per slot (m³), its last count
    std::vector<std::uint64_t> regions;  // per voxel: bit r when region r holds it (empty past 64 regions)
    std::vector<std::uint16_t> slot;     // per voxel: its tissue's slot (tissueSlot)
    std::bitset<512> cut;                // voxels counted as cut through
  };
  std::unordered_map<std::uint64_t, Block> blocks;
  std::vector<std::size_t> tissueSlot;  // per TissueMap entry: its slot (RegionAccounting::tissueSlots_)
  std::unordered_map<std::uint64_t, float> depths;  // per voxel cut through: depthBelowSurface, kept
  // How far below the original surface voxel c lies, straight up (world +Y):
  // to the first point above it whose starting material is under half, or
  // the volume's edge. Where world +Y is the volume's +j (an upright volume),
  // to the face below the first such voxel, from each column's material runs
  // (tops); else in half-voxel steps.
  double depthBelowSurface(const openvdb::Coord& c);
  // Per column (i, k) cut through: the j of the top voxel of each run of
  // starting material (φ ≥ ½), rising. At 25 µm the half-voxel march from
  // every cut voxel was 13 % of a §8.2 replay.
  std::unordered_map<std::uint64_t, std::vector<int>> tops;
  const std::vector<int>& columnTops(int i, int k);
  double phi(double v) const { return std::clamp((v - air) * phiScale, 0.0, 1.0); }
  glm::dvec3 world(int i, int j, int k) const {
    return glm::dvec3(localToWorld * glm::dvec4(origin->indexToLocal(glm::dvec3(i, j, k)), 1.0));
  }
  int label(int i, int j, int k) const { return tissues ? tissues->labelAt(i, j, k) : 0; }
};

// A soft tissue's surface voxels (world), as nanoflann reads a point cloud.
struct SurfacePoints {
  std::vector<glm::dvec3> points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t axis) const { return points[i][int(axis)]; }
  template <class Box> bool kdtree_get_bbox(Box&) const { return false; }
};
using SurfaceTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SurfacePoints>, SurfacePoints, 3>;

// A forbidden region's soft voxels in one volume: those of its tissues that
// are soft (TissueMap::soft) whose original density is below the isoValue.
struct RegionAccounting::SoftTissue {
  std::size_t region, volume;
  openvdb::CoordBBox box;                  // index box holding them
  double edge;                             // the volume's smallest voxel edge in the world (m)
  openvdb::FloatGrid::Ptr fog;             // 1 on its soft voxels, 0 on those around them
  openvdb::FloatGrid::Ptr distance;        // in voxels, negative inside: how deep a voxel lies in the tissue
  std::unordered_set<std::uint64_t> swept;  // voxels the head has held
  // Its surface voxels (world) and a k-d tree of them: the nearest is the
  // wall left where the burr cuts. A hash of 3 mm cells searched point by
  // point took 46 % of a 25 µm §8.2 replay (a pulp of 160 000 surface voxels).
  SurfacePoints surface;
  std::unique_ptr<SurfaceTree> surfaceTree;
  glm::dvec3 surfaceLo{INFINITY}, surfaceHi{-INFINITY};  // their world box
  // The wall left between voxel `c` at `world` (cut through) and the tissue:
  // the distance to the nearest surface voxel's centre less half a voxel (the
  // surface lies half a voxel out); -1 beyond kWallReach. Kept per voxel: a
  // block is counted again each time it is milled.
  double wallAt(const openvdb::Coord& c, const glm::dvec3& world);
  std::unordered_map<std::uint64_t, float> walls;
};

namespace {
const openvdb::Coord kFaceNeighbours[] = {openvdb::Coord(1, 0, 0),  openvdb::Coord(-1, 0, 0), openvdb::Coord(0, 1, 0),
                                          openvdb::Coord(0, -1, 0), openvdb::Coord(0, 0, 1),  openvdb::Coord(0, 0, -1)};

std::uint64_t voxelKey(const openvdb::Coord& c) {
  return std::uint64_t(std::uint32_t(c.x()) & 0x1fffff) | (std::uint64_t(std::uint32_t(c.y()) & 0x1fffff) << 21) |
         (std::uint64_t(std::uint32_t(c.z()) & 0x1fffff) << 42);
}
}  // namespace

const std::vector<int>& RegionAccounting::Volume::columnTops(int i, int k) {
  const auto [known, added] = tops.try_emplace(voxelKey(openvdb::Coord(i, 0, k)));
  if (!added) return known->second;
  auto density = origin->grid().getConstAccessor();
  const int n = origin->dims().y;
  bool inside = false;
  for (int j = 0; j < n; ++j) {
    const bool material = !(phi(density.getValue(openvdb::Coord(i, j, k))) < 0.5);
    if (inside && !material) known->second.push_back(j - 1);
    inside = material;
  }
  if (inside) known->second.push_back(n - 1);
  return known->second;
}

double RegionAccounting::Volume::depthBelowSurface(const openvdb::Coord& c) {
  const glm::dvec3 h = origin->voxelSize();
  const glm::dvec3 up = glm::dvec3(worldToLocal * glm::dvec4(0.0, 1.0, 0.0, 0.0));  // local, scaled by the Transforms
  if (up.x == 0.0 && up.z == 0.0 && up.y > 0.0) {
    // The run c lies in (it held material at the start) ends at its top; the
    // surface is that voxel's upper face, (top − j + ½) voxels up; a local metre is 1/|up| world metres.
    const std::vector<int>& t = columnTops(c.x(), c.z());
    const auto top = std::lower_bound(t.begin(), t.end(), c.y());
    return top == t.end() ? 0.0 : (double(*top - c.y()) + 0.5) * h.y / up.y;
  }
  const auto [known, added] = depths.try_emplace(voxelKey(c), 0.f);
  if (!added) return known->second;
  const double step = 0.5 * std::min({h.x, h.y, h.z}) / std::max(glm::length(up), 1e-12);  // world m per step
  const glm::dvec3 from = origin->indexToLocal(glm::dvec3(c.x(), c.y(), c.z()));
  const glm::ivec3 dims = origin->dims();
  auto density = origin->grid().getConstAccessor();
  double depth = 0.0;
  for (int k = 1; k < 4096; ++k) {
    const glm::dvec3 index = origin->localToIndex(from + double(k) * step * up);
    const glm::ivec3 i(glm::round(index));
    depth = double(k) * step;
    if (glm::any(glm::lessThan(i, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(i, dims))) break;
    if (phi(density.getValue(openvdb::Coord(i.x, i.y, i.z))) < 0.5) break;
  }
  known->second = float(depth);
  return depth;
}

double RegionAccounting::SoftTissue::wallAt(const openvdb::Coord& c, const glm::dvec3& world) {
  // Most of a lesson's cutting is far from the pulp: one box test.
  if (glm::length(glm::max(glm::dvec3(0.0), glm::max(surfaceLo - world, world - surfaceHi))) > kWallReach + edge)
    return -1.0;  // also a tissue without surface points: its box is empty
  const auto [known, added] = walls.try_emplace(voxelKey(c), -1.f);
  if (!added) return known->second;
  std::uint32_t index = 0;
  double nearest2 = INFINITY;
  surfaceTree->knnSearch(&world.x, 1, &index, &nearest2);
  const double nearest = std::sqrt(nearest2);
  const double wall = std::max(0.0, nearest - 0.5 * edge);
  known->second = wall <= kWallReach ? float(wall) : -1.f;
  return known->second;
}

RegionAccounting::RegionAccounting(const Scene& scene, bool counting) {
  // A scene without regions costs nothing: no snapshot of its volumes.
  if (scene.nodesOfType<AssessmentRegion>().empty()) return;
  for (const PlacedVolume& p : placedVolumes(scene)) {
    auto v = std::make_unique<Volume>();
    const VoxelVolume& live = *p.node->volume();
    v->live = &live;
    if (counting) v->start = std::make_unique<VoxelVolume>(live.grid().deepCopy(), live.dims(), live.voxelSize(), live.airValue());
    v->origin = counting ? v->start.get() : &live;
    v->localToWorld = p.localToWorld;
    v->worldToLocal = glm::inverse(p.localToWorld);
    v->tissues = p.node->tissueMap();
    v->air = live.airValue();
    v->iso = double(p.node->isoValue.get());
    v->phiScale = 1.0 / (2.0 * (double(p.node->isoValue.get()) - v->air));
    const glm::dvec3 h = live.voxelSize();
    v->voxelVolume = h.x * h.y * h.z * std::abs(glm::determinant(glm::dmat3(p.localToWorld)));
    volumes_.push_back(std::move(v));
  }

  // Regions where they sit, with the shapes among their children.
  walkScene(scene, [&](Node& n, const WalkFrame& at) {
    auto* node = dynamic_cast<AssessmentRegion*>(&n);
    if (!node) return;
    auto r = std::make_unique<Region>();
    r->node = node;
    std::function<void(const Node&, const glm::dmat4&)> gather = [&](const Node& c, const glm::dmat4& m) {
      if (const auto* t = dynamic_cast<const TransformingNode*>(&c)) {
        const glm::dmat4 inner = m * glm::dmat4(t->localMatrix());
        for (const auto& k : t->children.get()) gather(*k, inner);
      } else if (const auto* g = dynamic_cast<const GroupingNode*>(&c)) {
        for (const auto& k : g->children.get()) gather(*k, m);
      } else if (const auto* s = dynamic_cast<const millsim::Shape*>(&c)) {
        const Node* geometry = s->geometry.get().get();
        const glm::dmat4 inverse = glm::inverse(m);
        if (const auto* b = dynamic_cast<const Box*>(geometry))
          r->shapes.push_back({Shape::Kind::Box, inverse, glm::dvec3(b->size.get())});
        else if (const auto* sp = dynamic_cast<const Sphere*>(geometry))
          r->shapes.push_back({Shape::Kind::Sphere, inverse, glm::dvec3(sp->radius.get(), 0, 0)});
        else if (const auto* cy = dynamic_cast<const Cylinder*>(geometry))
          r->shapes.push_back({Shape::Kind::Cylinder, inverse, glm::dvec3(cy->radius.get(), cy->height.get(), 0)});
      }
    };
    for (const auto& c : node->children.get()) gather(*c, at.localToWorld);
    r->labels.resize(volumes_.size());
    for (const std::string& name : node->tissues.get()) {
      bool found = false;
      for (std::size_t i = 0; i < volumes_.size(); ++i)
        if (const int l = volumes_[i]->tissues ? volumes_[i]->tissues->find(name) : 0; l > 0) {
          r->labels[i].push_back(l);
          found = true;
        }
      if (!found)
        throw std::runtime_error(node->location().str() + ": " + node->typeName() + " '" + node->name.get() +
                                 "' names tissue '" + name + "', which no VolumeObject's tissues has");
    }
    regions_.push_back(std::move(r));
  });

  // The material each region holds at the start.
  results_.resize(regions_.size());
  for (std::size_t r = 0; r < regions_.size(); ++r) {
    results_[r].name = regions_[r]->node->name.get();
    results_[r].forbidden = dynamic_cast<ForbiddenRegion*>(regions_[r]->node) != nullptr;
  }
  if (regions_.empty()) return;
  if (counting) findSoftTissues();

  // Removal outside the targets and per tissue: slots after the regions'.
  summary_.overPreparationPenalty = 0.0;
  for (const auto& r : regions_)
    if (const auto* target = dynamic_cast<const MillingTarget*>(r->node)) {
      summary_.hasTargets = true;
      summary_.overPreparationPenalty = std::max(summary_.overPreparationPenalty, double(target->overPreparationPenalty.get()));
    }
  if (!summary_.hasTargets) summary_.overPreparationPenalty = 1.0;
  outsideSlot_ = regions_.size();
  for (auto& v : volumes_) {
    const std::size_t entries = v->tissues ? v->tissues->entries().size() : 1;
    for (std::size_t e = 0; e < entries; ++e) {
      const std::string name = e == 0 || !v->tissues ? std::string("no tissue") : v->tissues->entries()[e].name;
      auto it = std::find_if(summary_.byTissue.begin(), summary_.byTissue.end(),
                             [&](const auto& t) { return t.first == name; });
      if (it == summary_.byTissue.end()) it = summary_.byTissue.insert(it, {name, 0.0});
      v->tissueSlot.push_back(outsideSlot_ + 1 + std::size_t(it - summary_.byTissue.begin()));
    }
  }
  tissueSlots_ = summary_.byTissue.size();

  for (std::size_t vi = 0; vi < volumes_.size(); ++vi) measureAtStart(vi);
}

// The material each region holds at the start: a pass over every material
// voxel, leaf by leaf on TBB's threads (50 M voxels at 25 µm: 1.9 s on one
// core through a root-down label lookup a voxel), each leaf's sums kept
// apart and added in leaf order, so the totals do not depend on the split.
void RegionAccounting::measureAtStart(std::size_t vi) {
  const Volume& v = *volumes_[vi];
  using Labels = TissueMap::LabelGrid::ConstAccessor;
  struct Sums {
    std::vector<double> initial, initialForbidden;
    double targets = 0.0;
  };
  auto measure = [&](const openvdb::Coord& c, float value, Labels* labels, Sums& sums) {
    const double phi0 = v.phi(value);
    if (phi0 <= 0.0) return;
    const glm::dvec3 w = v.world(c.x(), c.y(), c.z());
    const int label = labels ? labels->getValue(c) : 0;
    bool forbidden = false, target = false;
    for (std::size_t r = 0; r < regions_.size(); ++r) {
      const bool in = regions_[r]->contains(vi, w, label);
      forbidden |= in && results_[r].forbidden;
      target |= in && !results_[r].forbidden;
    }
    if (!forbidden && !target) return;
    for (std::size_t r = 0; r < regions_.size(); ++r)
      if (regions_[r]->contains(vi, w, label)) {
        sums.initial[r] += phi0 * v.voxelVolume;
        if (forbidden && !results_[r].forbidden) sums.initialForbidden[r] += phi0 * v.voxelVolume;
      }
    if (target) sums.targets += phi0 * v.voxelVolume;
  };
  const Sums empty{std::vector<double>(regions_.size(), 0.0), std::vector<double>(regions_.size(), 0.0), 0.0};
  using Leaf = VoxelVolume::Grid::TreeType::LeafNodeType;
  std::vector<const Leaf*> leaves;
  leaves.reserve(v.origin->grid().tree().leafCount());
  v.origin->grid().tree().getNodes(leaves);
  std::vector<Sums> perLeaf(leaves.size() + 1, empty);  // the last: the active tiles
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size()), [&](const tbb::blocked_range<std::size_t>& range) {
    std::unique_ptr<Labels> labels = v.tissues ? std::make_unique<Labels>(v.tissues->labels().getConstAccessor()) : nullptr;
    for (std::size_t i = range.begin(); i != range.end(); ++i)
      for (auto it = leaves[i]->cbeginValueOn(); it; ++it) measure(it.getCoord(), *it, labels.get(), perLeaf[i]);
  });
  // Active tiles (a VDB file may hold them; the readers and the phantom make leaves), voxel by voxel.
  std::unique_ptr<Labels> labels = v.tissues ? std::make_unique<Labels>(v.tissues->labels().getConstAccessor()) : nullptr;
  auto tiles = v.origin->grid().tree().cbeginValueOn();
  tiles.setMaxDepth(VoxelVolume::Grid::TreeType::ValueOnCIter::LEAF_DEPTH - 1);
  for (; tiles; ++tiles) {
    const openvdb::CoordBBox box = tiles.getBoundingBox();
    for (auto c = box.begin(); c; ++c) measure(*c, *tiles, labels.get(), perLeaf.back());
  }
  for (const Sums& sums : perLeaf) {
    for (std::size_t r = 0; r < regions_.size(); ++r)
      results_[r].initial += sums.initial[r], results_[r].initialForbidden += sums.initialForbidden[r];
    summary_.targetsInitial += sums.targets;
  }
}

RegionAccounting::~RegionAccounting() = default;

std::vector<RegionResult> RegionAccounting::atStart(const Scene& scene) {
  return RegionAccounting(scene, false).results();
}

void RegionAccounting::findSoftTissues() {
  for (std::size_t r = 0; r < regions_.size(); ++r) {
    if (!results_[r].forbidden) continue;
    for (std::size_t vi = 0; vi < volumes_.size(); ++vi) {
      const Volume& v = *volumes_[vi];
      std::vector<int> soft;
      for (int l : regions_[r]->labels[vi])
        if (v.tissues->soft(l)) soft.push_back(l);
      if (soft.empty()) continue;
      auto s = std::make_unique<SoftTissue>();
      s->region = r;
      s->volume = vi;
      // Its soft voxels as a fog (1 inside, 0 on the voxels around them), made
      // a signed distance by OpenVDB's fast sweeping: the depth of each below
      // the tissue's surface, to report how deep the burr went.
      s->fog = openvdb::FloatGrid::create(0.f);
      auto fogAccess = s->fog->getAccessor();
      auto density = v.origin->grid().getConstAccessor();
      for (auto it = v.tissues->labels().cbeginValueOn(); it; ++it) {
        if (std::find(soft.begin(), soft.end(), *it) == soft.end()) continue;
        const openvdb::CoordBBox voxels = it.getBoundingBox();
        for (auto c = voxels.begin(); c; ++c) {
          if (!(density.getValue(*c) < v.iso)) continue;
          s->box.expand(*c);
          fogAccess.setValue(*c, 1.f);
          for (const openvdb::Coord& d : kFaceNeighbours)
            if (!fogAccess.isValueOn(*c + d)) fogAccess.setValueOn(*c + d, 0.f);
        }
      }
      if (s->box.empty()) continue;
      const glm::dvec3 h = v.live->voxelSize();
      s->edge = std::cbrt(std::abs(glm::determinant(glm::dmat3(v.localToWorld)))) * std::min({h.x, h.y, h.z});
      s->distance = openvdb::tools::fogToSdf(*s->fog, 0.5f);
      // Its surface voxels in the world, in a k-d tree: where the burr cuts,
      // the nearest is the wall left (count()). A distance field reaching
      // kWallReach out cost a second at the start of every run (OpenVDB's
      // fast sweeping over the widened band, full-size phantom).
      for (auto it = s->fog->cbeginValueOn(); it; ++it) {
        if (*it != 1.f) continue;
        const openvdb::Coord c = it.getCoord();
        bool surface = false;
        for (const openvdb::Coord& d : kFaceNeighbours)
          surface |= fogAccess.getValue(c + d) != 1.f;
        if (!surface) continue;
        const glm::dvec3 w = v.world(c.x(), c.y(), c.z());
        s->surface.points.push_back(w);
        s->surfaceLo = glm::min(s->surfaceLo, w), s->surfaceHi = glm::max(s->surfaceHi, w);
      }
      s->surfaceTree = std::make_unique<SurfaceTree>(3, s->surface, nanoflann::KDTreeSingleIndexAdaptorParams(16));
      soft_.push_back(std::move(s));
    }
  }
}

void RegionAccounting::stampViolation(std::size_t r, double t) {
  double& first = results_[r].firstViolation;
  if (first < 0.0 || t < first) first = t;
}

void RegionAccounting::burrAt(const Pose& pose, const BurrHead& head, double t) {
  if (soft_.empty()) return;
  // Frames a few micrometres apart read the same voxels: look again once the
  // burr moved a quarter of the finest voxel or turned by a degree.
  if (posed_ && head.shape == lastHead_.shape && head.radius == lastHead_.radius && head.length == lastHead_.length &&
      head.endRadius == lastHead_.endRadius &&
      glm::length(pose.position - lastPose_.position) < 0.25 * soft_.front()->edge &&
      std::abs(glm::dot(pose.orientation, lastPose_.orientation)) > std::cos(0.5 * 0.01745))
    return;
  posed_ = true;
  lastPose_ = pose;
  lastHead_ = head;
  const glm::dquat toHead = glm::inverse(pose.orientation);
  const double reach = head.boundingRadius();
  for (const auto& sp : soft_) {
    SoftTissue& s = *sp;
    const Volume& v = *volumes_[s.volume];
    // The head's bounding sphere as an index box (corners of its world box).
    openvdb::CoordBBox box;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner = pose.position + reach * glm::dvec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
      const glm::dvec3 index = v.origin->localToIndex(glm::dvec3(v.worldToLocal * glm::dvec4(corner, 1.0)));
      box.expand(openvdb::Coord(int(std::floor(index.x)), int(std::floor(index.y)), int(std::floor(index.z))));
      box.expand(openvdb::Coord(int(std::ceil(index.x)), int(std::ceil(index.y)), int(std::ceil(index.z))));
    }
    box.intersect(s.box);
    if (box.empty()) continue;
    auto fog = s.fog->getConstAccessor();
    auto distance = s.distance->getConstAccessor();
    RegionResult& result = results_[s.region];
    bool entered = false;
    for (auto it = box.begin(); it; ++it) {
      const openvdb::Coord c = *it;
      if (fog.getValue(c) != 1.f) continue;  // not one of the region's soft voxels
      const glm::dvec3 q = toHead * (v.world(c.x(), c.y(), c.z()) - pose.position);
      const double d = head.shape == BurrShape::Round ? glm::length(q) - head.radius
                                                      : headProfileDistance(head, std::hypot(q.x, q.z), q.y);
      if (d > 0.0) continue;
      entered = true;
      result.depth = std::max(result.depth, -double(distance.getValue(c)) * s.edge);
      if (s.swept.insert(voxelKey(c)).second) result.swept += v.voxelVolume;
    }
    if (entered && result.firstEntry < 0.0) {
      result.firstEntry = t;
      result.thinnestWall = 0.0;  // none left
      stampViolation(s.region, t);
    }
  }
}

BlockChannel& RegionAccounting::channel(std::size_t volume) { return volumes_.at(volume)->channel; }

void RegionAccounting::update(double t) {
  for (std::size_t i = 0; i < volumes_.size(); ++i)
    volumes_[i]->channel.drain([&](const BlockUpdate& b) { count(i, b, t); });
}

void RegionAccounting::count(std::size_t vi, const BlockUpdate& block, double t) {
  Volume& v = *volumes_[vi];
  const openvdb::Coord origin(block.origin.x, block.origin.y, block.origin.z);
  const auto* startLeaf = v.origin->grid().tree().probeConstLeaf(origin);
  const std::uint64_t key = (std::uint64_t(std::uint32_t(block.origin.x) >> 3)) |
                            (std::uint64_t(std::uint32_t(block.origin.y) >> 3) << 21) |
                            (std::uint64_t(std::uint32_t(block.origin.z) >> 3) << 42);
  Volume::Block& kept = v.blocks[key];
  const bool masks = regions_.size() <= 64;
  if (startLeaf && kept.slot.empty()) {
    // The first count of this block: each voxel's regions and tissue slot.
    kept.slot.resize(512);
    if (masks) kept.regions.assign(512, 0);
    for (int i = 0; i < 512; ++i) {
      const openvdb::Coord c = origin + openvdb::Coord(i & 7, (i >> 3) & 7, i >> 6);
      const int label = v.label(c.x(), c.y(), c.z());
      kept.slot[std::size_t(i)] = std::uint16_t(v.tissueSlot[std::min(std::size_t(std::max(label, 0)), v.tissueSlot.size() - 1)]);
      if (!masks) continue;
      const glm::dvec3 w = v.world(c.x(), c.y(), c.z());
      for (std::size_t r = 0; r < regions_.size(); ++r)
        if (regions_[r]->contains(vi, w, label)) kept.regions[std::size_t(i)] |= std::uint64_t(1) << r;
    }
  }
  std::vector<double> now(outsideSlot_ + 1 + tissueSlots_, 0.0);
  if (startLeaf) {  // a block that started as air has nothing to lose
    for (int z = 0; z < 8; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
          const std::size_t i = std::size_t((z * 8 + y) * 8 + x);
          const openvdb::Coord c = origin + openvdb::Coord(x, y, z);
          const double lost = v.phi(startLeaf->getValue(c)) - v.phi(block.values[i]);
          if (lost <= 0.0) continue;
          bool inTarget = false;
          if (masks) {
            for (std::uint64_t held = kept.regions[i]; held != 0; held &= held - 1) {
              const std::size_t r = std::size_t(std::countr_zero(held));
              now[r] += lost * v.voxelVolume;
              inTarget |= !results_[r].forbidden;
            }
          } else {
            const glm::dvec3 w = v.world(c.x(), c.y(), c.z());
            const int label = v.label(c.x(), c.y(), c.z());
            for (std::size_t r = 0; r < regions_.size(); ++r)
              if (regions_[r]->contains(vi, w, label)) {
                now[r] += lost * v.voxelVolume;
                inTarget |= !results_[r].forbidden;
              }
          }
          if (!inTarget) now[outsideSlot_] += lost * v.voxelVolume;
          // A voxel cut through (to the surface, φ ≤ ½): how deep the cut is, and the wall it leaves
          // over a forbidden soft tissue near it; once, when it is first counted so.
          // (Not a voxel the surface only grazed: it held more than half material at the start.)
          const bool cutThrough = v.phi(block.values[i]) <= 0.5 && v.phi(startLeaf->getValue(c)) > 0.5;
          if (cutThrough && !kept.cut[i]) {
            kept.cut[i] = true;
            summary_.deepestCut = std::max(summary_.deepestCut, v.depthBelowSurface(c));
            const glm::dvec3 w = v.world(c.x(), c.y(), c.z());
            for (const auto& sp : soft_)
              if (sp->volume == vi && results_[sp->region].thinnestWall != 0.0)  // 0: entered, nothing thinner
                if (const double left = sp->wallAt(c, w); left >= 0.0) {
                  double& wall = results_[sp->region].thinnestWall;
                  if (wall < 0.0 || left < wall) wall = left;
                }
          }
          now[kept.slot[i]] += lost * v.voxelVolume;
        }
  }
  std::vector<double>& before = kept.contribution;
  before.resize(now.size(), 0.0);
  for (std::size_t r = 0; r < regions_.size(); ++r) {
    results_[r].removed += now[r] - before[r];
    if (results_[r].forbidden && results_[r].removed > kViolationVoxels * v.voxelVolume) stampViolation(r, t);
  }
  summary_.outsideTargets += now[outsideSlot_] - before[outsideSlot_];
  for (std::size_t i = 0; i < tissueSlots_; ++i) summary_.byTissue[i].second += now[outsideSlot_ + 1 + i] - before[outsideSlot_ + 1 + i];
  before = std::move(now);
  stampCompletion(t);
}

// A target that held nothing at the start (check warns of it) cannot be done
// and does not hold the others back.
void RegionAccounting::stampCompletion(double t) {
  if (!summary_.hasTargets || summary_.completed >= 0.0) return;
  bool any = false;
  for (std::size_t r = 0; r < regions_.size(); ++r) {
    const auto* target = dynamic_cast<const MillingTarget*>(regions_[r]->node);
    if (!target || !(results_[r].initial > 0.0)) continue;
    if (!(results_[r].fraction() >= double(target->completeAt.get()))) return;
    any = true;
  }
  if (any) summary_.completed = t;
}

void RegionAccounting::publishFields() {
  for (std::size_t r = 0; r < regions_.size(); ++r) {
    AssessmentRegion& node = *regions_[r]->node;
    const RegionResult& res = results_[r];
    if (node.removedVolume.get() != float(res.removed)) node.removedVolume.set(float(res.removed));
    if (auto* target = dynamic_cast<MillingTarget*>(&node); target && target->fraction.get() != float(res.fraction()))
      target->fraction.set(float(res.fraction()));
    auto* forbidden = dynamic_cast<ForbiddenRegion*>(&node);
    if (!forbidden) continue;
    if (res.firstViolation >= 0.0 && forbidden->firstViolationTime.get().seconds != res.firstViolation)
      forbidden->firstViolationTime.set(Time{res.firstViolation});
    if (res.firstViolation >= 0.0 && !forbidden->violated.get()) forbidden->violated.set(true);
    if (forbidden->depth.get() != float(res.depth)) forbidden->depth.set(float(res.depth));
    if (forbidden->sweptVolume.get() != float(res.swept)) forbidden->sweptVolume.set(float(res.swept));
  }
}

}  // namespace millsim
