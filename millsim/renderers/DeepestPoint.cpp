#include "millsim/renderers/DeepestPoint.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "millsim/haptics/HapticScene.h"
#include "millsim/math/Pose.h"

namespace millsim {

double lineCrossing(const HapticScene& scene, const glm::dvec3& o, const glm::dvec3& u, double t0, double tMin,
                    double tMax) {
  const double step = 0.5 * scene.voxelSize();
  double tAir = std::clamp(t0, tMin, tMax), sAir = scene.field(o + tAir * u);
  double tMat = tAir, sMat = sAir;
  if (sAir > 0.0) {  // in material: down to air
    for (;;) {
      if (tMat <= tMin) return tMin;
      tAir = std::max(tMin, tMat - step), sAir = scene.field(o + tAir * u);
      if (sAir <= 0.0) break;
      tMat = tAir, sMat = sAir;
    }
  } else {  // in air: up to material
    for (;;) {
      if (tAir >= tMax) return tMax;
      tMat = std::min(tMax, tAir + step), sMat = scene.field(o + tMat * u);
      if (sMat > 0.0) break;
      tAir = tMat, sAir = sMat;
    }
  }
  // Eq. 1's fraction between the bracket's samples, then once more inside the
  // narrowed bracket (regula falsi): the density is only piecewise linear.
  for (int i = 0;; ++i) {
    const double t = tAir + (tMat - tAir) * std::clamp(-sAir / (sMat - sAir), 0.0, 1.0);
    if (i == 1) return t;
    const double s = scene.field(o + t * u);
    if (s > 0.0) tMat = t, sMat = s;
    else tAir = t, sAir = s;
  }
}

namespace {

// Moves (a, b) to the least t(a, b) nearby: per scale, a parabola through
// t at ±step along each coordinate, and a Newton step to its vertex (at most
// two steps; off a ridge, two steps down its steeper side). A move must gain
// more than `gain`: where t is about as small along many lines (a burr in
// its own round pit) a tracked contact then stays put instead of wandering
// with the iso-surface's ripple.
template <class T>
double fitLeast(const T& t, double& a, double& b, double ta, const double* scales, int count, double stepA,
                double stepB, double gain) {
  for (int k = 0; k < count; ++k) {
    const double e[2] = {scales[k] * stepA, scales[k] * stepB};
    double move[2] = {0.0, 0.0}, side[3] = {a, b, ta};  // the best of the samples, should no step go downhill
    for (int i = 0; i < 2; ++i) {
      const double tp = i == 0 ? t(a + e[0], b) : t(a, b + e[1]), tm = i == 0 ? t(a - e[0], b) : t(a, b - e[1]);
      const double slope = (tp - tm) / (2.0 * e[i]), curve = (tp - 2.0 * ta + tm) / (e[i] * e[i]);
      if (curve > 0.0) move[i] = std::clamp(-slope / curve, -2.0 * e[i], 2.0 * e[i]);
      else if (tp != tm) move[i] = tp < tm ? 2.0 * e[i] : -2.0 * e[i];
      if (std::min(tp, tm) < side[2])
        side[0] = a + (i == 0 ? (tp < tm ? e[0] : -e[0]) : 0.0), side[1] = b + (i == 1 ? (tp < tm ? e[1] : -e[1]) : 0.0),
        side[2] = std::min(tp, tm);
    }
    if (move[0] == 0.0 && move[1] == 0.0) continue;
    // Downhill only (the whole step, else half of it, else the best sample):
    // a held pose then settles on one point instead of cycling round a kink.
    bool moved = false;
    for (const double f : {1.0, 0.5}) {
      const double tn = t(a + f * move[0], b + f * move[1]);
      if (!(tn < ta - gain)) continue;
      a += f * move[0], b += f * move[1], ta = tn, moved = true;
      break;
    }
    if (!moved && side[2] < ta - gain) a = side[0], b = side[1], ta = side[2];
  }
  return ta;
}

// Moves x to the most f(x) nearby: per scale a parabola through f at
// ±step, a move to its vertex (clamped to two steps) if that gains over the
// samples, else to the better sample if it gains.
template <class F>
double fitMost(const F& f, double& x, double fx, const double* scales, int count, double step) {
  for (int k = 0; k < count; ++k) {
    const double e = scales[k] * step, up = f(x + e), down = f(x - e);
    const double slope = (up - down) / (2.0 * e), curve = (up - 2.0 * fx + down) / (e * e);
    double move = 0.0;
    if (curve < 0.0) move = std::clamp(-slope / curve, -2.0 * e, 2.0 * e);
    else if (up != down) move = up > down ? 2.0 * e : -2.0 * e;
    if (move != 0.0) {
      const double fn = f(x + move);
      if (fn > fx && fn >= std::max(up, down)) {
        x += move, fx = fn;
        continue;
      }
    }
    if (std::max(up, down) > fx) x += up > down ? e : -e, fx = std::max(up, down);
  }
  return fx;
}

// Coarse steps to find the contact, then finer ones: where the depth has a
// kink (an edge), a fit's vertex is off the kink by up to its step.
constexpr double kFresh[] = {2.0, 2.0, 1.0, 0.5, 0.25, 0.1};
constexpr double kTracking[] = {0.5, 0.25, 0.1};
// What a tracked contact's move must gain (voxels): the iso-surface ripple's size.
constexpr double kGain = 0.02;
// How far a tracked burr line may turn in a frame (rad, about 3°): 3000°/s, far
// more than a hand turns the tool, so an edge's kink is still followed at once.
// In the §8.2 replay 0.02 and 0.05 both keep mill-and-lean's lean under 0.02 N
// a frame (none: 0.07 N); 0.05 also keeps the §8.2 lean under 0.05 N.
constexpr double kMaxTurn = 0.05;

}  // namespace

double sphereContact(const HapticScene& scene, const glm::dvec3& c, double r, glm::dvec3& u, double tGuess,
                     glm::dvec3& normal, double& depth) {
  const double h = scene.voxelSize(), tMax = r + 4.0 * h;
  {
    // Towards the deepest line nearby, each move gaining at least kGain
    // voxels: at an edge a line a few degrees off is much shallower, while in
    // a burr's own round pit, about as deep along many lines, u stays put.
    const Tangents basis = tangentsOf(u);
    const glm::dvec3 t1 = basis.t1, t2 = basis.t2;
    const glm::dvec3 u0 = u;
    double guess = tGuess;
    auto dir = [&](double a, double b) {
      return glm::normalize(u0 + std::tan(std::clamp(a, -1.2, 1.2)) * t1 + std::tan(std::clamp(b, -1.2, 1.2)) * t2);
    };
    auto t = [&](double a, double b) { return lineCrossing(scene, c, dir(a, b), guess, -r, tMax); };
    double a = 0.0, b = 0.0;
    const double first = t(0.0, 0.0);
    guess = first;
    const double angle = std::min(0.3, h / r);
    if (tGuess >= r) {
      fitLeast(t, a, b, first, kFresh, 6, angle, angle, 0.0);
      u = dir(a, b);
    } else {
      fitLeast(t, a, b, first, kTracking, 3, angle, angle, kGain * h);
      // A tracked line turns at most kMaxTurn a frame: where the material is
      // about as deep along many lines (a burr in its own round pit) the
      // deepest one hops several degrees at once as the tool moves, and the
      // force's direction would hop with it.
      const glm::dvec3 to = dir(a, b);
      const double turn = std::acos(std::clamp(glm::dot(u0, to), -1.0, 1.0));
      u = turn > kMaxTurn ? glm::normalize(u0 + (to - u0) * (kMaxTurn / turn)) : to;
    }
  }
  const double t0 = lineCrossing(scene, c, u, tGuess, -r, tMax);
  normal = -u, depth = r - t0;
  // The normal of the surface through the crossings of four lines two voxels
  // to each side: where the line meets a flat face it is the face's normal
  // wherever it meets it, and the one-voxel density ramp's iso-surface,
  // terraced with the voxel lattice (its local normal several degrees off
  // where the surface is oblique to the voxel axes), is averaged over ±2
  // voxels. Kept when all four lines meet material and it is within 30° of
  // the line (else a rim or a crease lies in between), faded out towards 40°
  // and towards the line's own depth of zero (below).
  if (!(t0 > 0.0 && t0 < r)) return t0;
  const Tangents basis = tangentsOf(u);
  const glm::dvec3 t1 = basis.t1, t2 = basis.t2;
  const double span = std::tan(std::min(0.6, 2.0 * h / t0));
  const glm::dvec3 side[4] = {t1, -t1, t2, -t2};
  glm::dvec3 q[4];
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3 d = glm::normalize(u + span * side[i]);
    const double ti = lineCrossing(scene, c, d, t0, -r, tMax);
    if (ti >= tMax) return t0;
    q[i] = c + ti * d;
  }
  glm::dvec3 n = glm::cross(q[0] - q[1], q[2] - q[3]);
  if (!(glm::length(n) > 0.0)) return t0;
  n = glm::normalize(n);
  if (glm::dot(n, u) < 0.0) n = -n;
  // Measured along the plane's normal, the depth is the line's plus
  // t0·(1 − cos δ), δ the plane's angle to the line: 17 µm at 15°, 67 µm at
  // 30°. At a milled pit's rim, where the plane spans the rim, that came and
  // went whole as the line's own depth crossed zero (the plane is not looked
  // for then) or δ crossed 30°: 21 µm, 0.05 N in one frame, and chatter in
  // half of the §8.2 replays at rates 1–1.5 % off 1 kHz. So the plane counts
  // in full from half a voxel of the line's depth and up to 30°, and fades
  // out to the line's depth and direction at zero depth and at 40°. (Fading
  // from 30° to 20° instead moved the normal of contacts that had kept it: a
  // 0.78 N push swung 4° a frame in the §8.2 lean.)
  constexpr double kFull = 30.0 * std::numbers::pi / 180.0, kFade = 10.0 * std::numbers::pi / 180.0;
  const double angle = std::acos(std::clamp(glm::dot(n, u), -1.0, 1.0));
  const double weight =
      std::clamp((r - t0) / (0.5 * h), 0.0, 1.0) * std::clamp((kFull + kFade - angle) / kFade, 0.0, 1.0);
  if (!(weight > 0.0)) return t0;
  normal = -glm::normalize(u + weight * (n - u));
  depth = (r - t0) + weight * t0 * (1.0 - glm::dot(u, n));  // the line's crossing, along the surface's normal
  return t0;
}

double deepestOnShaft(const HapticScene& scene, const glm::dvec3& c, const glm::dmat3& R, double rho, double y0,
                      double y1, double& y, double& phi, double tGuess) {
  const double h = scene.voxelSize(), tMax = rho + 4.0 * h;
  const glm::dvec3 axis = R * glm::dvec3(0, 1, 0);
  // The radial line at height yy towards angle p, searched from t = from down to tMin.
  auto crossing = [&](double yy, double p, double from, double tMin) {
    return lineCrossing(scene, c + std::clamp(yy, y0, y1) * axis, R * glm::dvec3(std::cos(p), 0.0, std::sin(p)), from,
                        tMin, tMax);
  };
  double guess = tGuess;
  auto line = [&](double yy, double p) { return crossing(yy, p, guess, -rho); };
  const bool fresh = tGuess >= rho;
  // A voxel across on the shaft's surface, and along it.
  const double angle = std::min(0.6, h / rho);
  // Where the axis itself is in material the nearest crossing of the radial
  // lines is behind the axis, and the deepest line no longer says which way
  // is out (it runs along the rim, where the material is longest): the fit
  // stays out of there, and a contact already there turns its line to the
  // shortest way out instead (below).
  auto t = [&](double yy, double p) {
    const double at = line(yy, p);
    return at < 0.0 ? tMax : at;
  };
  const double t0 = line(y, phi);
  if (t0 < 0.0) {
    // A rigid shaft leaves by the shortest way out at each height, and is
    // held by the height where that way is longest: alternately the line at
    // its height with the nearest crossing behind the axis, and the height
    // (along that line's direction) where the crossing is farthest behind.
    // Searched up to 3ρ behind the axis: depths up to 4ρ, beyond which the
    // push stops growing.
    auto behind = [&](double yy, double p) { return crossing(yy, p, 0.0, -3.0 * rho); };
    const double* scales = fresh ? kFresh : kTracking;
    const int count = fresh ? 6 : 3;
    double at = behind(y, phi);
    for (int round = 0; round < 2; ++round) {
      at = fitMost([&](double p) { return behind(y, p); }, phi, at, scales, count, angle);
      at = -fitMost([&](double yy) { return -behind(yy, phi); }, y, -at, scales, count, h);
      y = std::clamp(y, y0, y1);
    }
    return at;
  }
  guess = t0;
  const double tBest = fresh ? fitLeast(t, y, phi, t0, kFresh, 6, h, angle, 0.0)
                             : fitLeast(t, y, phi, t0, kTracking, 3, h, angle, 0.0);
  y = std::clamp(y, y0, y1);
  return tBest;
}

}  // namespace millsim
