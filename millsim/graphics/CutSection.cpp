#include "millsim/graphics/CutSection.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "millsim/graphics/VolumeMesh.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VolumeSampler.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

CutSection::CutSection(const VoxelVolume& voxels, float isoValue, const TissueMap* tissues)
    : voxels_(voxels), tissues_(tissues), iso_(isoValue) {}

glm::dvec3 CutSection::corner(int i) const {
  const double a = (i == 1 || i == 2) ? double(width_) : 0.0, b = i >= 2 ? double(height_) : 0.0;
  return origin_ + texel_ * (a * u_ + b * v_);
}

bool CutSection::aim(const glm::dvec4& plane, const glm::dmat4& localToWorld) {
  if (aimed_ && plane == plane_ && localToWorld == localToWorld_) return hasSection();
  aimed_ = true;
  plane_ = plane;
  localToWorld_ = localToWorld;
  width_ = height_ = 0;
  rgba_.clear();

  // Index space (voxel centres at integers) to the world, and the plane in it.
  const glm::dvec3 h = voxels_.voxelSize(), at0 = voxels_.indexToLocal(glm::dvec3(0.0));
  glm::dmat4 indexToLocal(1.0);
  indexToLocal[0][0] = h.x, indexToLocal[1][1] = h.y, indexToLocal[2][2] = h.z;
  indexToLocal[3] = glm::dvec4(at0, 1.0);
  const glm::dmat4 indexToWorld = localToWorld * indexToLocal;
  worldToIndex_ = glm::inverse(indexToWorld);
  indexPlane_ = glm::transpose(indexToWorld) * plane;

  // Where the plane crosses the box of voxel centres: its edges' crossings.
  const glm::dvec3 hi = glm::dvec3(voxels_.dims() - 1);
  auto cornerOf = [&](int c) { return glm::dvec3(c & 1 ? hi.x : 0.0, c & 2 ? hi.y : 0.0, c & 4 ? hi.z : 0.0); };
  auto side = [&](const glm::dvec3& p) { return glm::dot(glm::dvec3(indexPlane_), p) + indexPlane_.w; };
  std::vector<glm::dvec3> crossings;
  for (int c = 0; c < 8; ++c)
    for (int axis = 1; axis <= 4; axis <<= 1) {
      if (c & axis) continue;  // each edge once, from its lower corner
      const glm::dvec3 p = cornerOf(c), q = cornerOf(c | axis);
      const double sp = side(p), sq = side(q);
      if ((sp < 0.0) == (sq < 0.0) && sp != 0.0 && sq != 0.0) continue;
      const double t = sp == sq ? 0.0 : sp / (sp - sq);
      crossings.push_back(glm::dvec3(indexToWorld * glm::dvec4(p + t * (q - p), 1.0)));
    }
  if (crossings.empty()) return false;

  // A square texel a voxel wide (the smallest edge in the world), coarser
  // where the section would be wider than kMaxTexels.
  const glm::dvec3 n = glm::normalize(glm::dvec3(plane));
  const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
  u_ = glm::normalize(glm::cross(helper, n));
  v_ = glm::cross(n, u_);
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  for (const glm::dvec3& p : crossings) {
    u0 = std::min(u0, glm::dot(p, u_)), u1 = std::max(u1, glm::dot(p, u_));
    v0 = std::min(v0, glm::dot(p, v_)), v1 = std::max(v1, glm::dot(p, v_));
  }
  texel_ = std::min({glm::length(glm::dvec3(indexToWorld[0])), glm::length(glm::dvec3(indexToWorld[1])),
                     glm::length(glm::dvec3(indexToWorld[2]))});
  const double span = std::max(u1 - u0, v1 - v0);
  if (!(texel_ > 0.0) || !std::isfinite(span)) return false;
  texel_ = std::max(texel_, span / double(kMaxTexels - 2));
  // A texel of margin on each side: the filtering reaches half a texel out.
  width_ = int(std::ceil((u1 - u0) / texel_)) + 2;
  height_ = int(std::ceil((v1 - v0) / texel_)) + 2;
  const glm::dvec3 onPlane = -plane.w / glm::dot(glm::dvec3(plane), n) * n;
  origin_ = onPlane + (u0 - texel_) * u_ + (v0 - texel_) * v_;
  rgba_.assign(std::size_t(width_) * std::size_t(height_) * 4, 0);
  const TexelRect all{0, 0, width_, height_};
  sample(all);
  fillEmptyColours(all);
  return true;
}

void CutSection::sample(const TexelRect& r) {
  const VolumeSampler sampler(voxels_);
  const float air = voxels_.airValue();
  // Milling's material fraction: ½ at the isoValue, 0 at air.
  const double phiScale = iso_ > air ? 1.0 / (2.0 * (double(iso_) - air)) : 0.0;
  auto phi = [&](double d) { return phiScale > 0.0 ? std::clamp((d - air) * phiScale, 0.0, 1.0) : d >= iso_ ? 1.0 : 0.0; };
  const glm::ivec3 dims = voxels_.dims();
  std::optional<TissueMap::LabelGrid::ConstAccessor> labels;
  if (tissues_) labels.emplace(tissues_->labels().getConstAccessor());
  // Texel centres are affine in (a, b): one index-space step per texel along each image axis.
  const glm::dvec3 du(worldToIndex_ * glm::dvec4(texel_ * u_, 0.0)), dv(worldToIndex_ * glm::dvec4(texel_ * v_, 0.0));
  const glm::dvec3 first(worldToIndex_ * glm::dvec4(origin_ + 0.5 * texel_ * (u_ + v_), 1.0));
  for (int b = r.y0; b < r.y1; ++b)
    for (int a = r.x0; a < r.x1; ++a) {
      const glm::dvec3 p = first + double(a) * du + double(b) * dv;
      const float d = sampler.density(p);
      double fraction = phi(d);
      glm::vec3 colour = densityColour(d, iso_);
      if (labels) {
        // The tissue colours of the cell's eight voxels blended by their
        // trilinear weights (as VolumeMesh colours the surface): the labels'
        // voxel steps would otherwise show as stairs along each boundary.
        const glm::dvec3 base = glm::floor(p), f = p - base;
        glm::vec3 sum(0.f);
        double weight = 0.0, softWeight = 0.0, softFraction = 0.0;
        for (int k = 0; k < 8; ++k) {
          const glm::ivec3 v = glm::ivec3(base) + glm::ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
          if (glm::any(glm::lessThan(v, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(v, dims))) continue;
          const int label = labels->getValue(openvdb::Coord(v.x, v.y, v.z));
          const double w = (k & 1 ? f.x : 1.0 - f.x) * (k & 2 ? f.y : 1.0 - f.y) * (k & 4 ? f.z : 1.0 - f.z);
          if (label <= 0 || !(w > 0.0)) continue;
          const TissueMap::Entry& e = tissues_->entries()[std::size_t(label)];
          sum += float(w) * e.colour;
          weight += w;
          // A soft tissue is there as far as milling left its original density.
          if (e.soft && e.densityBelowSurface < iso_ && e.densityBelowSurface > air) {
            softFraction += w * std::clamp((double(d) - air) / (double(e.densityBelowSurface) - air), 0.0, 1.0);
            softWeight += w;
          }
        }
        if (weight > 0.0) colour = sum / float(weight);
        // Soft where most of the cell is: the section's edge then lies where the tissue's does.
        if (softWeight > 0.5) fraction = std::max(fraction, softFraction / softWeight);
      }
      std::uint8_t* t = &rgba_[(std::size_t(b) * std::size_t(width_) + std::size_t(a)) * 4];
      for (int k = 0; k < 3; ++k) t[k] = std::uint8_t(std::lround(255.0 * std::clamp(double(colour[k]), 0.0, 1.0)));
      t[3] = std::uint8_t(std::lround(255.0 * fraction));
    }
  sampled_ += std::uint64_t(std::max(r.x1 - r.x0, 0)) * std::uint64_t(std::max(r.y1 - r.y0, 0));
}

void CutSection::fillEmptyColours(const TexelRect& r) {
  // An empty texel next to material takes that material's colour: filtered
  // between them, the cap's rim is then the tissue's colour, not half black.
  const TexelRect e{std::max(r.x0 - 1, 0), std::max(r.y0 - 1, 0), std::min(r.x1 + 1, width_), std::min(r.y1 + 1, height_)};
  auto at = [&](int a, int b) { return &rgba_[(std::size_t(b) * std::size_t(width_) + std::size_t(a)) * 4]; };
  for (int b = e.y0; b < e.y1; ++b)
    for (int a = e.x0; a < e.x1; ++a) {
      std::uint8_t* t = at(a, b);
      if (t[3] >= 128) continue;
      for (int k = 0; k < 8; ++k) {
        static constexpr int kDa[8] = {1, -1, 0, 0, 1, 1, -1, -1}, kDb[8] = {0, 0, 1, -1, 1, -1, 1, -1};
        const int na = a + kDa[k], nb = b + kDb[k];
        if (na < 0 || nb < 0 || na >= width_ || nb >= height_) continue;
        if (const std::uint8_t* n = at(na, nb); n[3] >= 128) {
          std::copy(n, n + 3, t);
          break;
        }
      }
    }
}

TexelRect CutSection::update(const std::vector<BlockOrigin>& blocks) {
  if (!aimed_ || !hasSection() || blocks.empty()) return {};
  const glm::dmat4 indexToWorld = glm::inverse(worldToIndex_);
  auto side = [&](const glm::dvec3& p) { return glm::dot(glm::dvec3(indexPlane_), p) + indexPlane_.w; };
  double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
  for (const BlockOrigin& o : blocks) {
    // A texel reads the voxels of the cell it lies in: a block reaches the
    // texels within a voxel of it.
    const glm::dvec3 lo = glm::dvec3(o) - 1.0, hi = glm::dvec3(o) + double(DirtyBlocks::kSize);
    glm::dvec3 corners[8];
    bool below = false, above = false;
    for (int c = 0; c < 8; ++c) {
      corners[c] = glm::dvec3(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
      const double s = side(corners[c]);
      below |= s <= 0.0, above |= s >= 0.0;
    }
    if (!below || !above) continue;
    for (const glm::dvec3& c : corners) {
      const glm::dvec3 w(indexToWorld * glm::dvec4(c, 1.0));
      const double a = glm::dot(w - origin_, u_) / texel_, b = glm::dot(w - origin_, v_) / texel_;
      a0 = std::min(a0, a), a1 = std::max(a1, a), b0 = std::min(b0, b), b1 = std::max(b1, b);
    }
  }
  if (a0 > a1) return {};
  const TexelRect r{std::clamp(int(std::floor(a0)) - 1, 0, width_), std::clamp(int(std::floor(b0)) - 1, 0, height_),
                    std::clamp(int(std::ceil(a1)) + 1, 0, width_), std::clamp(int(std::ceil(b1)) + 1, 0, height_)};
  if (r.empty()) return {};
  sample(r);
  fillEmptyColours(r);
  // What fillEmptyColours may have touched: one texel more on each side.
  return {std::max(r.x0 - 1, 0), std::max(r.y0 - 1, 0), std::min(r.x1 + 1, width_), std::min(r.y1 + 1, height_)};
}

}  // namespace millsim
