#pragma once
// The accuracy suite (docs/accuracy.md): quasi-static poses against analytic
// scenes voxelised at spacing h, each renderer's output compared with a
// reference computed from the exact geometry with that renderer's own force
// law (ReferenceKind), and the frame time measured alongside.
#include <string>
#include <vector>

#include "measure/Renderers.h"

namespace millsim::measure {

// How a renderer's reference is computed from the exact geometry, and which
// resolution fields are swept, is declared by the renderer node
// (RendererTraits::reference and ::resolutionSweeps; rendererTraits(type)).
using ReferenceKind = millsim::ReferenceKind;

struct AccuracyConfig {
  std::vector<std::string> scenes{"half-space", "sphere", "cavity", "edge", "plate"};
  std::vector<double> tiltsDeg{0, 15, 30, 45, 60};
  int depths = 6;          // 0.5h, 1h, ..., 3h
  int phases = 2;          // sub-voxel offsets of the contact point
  int settleFrames = 20;   // frames held at each pose (timed)
};

struct AccuracyRow {
  std::string renderer;   // type
  std::string resolution; // "field=value" or "default"
  double h = 0.0;         // m
  std::string scene;      // a scene name or "all"
  int poses = 0, counted = 0;  // counted: poses with a force error sample
  double forceRms = 0, forceP95 = 0;        // |F − F_ref| / max(|F_ref|, 0.5 N)
  double directionRms = 0, directionP95 = 0;  // degrees
  double torqueRms = 0, torqueP95 = 0;      // |τ − τ_ref| / (max(reaction, 0.5 N)·lever)
  double drawnRms = 0, drawnP95 = 0;        // voxels
  double p50Us = 0, p99Us = 0;              // per-frame compute time
};

// One renderer configuration at one voxel size: a row per scene and one for "all".
std::vector<AccuracyRow> measureAccuracy(const RendererSpec& spec, double h, const AccuracyConfig& config,
                                         const std::string& resolutionLabel = "default");

std::string accuracyCsvHeader();
std::string toCsv(const AccuracyRow& r);

// Order p of err ∝ x^p fitted by least squares on log–log (NaN with < 2 usable points).
double convergenceOrder(const std::vector<double>& x, const std::vector<double>& err);

}  // namespace millsim::measure
