#pragma once
// The paper's §8.2 procedure as a benchmark: a scene (by default the default
// lesson) replayed in simulated time through its trajectory, every frame
// timed on the haptic thread's CPU clock and classed by phase:
//  - free: no contact;
//  - contact: in contact, button off, the tool within 5° of upright;
//  - lean: in contact, button off, the tool leaning 5° or more (the shaft on
//    the hole's edge);
//  - milling: in contact with the button held (upright or leaning).
// Per phase: p50 / p99 / p99.9 / max, next to a constant-work control of the
// phase's median length timed in the same run (what the machine adds to any
// frame that long). And the brute-force variant of a milling frame: the
// renderer compiled afresh against a new scene over the milled volumes (#3
// builds its point shells again from the voxels), on every Nth milling frame,
// to set beside the incremental update.
#include <string>
#include <vector>

#include "measure/ConstantWork.h"
#include "measure/Renderers.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::measure {

struct ProcedurePhase {
  std::string name;  // free, contact, lean, milling, all
  long frames = 0;
  FrameTimes cpu;      // µs, thread CPU time of each frame (device, step, mill, publish)
  FrameTimes control;  // constant work of length cpu.p50, same run
};

struct ProcedureResult {
  std::string renderer, resolution;
  std::vector<ProcedurePhase> phases;
  long bruteSamples = 0;
  FrameTimes brute;        // µs, compiling the renderer afresh on sampled milling frames
  long preempted = 0;      // frames whose wall time exceeded their CPU time by > 10 µs
  int maxContacts = 0;
  double removedMm3 = 0.0;
};

// Throws std::runtime_error if the scene does not load or has no device.
// `overrides`: fields set on the scene as `--set` does (bench resolution's voxel size).
ProcedureResult measureProcedure(const RendererSpec& spec, const std::string& label, const std::string& scenePath,
                                 const std::string& trajectoryPath, long bruteEvery = 100,
                                 const std::vector<LoadOptions::FieldOverride>& overrides = {});

}  // namespace millsim::measure
