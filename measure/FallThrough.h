#pragma once
// Fall-through: the tool driven kinematically (the device moves at a fixed
// speed whatever the force, the worst case) straight through a plate.
//  - held: after first contact the force never pushes along the motion, it
//    still resists at the end, with the burr centre well past the plate, and a
//    reported proxy (HapticOutput::proxy) never crosses the plate's midplane —
//    the renderer remembers the plate (proxy and coupling methods must);
//  - detected: the first frame with a force pushes back (a penalty method,
//    which has no memory, at least felt the plate on its near side).
// Each speed is run at several phases of the frame grid against the plate,
// since where the samples fall decides whether a thin plate is seen.
#include <string>
#include <vector>

#include "measure/Renderers.h"

namespace millsim::measure {

struct FallThroughResult {
  std::string renderer;
  double thickness = 0.0, speed = 0.0;  // m, m/s
  int phases = 0;
  bool held = true, detected = true;    // at every phase
  double lowestProxy = 0.0;    // m: the lowest reported proxy height (plate midplane at 0), NaN if none
  double minPeakResist = 0.0;  // N: the smallest (over phases) largest resisting force before the midplane
  std::string firstFailure;    // phase and frame of the first failure, to reproduce
};

FallThroughResult fallThrough(const RendererSpec& renderer, double thickness, double speed, int phases = 8);

// Plate thicknesses of the protocol for voxel size h: h, 2h, 4h and 1 mm.
std::vector<double> plateThicknesses(double h);
// Speeds tried, m/s (up to 2 m/s, to find where the penalty method stops being safe).
std::vector<double> fallThroughSpeeds();
double fallThroughVoxelSize();

}  // namespace millsim::measure
