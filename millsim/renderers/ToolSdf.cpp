#include "millsim/renderers/ToolSdf.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace millsim {

namespace {

glm::dmat3 outer(const glm::dvec3& a, const glm::dvec3& b) {
  return glm::dmat3(a * b.x, a * b.y, a * b.z);  // column j = a · b_j
}

// The finite cylinder (radius r, axis +Y, y in [0, L]): exact distance in the
// 2-D (radial, axial) half-plane, as in Quilez's capped-cylinder formula.
double cylinder(const glm::dvec3& q, double r, double L, double& rho, glm::dvec2& e) {
  // Not std::hypot: its guard against overflow (none at a tool's scale) made
  // it 1.7 % of #3's frames, called for every contact.
  rho = std::sqrt(q.x * q.x + q.z * q.z);
  const double halfL = 0.5 * L;
  e = glm::dvec2(rho - r, std::abs(q.y - halfL) - halfL);  // > 0: outside the side / the end caps
  return std::min(std::max(e.x, e.y), 0.0) + glm::length(glm::max(e, glm::dvec2(0.0)));
}

}  // namespace

ToolSdf::ToolSdf(const ToolGeometry& tool, double gridVoxelSize)
    : tool_(tool), outer_(std::max(tool.tipRadius, tool.shaftRadius)), h_(gridVoxelSize) {
  // Grid over the bounding box plus a margin: two cells, so that trilinear
  // values near the surface never reach the grid's edge. Capped so a silly
  // voxel size cannot allocate gigabytes (the grid is for comparison).
  const double margin = 2.0 * h_;
  origin_ = boxLo() - margin;
  const glm::dvec3 size = boxHi() - boxLo() + 2.0 * margin;
  dims_ = glm::ivec3(glm::ceil(size / h_)) + 1;
  if (double(dims_.x) * dims_.y * dims_.z > 64e6) throw std::invalid_argument("tool SDF grid too fine");
  grid_.resize(std::size_t(dims_.x) * dims_.y * dims_.z);
  for (int k = 0; k < dims_.z; ++k)
    for (int j = 0; j < dims_.y; ++j)
      for (int i = 0; i < dims_.x; ++i)
        grid_[(std::size_t(k) * dims_.y + j) * dims_.x + i] = float(distance(origin_ + glm::dvec3(i, j, k) * h_));
}

double ToolSdf::distance(const glm::dvec3& q) const {
  double rho;
  glm::dvec2 e;
  return std::min(headDistance(q), cylinder(q, tool_.shaftRadius, tool_.shaftLength, rho, e));
}

double ToolSdf::headDistance(const glm::dvec3& q) const {
  if (tool_.round()) return glm::length(q) - tool_.tipRadius;
  return headProfileDistance(tool_.head(), std::hypot(q.x, q.z), q.y);
}

SdfSample ToolSdf::analytic(const glm::dvec3& q, bool withHessian) const {
  SdfSample s;
  const double len = glm::length(q);
  double rho;
  glm::dvec2 e;
  const double dCyl = cylinder(q, tool_.shaftRadius, tool_.shaftLength, rho, e);
  if (!tool_.round()) {
    // A head of revolution: d(ρ, y) of its profile. ∇d = d_ρ ρ̂ + d_y ŷ; the
    // Hessian is d_ρ ∇²ρ (∇²ρ = (P − ρ̂ρ̂ᵀ)/ρ) plus the profile's own 2-D
    // Hessian, (I − g gᵀ)/d at a rim corner and zero on a flat side or cap.
    glm::dvec2 g;
    bool corner = false;
    const double dHead = headProfileDistance(tool_.head(), rho, q.y, &g, &corner);
    if (dHead <= dCyl) {
      s.distance = dHead;
      const glm::dvec3 radial = rho > 1e-12 ? glm::dvec3(q.x, 0, q.z) / rho : glm::dvec3(1, 0, 0);
      s.gradient = radial * g.x + glm::dvec3(0, g.y, 0);
      if (withHessian) {
        const glm::dmat3 P(glm::dvec3(1, 0, 0), glm::dvec3(0), glm::dvec3(0, 0, 1));
        if (rho > 1e-12) s.hessian = (P - outer(radial, radial)) * (g.x / rho);
        if (corner && dHead > 1e-12) {
          const glm::dvec3 y(0, 1, 0);
          // J (I − g gᵀ) Jᵀ / d with J = [ρ̂ ŷ].
          s.hessian += (outer(radial, radial) + outer(y, y) - outer(s.gradient, s.gradient)) / dHead;
        }
      }
      return s;
    }
  }
  const double dSphere = tool_.round() ? len - tool_.tipRadius : 1e300;
  // Union = min; each branch's derivatives are exact where it is the minimum.
  if (dSphere <= dCyl) {
    s.distance = dSphere;
    if (len < 1e-12) return s.gradient = {0, -1, 0}, s;  // the centre: any direction, pick one
    s.gradient = q / len;
    if (withHessian) s.hessian = (glm::dmat3(1.0) - outer(s.gradient, s.gradient)) / len;
    return s;
  }
  s.distance = dCyl;
  const glm::dvec3 radial = rho > 1e-12 ? glm::dvec3(q.x, 0, q.z) / rho : glm::dvec3(1, 0, 0);
  const double axial = q.y > 0.5 * tool_.shaftLength ? 1.0 : -1.0;
  if (e.x > 0.0 && e.y > 0.0) {
    // Outside, nearest the rim circle: d = |(e.x, e.y)|.
    const double l = std::hypot(e.x, e.y);
    s.gradient = (radial * e.x + glm::dvec3(0, axial, 0) * e.y) / l;
    if (withHessian) {
      // ∇e.x = radial, ∇e.y = axial ŷ; ∇²e.x = (P − radial radialᵀ)/ρ with P the xz projector.
      const glm::dmat3 P(glm::dvec3(1, 0, 0), glm::dvec3(0), glm::dvec3(0, 0, 1));
      const glm::dmat3 Hex = rho > 1e-12 ? (P - outer(radial, radial)) / rho : glm::dmat3(0.0);
      s.hessian = (Hex * e.x + outer(radial, radial) + outer(glm::dvec3(0, axial, 0), glm::dvec3(0, axial, 0)) -
                   outer(s.gradient, s.gradient)) / l;
    }
  } else if (e.x >= e.y) {
    // The side wall: d = ρ − r.
    s.gradient = radial;
    if (withHessian && rho > 1e-12) {
      const glm::dmat3 P(glm::dvec3(1, 0, 0), glm::dvec3(0), glm::dvec3(0, 0, 1));
      s.hessian = (P - outer(radial, radial)) / rho;
    }
  } else {
    s.gradient = {0, axial, 0};  // an end cap: flat, zero Hessian
  }
  return s;
}

bool ToolSdf::cell(const glm::dvec3& q, glm::ivec3& i0, glm::dvec3& f) const {
  const glm::dvec3 g = (q - origin_) / h_;
  if (!(g.x >= 0.0 && g.y >= 0.0 && g.z >= 0.0)) return false;
  i0 = glm::ivec3(g);
  if (i0.x >= dims_.x - 1 || i0.y >= dims_.y - 1 || i0.z >= dims_.z - 1) return false;
  f = g - glm::dvec3(i0);
  return true;
}

double ToolSdf::sampledDistance(const glm::dvec3& q) const {
  glm::ivec3 i;
  glm::dvec3 f;
  if (!cell(q, i, f)) return distance(q);
  const double c00 = at(i.x, i.y, i.z) * (1 - f.x) + at(i.x + 1, i.y, i.z) * f.x;
  const double c10 = at(i.x, i.y + 1, i.z) * (1 - f.x) + at(i.x + 1, i.y + 1, i.z) * f.x;
  const double c01 = at(i.x, i.y, i.z + 1) * (1 - f.x) + at(i.x + 1, i.y, i.z + 1) * f.x;
  const double c11 = at(i.x, i.y + 1, i.z + 1) * (1 - f.x) + at(i.x + 1, i.y + 1, i.z + 1) * f.x;
  return (c00 * (1 - f.y) + c10 * f.y) * (1 - f.z) + (c01 * (1 - f.y) + c11 * f.y) * f.z;
}

SdfSample ToolSdf::sampled(const glm::dvec3& q) const {
  glm::ivec3 i;
  glm::dvec3 f;
  if (!cell(q, i, f)) return analytic(q, false);
  double v[2][2][2];
  for (int c = 0; c < 8; ++c) v[c & 1][(c >> 1) & 1][c >> 2] = at(i.x + (c & 1), i.y + ((c >> 1) & 1), i.z + (c >> 2));
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  SdfSample s;
  // Trilinear value and its exact derivative (piecewise constant per cell axis).
  const double x00 = lerp(v[0][0][0], v[1][0][0], f.x), x10 = lerp(v[0][1][0], v[1][1][0], f.x);
  const double x01 = lerp(v[0][0][1], v[1][0][1], f.x), x11 = lerp(v[0][1][1], v[1][1][1], f.x);
  s.distance = lerp(lerp(x00, x10, f.y), lerp(x01, x11, f.y), f.z);
  const double dx00 = v[1][0][0] - v[0][0][0], dx10 = v[1][1][0] - v[0][1][0];
  const double dx01 = v[1][0][1] - v[0][0][1], dx11 = v[1][1][1] - v[0][1][1];
  s.gradient.x = lerp(lerp(dx00, dx10, f.y), lerp(dx01, dx11, f.y), f.z) / h_;
  s.gradient.y = lerp(x10 - x00, x11 - x01, f.z) / h_;
  s.gradient.z = (lerp(x01, x11, f.y) - lerp(x00, x10, f.y)) / h_;
  return s;
}

}  // namespace millsim
