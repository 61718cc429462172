#pragma once
// The tool's locally deepest points in material, for SurfacePointRenderer's
// default force (docs/algorithms.md, Algorithm #2). Depths are measured along
// lines through the tool: from the burr centre, or out of the shaft's axis,
// to where the line crosses from air into material (half-voxel steps, then
// the density fraction of eq. 1 and a regula-falsi step). A contact is the
// line where that crossing is nearest the tool's centre — its depth largest —
// found from a colliding surface point by parabola fits over the line's two
// angles. The lines' symmetric samples a fixed angle apart average the
// one-voxel ripple of the iso-surface instead of following it.
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace millsim {

class HapticScene;

struct PointContact {
  glm::dvec3 point{0.0};   // on the material's surface, on the contact's line
  glm::dvec3 normal{0.0};  // unit, out of the material: the way it pushes the tool
  double depth = 0.0;      // m, how far the tool's surface is past `point` along −normal
};

// Where o + t·u crosses from air (smaller t) into material (larger t),
// searched from t0 towards the nearest such crossing; tMin if the line is in
// material all the way down, tMax if it is in air all the way up.
double lineCrossing(const HapticScene& scene, const glm::dvec3& o, const glm::dvec3& u, double t0, double tMin,
                    double tMax);

// The burr sphere (centre c, radius r) near the unit direction u (centre
// towards material): moves u towards the deepest line nearby (only by moves
// that gain), returns where c + t·u crosses into material (tGuess: where to
// start the search), and the contact's `normal` (the surface's, over ±2
// voxels round the crossing) and the burr's `depth` along it.
double sphereContact(const HapticScene& scene, const glm::dvec3& c, double r, glm::dvec3& u, double tGuess,
                     glm::dvec3& normal, double& depth);

// The shaft (axis c + y·R·ŷ for y in [y0, y1], radius rho): moves (y, phi) —
// the radial line from the axis at y towards R·(cos phi, 0, sin phi) — to where
// the crossing is nearest the axis; returns that t (the depth is rho − t).
// Where the axis at y is already in material (t < 0), the line turns to the
// shortest way out at its height and y to where that way is longest (a
// rigid shaft's escape, not the deepest line, which would run along a rim).
double deepestOnShaft(const HapticScene& scene, const glm::dvec3& c, const glm::dmat3& R, double rho, double y0,
                      double y1, double& y, double& phi, double tGuess);

// At most this many contacts are tracked at once (burr and shaft together).
constexpr int kMaxPointContacts = 6;

}  // namespace millsim
