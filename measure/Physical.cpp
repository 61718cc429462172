#include "measure/Physical.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <ostream>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "measure/PhysicalScenes.h"
#include "measure/Statistics.h"

namespace millsim::measure {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kFloorDepth = 0.05e-3;  // m: forces are normalised by at least k_felt times this
// m past first contact: the felt stiffness is the slope between these depths on a flat face, the same at every h.
constexpr double kFeltDepth1 = 0.05e-3, kFeltDepth2 = 0.15e-3;

double numericField(const HapticsRendererNode& n, const std::string& name) {
  if (Field* f = n.field(name)) return std::stod(f->toString());
  return kNaN;
}

// The reference's rotational stiffness for this renderer, scaled like its
// translational one: a renderer with a rotational coupling (the field
// angularCouplingStiffness, over its declared stiffness) keeps its ratio; the
// others draw and press with the device's orientation, so the reference holds it (∞).
double angularStiffness(const HapticsRendererNode& n, double kFelt) {
  const RendererTraits t = n.traits();
  const double kr = numericField(n, "angularCouplingStiffness");
  const double k = t.stiffnessField.empty() ? kNaN : numericField(n, t.stiffnessField);
  if (std::isfinite(kr) && kr > 0.0 && std::isfinite(k) && k > 0.0) return kFelt * kr / k;
  return std::numeric_limits<double>::infinity();
}

struct Samples {
  std::vector<double> force, direction, torque, arm, armRel, line, drawn, drawnDeg, us;
  int poses = 0, missed = 0, pressed = 0;
  double violation = 0.0;
  bool converged = true;
  void append(const Samples& o) {
    for (auto [a, b] : {std::pair{&force, &o.force}, {&direction, &o.direction}, {&torque, &o.torque},
                        {&arm, &o.arm}, {&armRel, &o.armRel}, {&line, &o.line}, {&drawn, &o.drawn}, {&drawnDeg, &o.drawnDeg},
                        {&us, &o.us}})
      a->insert(a->end(), b->begin(), b->end());
    poses += o.poses, missed += o.missed, pressed += o.pressed;
    violation = std::max(violation, o.violation), converged = converged && o.converged;
  }
};

PhysicalRow summarise(const std::string& type, double h, const std::string& scene, double k, double kr,
                      const Samples& s) {
  PhysicalRow r;
  r.renderer = type, r.h = h, r.scene = scene, r.poses = s.poses, r.feltStiffness = k, r.angularStiffness = kr;
  r.forceRms = rms(s.force), r.forceP95 = percentile(s.force, 0.95);
  r.directionRms = rms(s.direction), r.directionP95 = percentile(s.direction, 0.95);
  r.missed = s.pressed > 0 ? double(s.missed) / s.pressed : kNaN;
  r.torqueRms = rms(s.torque), r.armRms = rms(s.arm), r.armRelRms = rms(s.armRel), r.lineRms = rms(s.line);
  r.drawnRms = rms(s.drawn), r.drawnDegRms = rms(s.drawnDeg);
  r.p50Us = percentile(s.us, 0.5), r.p99Us = percentile(s.us, 0.99);
  r.refViolation = s.violation, r.refConverged = s.converged;
  return r;
}

}  // namespace

std::vector<PhysicalRow> measurePhysical(const RendererSpec& spec, double h, const PhysicalConfig& cfg) {
  auto node = makeRenderer(spec);
  const ToolGeometry tool = standardTool();
  const double k = renderedStiffness(*node, tool, h, kFeltDepth1, kFeltDepth2), kr = angularStiffness(*node, k);
  const double floor = k * kFloorDepth;
  const std::vector<std::string> names = cfg.scenes.empty() ? physicalSceneNames() : cfg.scenes;
  std::vector<PhysicalRow> rows;
  Samples all;
  for (const std::string& name : names) {
    const PhysicalScene ps = physicalScene(name);
    auto scene = voxelisePhysical(ps, h);
    Samples s;
    for (const PhysicalProbe& probe : physicalProbes(ps, tool, h, cfg.phases)) {
      const PhysicalPose found = constrainedPose(ps.material, tool, probe.device, {k, kr});
      s.violation = std::max(s.violation, found.violation), s.converged = s.converged && found.converged;
      ++s.poses;
      auto algorithm = node->compile(tool, *scene->scene);
      algorithm->reset(Pose{probe.start, probe.device.orientation});
      HapticOutput out;
      for (int i = 1; i <= cfg.approachFrames; ++i)
        out = algorithm->step(*scene->scene,
                              HapticInput{Pose{probe.start + (probe.device.position - probe.start) *
                                                                 (double(i) / cfg.approachFrames),
                                               probe.device.orientation},
                                          1e-3});
      for (int i = 0; i < cfg.settleFrames; ++i) {
        const HapticOutput last = out;
        const auto t0 = std::chrono::steady_clock::now();
        out = algorithm->step(*scene->scene, HapticInput{probe.device, 1e-3});
        s.us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
        const bool still = glm::length(out.force - last.force) <= cfg.restForce &&
                           glm::length(out.torque - last.torque) <= cfg.restTorque;
        if (i + 1 >= cfg.minSettleFrames && still) break;
      }
      // Where the rigid tool has poses exactly as near (either face past an
      // edge's bisector), the renderer is measured against the one it took.
      const PhysicalPose* nearest = &found;
      for (const PhysicalPose& alt : found.alternatives)
        if (glm::dot(alt.force, out.force) > glm::dot(nearest->force, out.force)) nearest = &alt;
      const PhysicalPose& ref = *nearest;
      const double fr = glm::length(ref.force), fo = glm::length(out.force);
      s.force.push_back(std::abs(fo - fr) / std::max(fr, floor));
      if (fr >= floor) {
        ++s.pressed;
        if (fo > 0.0) s.direction.push_back(std::acos(std::clamp(glm::dot(out.force, ref.force) / (fo * fr), -1.0, 1.0)) / kRadiansPerDegree);
        else ++s.missed;
      }
      s.torque.push_back(glm::length(out.torque - ref.torque) /
                         (std::max(fr, floor) * std::max(ref.momentArm, tool.tipRadius)));
      if (fr >= floor && fo >= floor) {
        const double arm = glm::length(out.torque) / fo;
        s.arm.push_back((arm - ref.momentArm) * 1e3);
        if (ps.shaftContact) s.armRel.push_back((arm - ref.momentArm) / ref.momentArm);
        if (ref.contacts.size() == 1) {
          const glm::dvec3 axis = out.force / fo;
          const glm::dvec3 onLine = out.drawnTool.position + glm::cross(out.force, out.torque) / (fo * fo);
          s.line.push_back(glm::length(glm::cross(ref.contacts[0].point - onLine, axis)) * 1e3);
        }
      }
      s.drawn.push_back(glm::length(out.drawnTool.position - ref.pose.position) / h);
      s.drawnDeg.push_back(glm::length(rotationVector(out.drawnTool.orientation * glm::inverse(ref.pose.orientation))) /
                           kRadiansPerDegree);
      if (cfg.poses) {
        const glm::dvec3 axis = probe.device.orientation * glm::dvec3(0, 1, 0);
        auto v = [](const glm::dvec3& x) {
          std::ostringstream o;
          o.precision(5);
          o << x.x << "," << x.y << "," << x.z;
          return o.str();
        };
        std::ostringstream row;
        row.precision(5);
        row << spec.type << "," << h * 1e3 << "," << name << "," << s.poses - 1 << "," << probe.depth * 1e3 << ","
            << v(probe.device.position * 1e3) << "," << v(axis) << "," << v(out.force) << "," << v(ref.force) << ","
            << v(out.torque) << "," << v(ref.torque) << "," << ref.contacts.size() << "," << out.contacts << ","
            << s.force.back() << "," << (fr >= floor && fo > 0.0 ? s.direction.back() : kNaN) << ","
            << s.torque.back() << "," << s.drawn.back() << "\n";
        *cfg.poses << row.str();
      }
    }
    rows.push_back(summarise(spec.type, h, name, k, kr, s));
    all.append(s);
  }
  rows.push_back(summarise(spec.type, h, "all", k, kr, all));
  return rows;
}

std::string physicalCsvHeader() {
  return "renderer,resolution,h_mm,scene,poses,felt_k,felt_kr,force_rms,force_p95,dir_rms_deg,dir_p95_deg,missed,torque_rms,"
         "arm_rms_mm,arm_rel_rms,line_rms_mm,drawn_rms_vox,drawn_rms_deg,p50_us,p99_us,ref_violation_m,ref_converged";
}

std::string physicalPoseCsvHeader() {
  return "renderer,h_mm,scene,pose,depth_mm,device_x_mm,device_y_mm,device_z_mm,axis_x,axis_y,axis_z,fx,fy,fz,ref_fx,"
         "ref_fy,ref_fz,tx,ty,tz,ref_tx,ref_ty,ref_tz,ref_contacts,contacts,force_err,dir_err_deg,torque_err,drawn_vox";
}

std::string toCsv(const PhysicalRow& r) {
  std::ostringstream o;
  o.precision(4);
  o << r.renderer << "," << r.resolution << "," << r.h * 1e3 << "," << r.scene << "," << r.poses << "," << r.feltStiffness << ","
    << r.angularStiffness << "," << r.forceRms << "," << r.forceP95 << "," << r.directionRms << ","
    << r.directionP95 << "," << r.missed << "," << r.torqueRms << "," << r.armRms << "," << r.armRelRms << "," << r.lineRms << ","
    << r.drawnRms << "," << r.drawnDegRms << "," << r.p50Us << "," << r.p99Us << "," << r.refViolation << ","
    << (r.refConverged ? 1 : 0);
  return o.str();
}

}  // namespace millsim::measure
