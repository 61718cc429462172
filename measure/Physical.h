#pragma once
// The physical accuracy suite (docs/accuracy.md, "Physical reference"): every
// renderer pressed into the physical scenes at voxel size h and compared with
// the constrained pose of the rigid tool (measure/PhysicalReference.h), the
// reference's stiffness being the one the renderer is felt to have.
#include <iosfwd>
#include <string>
#include <vector>

#include "measure/Renderers.h"

namespace millsim::measure {

struct PhysicalConfig {
  std::vector<std::string> scenes;  // empty: every physicalSceneNames()
  int phases = 2;
  int approachFrames = 40;  // steps from the approach start to the held pose
  // Steps held there, until the output rests (a frame changes the force by
  // at most restForce and the torque by at most restTorque) but at least
  // minSettleFrames and at most settleFrames; the last output is compared.
  // At most 0.6 s at 1 kHz: #3's coupled tool slides off an edge's saddle for
  // longer than 60 frames (its edge at h = 0.05 mm: 11.4° after 60 frames,
  // 1.4° at rest); #1 and #2 rest within 60.
  int minSettleFrames = 60;
  int settleFrames = 600;
  double restForce = 1e-9;    // N
  double restTorque = 1e-12;  // N·m
  // Not null: one CSV row per pose (physicalPoseCsvHeader()), to see which
  // poses make a scene's error.
  std::ostream* poses = nullptr;
};

struct PhysicalRow {
  std::string renderer;
  std::string resolution = "default";  // "default", or the swept "field=value"
  double h = 0.0;            // m
  std::string scene;         // a scene name or "all"
  int poses = 0;
  double feltStiffness = 0;  // N/m: renderedStiffness between 0.05 and 0.15 mm past first contact, the reference's k
  double angularStiffness = 0;  // N·m/rad the reference's kr; ∞: orientation held at the device's
  // |(|F| − |F_ref|)| / max(|F_ref|, F_floor), F_floor = k_felt·0.05 mm.
  double forceRms = 0, forceP95 = 0;
  double directionRms = 0, directionP95 = 0;  // degrees between F and F_ref (both non-zero)
  double missed = 0;         // fraction of poses with F_ref ≥ F_floor and no force at all
  double torqueRms = 0;      // |T − T_ref| / (max(|F_ref|, F_floor)·max(arm_ref, tip radius))
  double armRms = 0;         // mm: | |T|/|F| − |T_ref|/|F_ref| |, both forces ≥ F_floor
  double armRelRms = 0;      // the same over arm_ref, shaft contacts only (NaN without)
  // mm: distance from the reference's single contact point to the renderer's line of
  // action (its torque taken about its drawn burr centre); single-contact poses, F ≥ F_floor.
  double lineRms = 0;
  double drawnRms = 0;       // voxels: drawn burr centre against the constrained one
  double drawnDegRms = 0;    // degrees: drawn orientation against the constrained one
  double p50Us = 0, p99Us = 0;  // per-frame compute time over the held frames
  double refViolation = 0;   // m: the reference's largest remaining penetration
  bool refConverged = true;  // every reference pose met its tolerance
};

// One renderer configuration at one voxel size: a row per scene and one for "all".
std::vector<PhysicalRow> measurePhysical(const RendererSpec& spec, double h, const PhysicalConfig& config = {});

std::string physicalCsvHeader();
// The per-pose rows' columns (PhysicalConfig::poses): forces in N, torques in N·m, lengths in mm.
std::string physicalPoseCsvHeader();
std::string toCsv(const PhysicalRow& r);

}  // namespace millsim::measure
