#pragma once
// The burr's cutting head (issue 18 part 2): its shape and its exact signed
// distance. Header-only and glm-only, so milling (millsim/volume), the
// renderers and graphics share one definition.
//
// Frame (docs/algorithms.md, "Burr shapes"): the tool origin is the burr
// centre and the shaft runs along local +Y.
//   round          a sphere of radius tipRadius centred on the origin.
//   cylinder       a flat-ended cylinder of radius tipRadius, axis Y, from
//                  y = −tipLength/2 (the cutting end) to y = +tipLength/2.
//   taper          a truncated cone over the same span: radius tipEndRadius at
//                  the cutting end (y = −tipLength/2), tipRadius at the shank
//                  end (y = +tipLength/2) — a tapered fissure burr.
//   inverted-cone  the same span, tipRadius at the cutting end and
//                  tipEndRadius at the shank end (wider at the tip).
// So every non-round head is centred on the origin (the burr centre is the
// middle of the head's axis), and tipRadius is always its widest radius.
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

#include <glm/vec2.hpp>

namespace millsim {

enum class BurrShape { Round, Cylinder, Taper, InvertedCone };

inline constexpr std::string_view kBurrShapeNames = "round, cylinder, taper, inverted-cone";

inline bool parseBurrShape(std::string_view name, BurrShape& shape) {
  if (name == "round") shape = BurrShape::Round;
  else if (name == "cylinder") shape = BurrShape::Cylinder;
  else if (name == "taper") shape = BurrShape::Taper;
  else if (name == "inverted-cone") shape = BurrShape::InvertedCone;
  else return false;
  return true;
}

inline std::string_view burrShapeName(BurrShape s) {
  switch (s) {
    case BurrShape::Round: return "round";
    case BurrShape::Cylinder: return "cylinder";
    case BurrShape::Taper: return "taper";
    case BurrShape::InvertedCone: return "inverted-cone";
  }
  return "round";
}

// The shape after `s` in the order above, round after inverted-cone (the window's B key).
inline std::string_view nextBurrShape(BurrShape s) {
  switch (s) {
    case BurrShape::Round: return "cylinder";
    case BurrShape::Cylinder: return "taper";
    case BurrShape::Taper: return "inverted-cone";
    case BurrShape::InvertedCone: return "round";
  }
  return "round";
}

// The head's dimensions (in whatever length unit the caller works in).
struct BurrHead {
  BurrShape shape = BurrShape::Round;
  double radius = 1.0e-3;     // tipRadius: the sphere, or the head's widest radius
  double length = 2.0e-3;     // tipLength: the head's length along Y (not used by round)
  double endRadius = 0.5e-3;  // tipEndRadius: the narrow end's radius (taper, inverted-cone)

  // Radii at the cutting end (y = −length/2) and the shank end (y = +length/2).
  double cuttingEndRadius() const {
    return shape == BurrShape::Taper ? endRadius : radius;
  }
  double shankEndRadius() const { return shape == BurrShape::InvertedCone ? endRadius : radius; }
  // Radius of the smallest sphere about the origin that holds the head.
  double boundingRadius() const {
    return shape == BurrShape::Round ? radius : std::hypot(0.5 * length, radius);
  }
  BurrHead scaled(double s) const { return {shape, radius * s, length * s, endRadius * s}; }
};

// Signed distance (negative inside) of a non-round head's profile at radial
// distance rho ≥ 0 from the axis and axial coordinate y, with the outward unit
// gradient in (rho, y) and, when the nearest point is a corner of the profile
// (outside only), `corner` = true (the 2-D Hessian is then (I − g gᵀ)/d; on a
// flat side or cap it is zero). The profile is the trapezoid (0, −L/2),
// (r0, −L/2), (r1, L/2), (0, L/2); its edge on the axis is not a surface.
// For round heads use |q| − radius.
inline double headProfileDistance(const BurrHead& b, double rho, double y, glm::dvec2* gradient = nullptr,
                                  bool* corner = nullptr) {
  const double h = 0.5 * b.length, r0 = b.cuttingEndRadius(), r1 = b.shankEndRadius();
  const glm::dvec2 q(rho, y);
  const glm::dvec2 v[4] = {{0.0, -h}, {r0, -h}, {r1, h}, {0.0, h}};
  double best2 = 1e300;
  glm::dvec2 nearest(0.0), sideNormal(0.0);
  bool atCorner = false;
  for (int e = 0; e < 3; ++e) {
    const glm::dvec2 a = v[e], d = v[e + 1] - a;
    const double len2 = d.x * d.x + d.y * d.y;
    const double t = len2 > 0.0 ? std::clamp(((q.x - a.x) * d.x + (q.y - a.y) * d.y) / len2, 0.0, 1.0) : 0.0;
    const glm::dvec2 p = a + t * d;
    const double dist2 = (q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y);
    if (dist2 < best2) {
      best2 = dist2;
      nearest = p;
      // Outward normal of the edge (the profile runs counter-clockwise in (rho, y)).
      const double l = std::sqrt(len2);
      sideNormal = l > 0.0 ? glm::dvec2(d.y / l, -d.x / l) : glm::dvec2(0.0, -1.0);
      atCorner = (t <= 0.0 && e > 0) || (t >= 1.0 && e < 2);
    }
  }
  const bool inside = y > -h && y < h && rho < r0 + (r1 - r0) * (y + h) / b.length;
  const double dist = std::sqrt(best2);
  if (gradient) {
    if (atCorner && !inside && dist > 0.0) *gradient = (q - nearest) / dist;
    else *gradient = sideNormal;
  }
  if (corner) *corner = atCorner && !inside && dist > 0.0;
  return inside ? -dist : dist;
}

}  // namespace millsim
