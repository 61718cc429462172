#pragma once
// Pose fuzzing: random and degenerate device poses — on the iso-surface,
// deep inside (zero gradient), 180° flips, jumps of up to a metre, NaN/Inf and
// zero quaternions — fed to a renderer through the haptic loop (with dropped
// samples and milling) and directly. Nothing non-finite may come out.
#include <cstdint>
#include <string>

#include "measure/Renderers.h"

namespace millsim::measure {

struct FuzzResult {
  long frames = 0;
  long nonFinite = 0;      // frames with any non-finite output
  long suppressed = 0;     // frames the renderer or loop had to zero (allowed, counted)
  long firstBad = -1;      // first bad frame (-1: none)
  std::string firstBadWhat;
};

// Through HapticLoop::stepSimulated with a scripted driver; `dropFraction` of
// samples are marked invalid. Reproduce a failure with the same seed.
FuzzResult fuzzThroughLoop(const RendererSpec& renderer, long frames, std::uint64_t seed, double dropFraction = 0.05);
// Straight into HapticAlgorithm::step (NaN poses reach the renderer itself).
FuzzResult fuzzDirect(const RendererSpec& renderer, long frames, std::uint64_t seed);

}  // namespace millsim::measure
