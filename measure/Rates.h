#pragma once
// The paper's §8.1 test application, per renderer and resolution: the
// compute time of each step on the tooth phantom, with the shaft leaning 15°
// and circling once a second (as bench/RendererBench.cpp), and the
// equivalent haptic rate. Two poses:
//  - gentle: the burr pressed 0.3 mm into the unmilled occlusal surface (the
//    earlier table; #3 touches 1–3 shell points at scale 3);
//  - deep: the burr pressed 0.3 mm into the bottom of a 2.5 mm hole milled
//    first, so the leaning shaft also meets the hole's wall: the paper's
//    contact counts (about 15 points for #3 at scale 3) and its workload.
// Frames are timed by the thread's CPU clock (ThreadCpuTime.h) and by the wall
// clock; a constant-work control of the same median length, timed in the same
// run, shows what the machine alone adds to the tail (ConstantWork.h).
#include "measure/ConstantWork.h"
#include "measure/Renderers.h"

namespace millsim::measure {

enum class RatePose { Gentle, Deep };

struct RateResult {
  std::string renderer, resolution;
  std::string grid;  // the phantom's voxel grid, e.g. "256x256x176 @ 0.1 mm"
  std::string pose;  // "gentle" or "deep"
  long frames = 0;
  double meanUs = 0, p50Us = 0, p99Us = 0, p999Us = 0, maxUs = 0;  // thread CPU time
  double wallP99Us = 0;
  long preempted = 0;    // frames whose wall time exceeded their CPU time by > 10 µs
  FrameTimes control;    // constant work of length p50Us, same run
  double rateHz = 0;     // 1 / mean frame time
  int maxContacts = 0, minContacts = 0;
};

// fineGrid: the paper's "8× voxels" variant — the phantom at 512×512×352 with
// 0.05 mm voxels (same tooth, twice the resolution along each axis).
RateResult measureRate(const RendererSpec& spec, long frames, const std::string& resolutionLabel,
                       bool fineGrid = false, RatePose pose = RatePose::Gentle);

}  // namespace millsim::measure
