#include "millsim/haptics/HapticScene.h"

#include <cmath>
#include <functional>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "millsim/core/Scene.h"
#include "millsim/std/Inline.h"
#include "millsim/std/Transform.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim {

HapticScene::HapticScene(const Scene& scene) {
  std::function<void(Node&, const glm::dmat4&)> walk = [&](Node& n, const glm::dmat4& parent) {
    glm::dmat4 m = parent;
    if (auto* t = dynamic_cast<Transform*>(&n)) m = parent * glm::dmat4(t->localMatrix());
    if (auto* vo = dynamic_cast<VolumeObject*>(&n); vo && vo->volume())
      addVolume(*vo->volume(), m, double(vo->isoValue.get()), vo);
    for (Field* f : n.fields())
      if (auto* nf = dynamic_cast<NodeFieldBase*>(f))
        for (auto& child : nf->nodes()) walk(*child, m);
  };
  for (auto& n : scene.root->children.get()) walk(*n, glm::dmat4(1.0));
}

void HapticScene::addVolume(VoxelVolume& vox, const glm::dmat4& m, double iso, VolumeObject* node) {
  // index = (local / voxelSize) + halfExtent, local = worldToLocal · world.
  const glm::dmat4 worldToLocal = glm::inverse(m);
  const glm::dvec3 inv = 1.0 / vox.voxelSize();
  const glm::dmat3 lin =
      glm::dmat3(glm::dvec3(inv.x, 0, 0), glm::dvec3(0, inv.y, 0), glm::dvec3(0, 0, inv.z)) * glm::dmat3(worldToLocal);
  const glm::dvec3 offset = glm::dvec3(worldToLocal[3]) * inv + vox.localToIndex(glm::dvec3(0.0));
  const double scale = std::cbrt(std::abs(glm::determinant(glm::dmat3(m))));
  const bool millable = node ? node->millable.get() : true;
  volumes_.push_back(std::unique_ptr<Volume>(new Volume{node, millable, &vox, m, worldToLocal, lin, offset, iso, scale,
                                                        VolumeSampler(vox), Miller(vox, float(iso)),
                                                        DirtyBlocks(vox.dims())}));
  const glm::dvec3 h = vox.voxelSize() * scale;
  const double smallest = std::min({h.x, h.y, h.z});
  voxelSize_ = voxelSize_ > 0.0 ? std::min(voxelSize_, smallest) : smallest;
}

double HapticScene::field(const glm::dvec3& world) const {
  double best = -std::numeric_limits<double>::infinity();
  for (const auto& v : volumes_) {
    const glm::dvec3 idx = v->worldToIndexLinear * world + v->worldToIndexOffset;
    best = std::max(best, double(v->sampler.density(idx)) - v->iso);
  }
  return volumes_.empty() ? -1.0 : best;
}

glm::dvec3 HapticScene::gradient(const glm::dvec3& world) const {
  double best = -std::numeric_limits<double>::infinity();
  glm::dvec3 g(0.0);
  for (const auto& v : volumes_) {
    const glm::dvec3 idx = v->worldToIndexLinear * world + v->worldToIndexOffset;
    const double s = double(v->sampler.density(idx)) - v->iso;
    if (s > best) {
      best = s;
      // d s/d world = (d index/d world)ᵀ · d s/d index
      g = glm::transpose(v->worldToIndexLinear) * v->sampler.gradient(idx);
    }
  }
  return g;
}

glm::dvec3 HapticScene::outwardNormal(const glm::dvec3& world) const {
  const glm::dvec3 g = gradient(world);
  const double len = glm::length(g);
  return len > 1e-12 && std::isfinite(len) ? -g / len : glm::dvec3(0.0);
}

double HapticScene::mill(const glm::dvec3& centreWorld, double radius) {
  double removed = 0.0;
  for (auto& v : volumes_) {
    if (!v->millable) continue;
    const glm::dvec3 local = glm::dvec3(v->worldToLocal * glm::dvec4(centreWorld, 1.0));
    // Clearing first keeps `changed` to this call's blocks (O(blocks), no allocation).
    v->changed.clear();
    const StampResult res = v->miller.stamp(local, radius / v->worldPerLocal, v->changed);
    removed += res.removedVolume;
    if (!v->changed.empty()) ++v->millEpoch;
  }
  return removed;
}

}  // namespace millsim
