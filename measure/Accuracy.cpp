#include "measure/Accuracy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include <glm/geometric.hpp>

#include "measure/AnalyticScene.h"
#include "measure/Statistics.h"
#include "millsim/renderers/ContactShares.h"

namespace millsim::measure {

namespace {

using Sdf = std::function<double(const glm::dvec3&)>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMinForce = 0.5;  // N: the notes' threshold, used as the floor of the normaliser

glm::dvec3 gradient(const Sdf& f, const glm::dvec3& p) {
  const double e = 1e-8;
  return glm::dvec3(f(p + glm::dvec3(e, 0, 0)) - f(p - glm::dvec3(e, 0, 0)),
                    f(p + glm::dvec3(0, e, 0)) - f(p - glm::dvec3(0, e, 0)),
                    f(p + glm::dvec3(0, 0, e)) - f(p - glm::dvec3(0, 0, e))) /
         (2.0 * e);
}

// First point of the segment a → b where f ≤ level, by sphere tracing (f is a
// distance or a lower bound of one); b if the segment never gets there.
glm::dvec3 entryAlong(const Sdf& f, const glm::dvec3& a, const glm::dvec3& b, double level) {
  const double len = glm::length(b - a);
  const glm::dvec3 u = (b - a) / len;
  double t = 0.0;
  for (int i = 0; i < 10000 && t < len; ++i) {
    const double s = f(a + u * t) - level;
    if (s <= 1e-12) return a + u * t;
    t += std::max(s, 1e-10);
  }
  return b;
}

// Where the segment from p (inside) towards c leaves the material (eq. 14's a_i end).
glm::dvec3 exitTowards(const Sdf& f, const glm::dvec3& p, const glm::dvec3& c) {
  const double len = glm::length(c - p);
  const glm::dvec3 u = (c - p) / len;
  double t = 0.0;
  for (int i = 0; i < 10000 && t < len; ++i) {
    const double s = f(p + u * t);
    if (s >= -1e-12) return p + u * t;
    t += std::max(-s, 1e-10);
  }
  return c;
}

// The surface point closest to q (Newton steps along the exact gradient).
glm::dvec3 closestPoint(const Sdf& f, glm::dvec3 q) {
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3 g = gradient(f, q);
    const double gg = glm::dot(g, g);
    if (!(gg > 0.0)) break;
    q -= f(q) * g / gg;
  }
  return q;
}

struct ProbePose {
  Pose device;
  glm::dvec3 start;  // approach start, in free space
  bool shaftScene = false;
};

struct Reference {
  glm::dvec3 force{0.0}, torque{0.0}, drawn{0.0};
  double reaction = 0.0;  // |F_ref| + shaft reaction, N
  double lever = 0.0;     // m
  bool torqueKnown = true;
  bool valid = true;      // false: the pose is outside the law's domain (a hold rule would apply)
};

double fieldValue(const HapticsRendererNode& n, const std::vector<std::string>& names, double fallback) {
  for (const auto& name : names)
    if (Field* f = n.field(name)) return std::stod(f->toString());
  return fallback;
}

// `proxyRadius` (Proxy): how far from the surface the proxy is held — 0 for
// the paper's centre vertex, the burr radius for a proxy that feels the burr's
// surface (LineProxyRenderer's default, feelBurrSurface). `shaftSurface`
// (Proxy): the shaft's deepest point pushes k times its depth past the
// shaft's radius (feelShaftSurface) instead of eq. 7–11's torque only.
Reference reference(ReferenceKind kind, const Sdf& f, const ProbePose& pp, const ToolGeometry& tool, double k,
                    double proxyRadius = 0.0, bool shaftSurface = false, int sphereQuadrature = 4000,
                    int sliceQuadrature = 200, int ringQuadrature = 32) {
  Reference ref;
  const glm::dvec3 c = pp.device.position, dir = pp.device.shaftDirection();
  // The burr touching the exact surface on the approach path (drawn tool, coupling).
  // (Along the path, not by the sign at c: past a thin plate the device is outside again.)
  const glm::dvec3 touching = entryAlong(f, pp.start, c, tool.tipRadius);
  ref.drawn = touching;
  if (kind == ReferenceKind::Proxy) {
    const glm::dvec3 proxy = entryAlong(f, pp.start, c, proxyRadius);
    ref.force = k * (proxy - c);
    // The shaft from the tip proxy: its deepest point is the probe, and its
    // proxy the closest surface point (eq. 7–11 at the exact intersection).
    double deepest = 0.0, tBest = 0.0;
    const int n = 4000;
    for (int i = 1; i <= n; ++i) {
      const double t = tool.shaftLength * i / n, s = f(proxy + dir * t);
      if (s < deepest) deepest = s, tBest = t;
    }
    double shaftReaction = 0.0;
    if (shaftSurface) {
      // The shaft's surface, from where it leaves the burr sphere: its
      // deepest point pushes along the surface's normal there.
      const double y0 = std::sqrt(std::max(0.0, tool.tipRadius * tool.tipRadius - tool.shaftRadius * tool.shaftRadius));
      double least = tool.shaftRadius, tLeast = 0.0;
      for (int i = 0; i <= n; ++i) {
        const double t = y0 + (tool.shaftLength - y0) * i / n, s = f(proxy + dir * t);
        if (s < least) least = s, tLeast = t;
      }
      if (least < tool.shaftRadius) {
        const glm::dvec3 axis = proxy + dir * tLeast, normal = glm::normalize(gradient(f, axis));
        // The burr's push and the shaft's share one push, as the renderer's do.
        const glm::dvec3 burrPush = proxy - c;
        const BurrShaftShares shares = burrAndShaftShares(burrPush, normal, tool.shaftRadius - least);
        if (glm::length(burrPush) > 0.0)
          ref.force = k * shares.burr * (burrPush / glm::length(burrPush));
        const glm::dvec3 push = k * shares.shaft * normal;
        const glm::dvec3 r = axis - least * normal - proxy;  // the surface point nearest the axis
        ref.force += push;
        ref.torque = glm::cross(r, push);
        shaftReaction = glm::length(push);
        ref.lever = glm::length(r);
      }
    } else if (deepest < 0.0) {
      const glm::dvec3 ip = closestPoint(f, proxy + dir * tBest);
      const glm::dvec3 r = ip - proxy, g = ip - (proxy + glm::length(r) * dir);
      ref.torque = glm::cross(r, k * g);
      shaftReaction = k * glm::length(g);
      ref.lever = glm::length(r);
    }
    ref.reaction = glm::length(ref.force) + shaftReaction;
  } else if (kind == ReferenceKind::Penalty) {
    if (f(c) < 0.0) ref.valid = false;  // eq. 17 would hold the previous force
    // Eq. 14–16 in the continuum limit: the mean over the sphere of a(p).
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    glm::dvec3 sum(0.0);
    for (int i = 0; i < sphereQuadrature; ++i) {
      const double y = 1.0 - 2.0 * (i + 0.5) / sphereQuadrature, rr = std::sqrt(std::max(0.0, 1.0 - y * y));
      const glm::dvec3 p = c + tool.tipRadius * glm::dvec3(rr * std::cos(golden * i), y, rr * std::sin(golden * i));
      if (f(p) < 0.0) sum += exitTowards(f, p, c) - p;
    }
    ref.force = k * sum / double(sphereQuadrature);
    // Eq. 18–21 in the continuum limit along the shaft and around each ring.
    const glm::dvec3 e1 = glm::normalize(glm::cross(dir, std::abs(dir.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1)));
    const glm::dvec3 e2 = glm::cross(dir, e1);
    const double y0 = std::sqrt(std::max(0.0, tool.tipRadius * tool.tipRadius - tool.shaftRadius * tool.shaftRadius));
    glm::dvec3 total(0.0);
    for (int j = 0; j < sliceQuadrature; ++j) {
      const double y = y0 + (tool.shaftLength - y0) * (j + 0.5) / sliceQuadrature;
      const glm::dvec3 centre = c + dir * y;
      glm::dvec3 reaction(0.0);
      for (int i = 0; i < ringQuadrature; ++i) {
        const double a = 2.0 * std::numbers::pi * i / ringQuadrature;
        const glm::dvec3 p = centre + tool.shaftRadius * (std::cos(a) * e1 + std::sin(a) * e2);
        if (f(p) < 0.0) reaction += exitTowards(f, p, centre) - p;
      }
      if (reaction != glm::dvec3(0.0) && f(centre) < 0.0) ref.valid = false;  // eq. 19 would hold
      reaction *= k / ringQuadrature;
      ref.torque += glm::cross(centre - c, reaction) / double(sliceQuadrature);
      total += reaction / double(sliceQuadrature);
    }
    const double shaftReaction = glm::length(total);
    ref.lever = shaftReaction > 0.0 ? glm::length(ref.torque) / shaftReaction : 0.0;
    ref.reaction = glm::length(ref.force) + shaftReaction;
  } else {
    ref.force = k * (touching - c);
    ref.reaction = glm::length(ref.force);
    ref.torqueKnown = !pp.shaftScene;  // a coupled tool's shaft contact is not modelled here
  }
  if (ref.lever <= 0.0) ref.lever = tool.tipRadius;
  return ref;
}

// The quasi-static poses of one scene at voxel size h. `tipOffset` /
// `shaftOffset`: the height above a surface at which the burr / shaft is felt.
std::vector<ProbePose> poses(const std::string& scene, double h, const AccuracyConfig& cfg, double tipOffset,
                             double shaftOffset) {
  std::vector<ProbePose> out;
  const double maxTip = tipOffset > 0.0 ? 0.8 * tipOffset : 1e9, maxShaft = shaftOffset > 0.0 ? 0.8 * shaftOffset : 1e9;
  for (int di = 0; di < cfg.depths; ++di) {
    const double d = (0.5 + 0.5 * di) * h;
    for (double tiltDeg : cfg.tiltsDeg)
      for (int ph = 0; ph < cfg.phases; ++ph) {
        const double shift = h * ph / cfg.phases, tilt = tiltDeg * kRadiansPerDegree;
        ProbePose pp;
        glm::dvec3 n, contact;  // outward normal of the material and the contact point
        if (scene == "edge") {
          if (d > maxShaft) continue;
          // The shaft leans over the edge (the Z axis), the burr stays clear.
          const double th = std::max(tilt, 15.0 * kRadiansPerDegree), s = 2.5e-3, rho = shaftOffset - d;
          const glm::dvec3 dir(-std::sin(th), std::cos(th), 0.0), perp(std::cos(th), std::sin(th), 0.0);
          const glm::dvec3 c = perp * rho - dir * s + glm::dvec3(0, 0, shift);
          pp.device = Pose{c, rotationBetween({0, 1, 0}, dir)};
          pp.start = c + perp * 1.5e-3;
          pp.shaftScene = true;
          out.push_back(pp);
          continue;
        }
        if (d > maxTip) continue;
        if (scene == "half-space" || scene == "plate") {
          n = {0, 1, 0};
          contact = {shift, scene == "plate" ? h : 0.0, 0.5 * shift};
        } else if (scene == "sphere") {
          n = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));
          contact = 2e-3 * n;
        } else {  // cavity: the wall of a 2 mm bowl, pressed down and sideways
          n = -glm::normalize(glm::dvec3(0.35, -1.0, 0.0));
          contact = -2e-3 * n;
        }
        const glm::dvec3 t = glm::normalize(glm::cross(n, glm::dvec3(0, 0, 1)));
        const glm::dvec3 dir = std::cos(tilt) * n + std::sin(tilt) * t;
        const glm::dvec3 c = contact + n * (tipOffset - d);
        pp.device = Pose{c, rotationBetween({0, 1, 0}, dir)};
        pp.start = c + n * (d + 1.5e-3);
        out.push_back(pp);
      }
  }
  return out;
}

Shape sceneShape(const std::string& name, double h) {
  if (name == "half-space") return halfSpace({-3e-3, -2e-3, -3e-3}, {3e-3, 1.5e-3, 3e-3});
  if (name == "sphere") return ball(2e-3);
  if (name == "cavity")
    return {"cavity", [](const glm::dvec3& p) { return std::max(p.y, 2e-3 - glm::length(p)); },
            {-3.5e-3, -3.5e-3, -3.5e-3}, {3.5e-3, 1e-3, 3.5e-3}};
  if (name == "edge") return edge({-2e-3, -2e-3, -1.5e-3}, {1e-3, 1e-3, 1.5e-3});
  if (name == "plate") return plate(2.0 * h, {-3e-3, -1.5e-3, -3e-3}, {3e-3, 1.5e-3, 3e-3});
  throw std::runtime_error("unknown accuracy scene '" + name + "' (half-space, sphere, cavity, edge, plate)");
}

struct Samples {
  std::vector<double> force, direction, torque, drawn, us;
  int poses = 0;
};

AccuracyRow summarise(const std::string& type, const std::string& res, double h, const std::string& scene,
                      const Samples& s) {
  AccuracyRow r{type, res, h, scene, s.poses, int(s.force.size())};
  r.forceRms = rms(s.force), r.forceP95 = percentile(s.force, 0.95);
  r.directionRms = rms(s.direction), r.directionP95 = percentile(s.direction, 0.95);
  r.torqueRms = rms(s.torque), r.torqueP95 = percentile(s.torque, 0.95);
  r.drawnRms = rms(s.drawn), r.drawnP95 = percentile(s.drawn, 0.95);
  r.p50Us = percentile(s.us, 0.5), r.p99Us = percentile(s.us, 0.99);
  return r;
}

}  // namespace

std::vector<AccuracyRow> measureAccuracy(const RendererSpec& spec, double h, const AccuracyConfig& cfg,
                                         const std::string& resolution) {
  auto node = makeRenderer(spec);
  const ToolGeometry tool = standardTool();
  const RendererTraits traits = node->traits();
  const ReferenceKind kind = traits.reference;
  // The reference's spring: the declared stiffness field's value (1000 N/m if none is declared).
  const double k = traits.stiffnessField.empty() ? 1000.0 : fieldValue(*node, {traits.stiffnessField}, 1000.0);
  const double tipOffset = contactOffset(*node, tool, h), shaftOffset = tipOffset * tool.shaftRadius / tool.tipRadius;
  // A proxy renderer felt about a burr radius above the surface holds its
  // proxy against the surface dilated by the burr (the radius, not the
  // measured offset, which is only resolved to 0.01 h).
  const double proxyRadius = tipOffset > 0.5 * tool.tipRadius ? tool.tipRadius : 0.0;
  const Field* shaftField = node->field("feelShaftSurface");
  const bool shaftSurface = shaftField && shaftField->toString() == "true";
  std::vector<AccuracyRow> rows;
  Samples all;
  for (const std::string& name : cfg.scenes) {
    auto scene = voxelise(sceneShape(name, h), h);
    const Sdf& f = scene->shape.distance;
    Samples s;
    for (const ProbePose& pp : poses(name, h, cfg, tipOffset, shaftOffset)) {
      const Reference ref = reference(kind, f, pp, tool, k, proxyRadius, shaftSurface);
      if (!ref.valid) continue;
      ++s.poses;
      auto algorithm = node->compile(tool, *scene->scene);
      algorithm->reset(Pose{pp.start, pp.device.orientation});
      HapticOutput out;
      for (int i = 1; i <= 40; ++i)
        out = algorithm->step(*scene->scene, HapticInput{Pose{pp.start + (pp.device.position - pp.start) * (i / 40.0),
                                                              pp.device.orientation}, 1e-3});
      for (int i = 0; i < cfg.settleFrames; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        out = algorithm->step(*scene->scene, HapticInput{pp.device, 1e-3});
        s.us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
      }
      // Relative to |F_ref|, or to 0.5 N for smaller references (no division blow-up near first contact).
      const double fr = glm::length(ref.force);
      if (fr > 0.0 || glm::length(out.force) > 0.0) s.force.push_back(glm::length(out.force - ref.force) / std::max(fr, kMinForce));
      if (fr >= 0.05) {
        const double fo = glm::length(out.force);
        s.direction.push_back(fo > 0.0 ? std::acos(std::clamp(glm::dot(out.force, ref.force) / (fo * fr), -1.0, 1.0)) / kRadiansPerDegree
                                        : 180.0);
      }
      if (ref.torqueKnown && (ref.reaction > 0.0 || glm::length(out.torque) > 0.0))
        s.torque.push_back(glm::length(out.torque - ref.torque) / (std::max(ref.reaction, kMinForce) * ref.lever));
      if (!pp.shaftScene) s.drawn.push_back(glm::length(out.drawnTool.position - ref.drawn) / h);
    }
    rows.push_back(summarise(spec.type, resolution, h, name, s));
    auto append = [](std::vector<double>& a, const std::vector<double>& b) { a.insert(a.end(), b.begin(), b.end()); };
    append(all.force, s.force), append(all.direction, s.direction), append(all.torque, s.torque);
    append(all.drawn, s.drawn), append(all.us, s.us);
    all.poses += s.poses;
  }
  rows.push_back(summarise(spec.type, resolution, h, "all", all));
  return rows;
}

std::string accuracyCsvHeader() {
  return "renderer,resolution,h_mm,scene,poses,counted,force_rms,force_p95,dir_rms_deg,dir_p95_deg,torque_rms,"
         "torque_p95,drawn_rms_vox,drawn_p95_vox,p50_us,p99_us";
}

std::string toCsv(const AccuracyRow& r) {
  std::ostringstream o;
  o.precision(4);
  o << r.renderer << "," << r.resolution << "," << r.h * 1e3 << "," << r.scene << "," << r.poses << "," << r.counted
    << "," << r.forceRms << "," << r.forceP95 << "," << r.directionRms << "," << r.directionP95 << "," << r.torqueRms
    << "," << r.torqueP95 << "," << r.drawnRms << "," << r.drawnP95 << "," << r.p50Us << "," << r.p99Us;
  return o.str();
}

double convergenceOrder(const std::vector<double>& x, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size() && i < err.size(); ++i) {
    if (!(x[i] > 0.0) || !(err[i] > 0.0) || !std::isfinite(err[i])) continue;
    const double lx = std::log(x[i]), ly = std::log(err[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++n;
  }
  if (n < 2 || sxx * n - sx * sx <= 0.0) return kNaN;
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace millsim::measure
