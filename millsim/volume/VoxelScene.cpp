#include "millsim/volume/VoxelScene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "millsim/volume/PlacedVolumes.h"
#include "millsim/volume/PointShell.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim {

namespace {

constexpr int kWindowEdge = 24;  // voxels a side of the haptic sampler's window (addVolume)

}  // namespace

VoxelScene::VoxelScene() = default;
VoxelScene::~VoxelScene() = default;

VoxelScene::VoxelScene(const Scene& scene) {
  for (const PlacedVolume& p : placedVolumes(scene))
    addVolume(*p.node->volume(), p.localToWorld, double(p.node->isoValue.get()), p.node);
}

void VoxelScene::addVolume(VoxelVolume& vox, const glm::dmat4& m, double iso, VolumeObject* node,
                           const TissueMap* tissues) {
  if (node && !tissues) tissues = node->tissueMap();
  // index = (local / voxelSize) + halfExtent, local = worldToLocal · world.
  const glm::dmat4 worldToLocal = glm::inverse(m);
  const glm::dvec3 inv = 1.0 / vox.voxelSize();
  const glm::dmat3 lin =
      glm::dmat3(glm::dvec3(inv.x, 0, 0), glm::dvec3(0, inv.y, 0), glm::dvec3(0, 0, inv.z)) * glm::dmat3(worldToLocal);
  const glm::dvec3 offset = glm::dvec3(worldToLocal[3]) * inv + vox.localToIndex(glm::dvec3(0.0));
  const double scale = std::cbrt(std::abs(glm::determinant(glm::dmat3(m))));
  const bool millable = node ? node->millable.get() : true;
  // The largest stretch of lin: the square root of linᵀ·lin's largest
  // eigenvalue, by power iteration (a radius in metres is at most this many voxels).
  const glm::dmat3 ltl = glm::transpose(lin) * lin;
  glm::dvec3 e(1.0, 0.7, 0.4);
  double stretch2 = 0.0;
  for (int i = 0; i < 50 && glm::length(e) > 0.0; ++i) {
    const glm::dvec3 next = ltl * glm::normalize(e);
    stretch2 = glm::length(next);
    e = next;
  }
  const double indexPerWorld = 1.001 * std::sqrt(stretch2);
  volumes_.push_back(std::unique_ptr<Volume>(new Volume{node, millable, &vox, Placement{m, worldToLocal, iso, scale},
                                                        lin, offset, indexPerWorld, VolumeSampler(vox),
                                                        MaterialBlocks(vox),
                                                        Miller(vox, float(iso), tissues), tissues,
                                                        DirtyBlocks(vox.dims())}));
  Volume& added = *volumes_.back();
  if (node) added.millingBudget = node->millingBudget.get();
  if (tissues)
    for (float hardness : tissues->hardness()) added.feelsPendingCuts &= hardness > 0.f;
  added.axisAligned = lin[0][1] == 0.0 && lin[0][2] == 0.0 && lin[1][0] == 0.0 && lin[1][2] == 0.0 &&
                      lin[2][0] == 0.0 && lin[2][1] == 0.0;
  added.worldToIndexScale = glm::dvec3(lin[0][0], lin[1][1], lin[2][2]);
  // The haptic sampler's window (VolumeSampler::focus): 24³ voxels hold a
  // 0.6 mm burr's samples at 0.1 mm voxels with 3 voxels to move before it
  // is copied again; a reach it cannot hold is sampled as before.
  added.sampler.enableWindow(kWindowEdge);
  const glm::dvec3 h = vox.voxelSize() * scale;
  const double smallest = std::min({h.x, h.y, h.z});
  voxelSize_ = voxelSize_ > 0.0 ? std::min(voxelSize_, smallest) : smallest;
}

double VoxelScene::field(const glm::dvec3& world) const {
  // One volume, as in every shipped lesson: no loop and no maximum (66 → 58
  // instructions a call of its own; #1's §8.2 frames −1.7 %, callgrind).
  if (volumes_.size() == 1) {
    const Volume& v = *volumes_.front();
    return double(v.sampler.density(v.toIndex(world))) - v.placement.iso;
  }
  double best = -std::numeric_limits<double>::infinity();
  for (const auto& v : volumes_) {
    best = std::max(best, double(v->sampler.density(v->toIndex(world))) - v->placement.iso);
  }
  return volumes_.empty() ? -1.0 : best;
}

void VoxelScene::focus(const glm::dvec3& world, double reach) {
  for (const auto& v : volumes_)
    v->sampler.focus(v->toIndex(world), reach * v->indexPerWorld);
}

bool VoxelScene::mayHaveMaterialNear(const glm::dvec3& world, double radius) const {
  for (const auto& v : volumes_)
    if (v->material.mayHaveMaterialNear(v->toIndex(world),
                                        radius * v->indexPerWorld))
      return true;
  return false;
}

glm::dvec3 VoxelScene::gradient(const glm::dvec3& world) const {
  double best = -std::numeric_limits<double>::infinity();
  glm::dvec3 g(0.0);
  for (const auto& v : volumes_) {
    const glm::dvec3 idx = v->toIndex(world);
    const double s = double(v->sampler.density(idx)) - v->placement.iso;
    if (s > best) {
      best = s;
      // d s/d world = (d index/d world)ᵀ · d s/d index
      g = glm::transpose(v->worldToIndexLinear) * v->sampler.gradient(idx);
    }
  }
  return g;
}

const PointShellQuery& VoxelScene::pointShell(std::size_t volume, int scale) { return shell(volume, scale); }

const PointShellQuery& VoxelScene::preparePointShell(std::size_t volume, int scale) {
  for (Shell& s : shells_)
    if (s.volume == volume && s.scale == scale) return *s.shell;
  if (loopRunning_.load(std::memory_order_acquire))
    throw std::runtime_error("volume " + std::to_string(volume) + " has no point shell at scale " +
                             std::to_string(scale) +
                             " and one cannot be built while the haptic loop mills it; it takes effect at the next run");
  return shell(volume, scale);
}

const PointShell& VoxelScene::shell(std::size_t volume, int scale) {
  Volume& v = *volumes_.at(volume);
  for (Shell& s : shells_) {
    if (s.volume != volume || s.scale != scale) continue;
    if (!s.pending.empty()) {
      s.shell->update(*v.voxels, s.pending);
      s.pending.clear();
    }
    return *s.shell;
  }
  // First request (compile time): a node keeps its shells between runs, and a
  // kept one may have missed milling while no renderer used it.
  Shell s{volume, scale, nullptr, nullptr, DirtyBlocks(v.voxels->dims())};
  if (v.node) {
    const bool existed = v.node->hasPointShell(scale);
    s.shell = &v.node->pointShell(scale);
    if (existed) s.shell->rebuildAll(*v.voxels);
  } else {
    s.owned = std::make_unique<PointShell>(*v.voxels, float(v.placement.iso), scale);
    s.shell = s.owned.get();
  }
  shells_.push_back(std::move(s));
  return *shells_.back().shell;
}

double VoxelScene::hardness(const glm::dvec3& world) const {
  for (const auto& v : volumes_) {
    if (!v->tissues) continue;
    const glm::dvec3 idx = glm::round(v->toIndex(world));
    const glm::ivec3 dims = v->voxels->dims();
    if (!(idx.x >= 0 && idx.y >= 0 && idx.z >= 0 && idx.x < dims.x && idx.y < dims.y && idx.z < dims.z)) continue;
    const int label = v->tissues->labelAt(int(idx.x), int(idx.y), int(idx.z));
    if (label != 0) return double(v->tissues->hardness()[std::size_t(label)]);
  }
  return 1.0;
}

double VoxelScene::mill(const glm::dvec3& centreWorld, double radius) {
  for (const std::unique_ptr<Volume>& p : volumes_) {
    Volume& v = *p;
    if (!v.millable.load(std::memory_order_relaxed)) continue;
    const glm::dvec3 local = glm::dvec3(v.placement.worldToLocal * glm::dvec4(centreWorld, 1.0));
    v.miller.queue(local, radius / v.placement.worldPerLocal);
  }
  return continueMilling();
}

double VoxelScene::mill(const glm::dvec3& centreWorld, const glm::dquat& toolOrientation, const BurrHead& head) {
  if (head.shape == BurrShape::Round) return mill(centreWorld, head.radius);
  const glm::dvec3 axisWorld = toolOrientation * glm::dvec3(0.0, 1.0, 0.0);
  for (const std::unique_ptr<Volume>& p : volumes_) {
    Volume& v = *p;
    if (!v.millable.load(std::memory_order_relaxed)) continue;
    const glm::dvec3 local = glm::dvec3(v.placement.worldToLocal * glm::dvec4(centreWorld, 1.0));
    const glm::dvec3 axisLocal = glm::dmat3(v.placement.worldToLocal) * axisWorld;  // unit after normalising
    v.miller.queue(local, axisLocal, head.scaled(1.0 / v.placement.worldPerLocal));
  }
  return continueMilling();
}

double VoxelScene::continueMilling() {
  double removed = 0.0;
  for (std::size_t i = 0; i < volumes_.size(); ++i) {
    Volume& v = *volumes_[i];
    // A stamp begun while the volume was millable is finished: it was felt.
    if (!v.miller.busy()) continue;
    // Clearing first keeps `changed` to this call's blocks (O(blocks), no allocation).
    v.changed.clear();
    const StampResult res = v.miller.work(v.millingBudget, v.changed);
    removed += res.removedVolume;
    feelPendingCuts(v);
    if (v.changed.empty()) continue;
    v.sampler.refresh(v.changed.voxelLo(), v.changed.voxelHi());  // its window holds copies
    ++v.millEpoch;
    // The shells only collect the change here; each merges it when next asked for.
    for (Shell& s : shells_)
      if (s.volume == i) s.pending.add(v.changed);
  }
  return removed;
}

void VoxelScene::feelPendingCuts(Volume& v) {
  // The renderers feel what the stamps will leave, not how far the walk has
  // got: without this the cut trails the burr, a delay inside #2's loop of
  // force, feed and removal that set its simulated hand oscillating at 50 µm.
  VolumeSampler::PendingCut cuts[VolumeSampler::kMaxPendingCuts];
  int n = 0;
  if (v.feelsPendingCuts)
    for (const Miller::Stamp* s : {v.miller.walking(), v.miller.waiting()})
      if (s) cuts[n++] = {s->round, v.voxels->localToIndex(s->centreLocal), s->radius, s->axis, s->head};
  if (n > 0) v.sampler.setPendingCuts(cuts, n, float(v.placement.iso), v.voxels->voxelSize());
  else v.sampler.clearPendingCuts();
}

bool VoxelScene::millingPending() const {
  return std::any_of(volumes_.begin(), volumes_.end(), [](const std::unique_ptr<Volume>& v) { return v->miller.busy(); });
}

}  // namespace millsim
