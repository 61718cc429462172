#pragma once
// The paper's §8.1 test application, per renderer and resolution: the burr
// pressed 0.3 mm into the tooth phantom's occlusal surface with the shaft
// leaning 15° and circling once a second (as bench/RendererBench.cpp), and the
// compute time of each step — frame time and the equivalent haptic rate.
#include "measure/Renderers.h"

namespace millsim::measure {

struct RateResult {
  std::string renderer, resolution;
  std::string grid;  // the phantom's voxel grid, e.g. "256x256x176 @ 0.1 mm"
  long frames = 0;
  double meanUs = 0, p50Us = 0, p99Us = 0;
  double rateHz = 0;  // 1 / mean frame time
  int maxContacts = 0;
};

// fineGrid: the paper's "8× voxels" variant — the phantom at 512×512×352 with
// 0.05 mm voxels (same tooth, twice the resolution along each axis).
RateResult measureRate(const RendererSpec& spec, long frames, const std::string& resolutionLabel,
                       bool fineGrid = false);

}  // namespace millsim::measure
