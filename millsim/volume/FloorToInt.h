#pragma once
// floor(x) as an int, for an index-space coordinate within ±2^30 (callers
// clamp further points first): truncate, then step down below zero. Without
// SSE4.1 (Debian's x86-64 baseline) std::floor is a dozen instructions, and
// the trilinear fast paths (VolumeSampler, PointShell) take three a sample.
namespace millsim {

inline int floorToInt(double x) {
  const int t = static_cast<int>(x);
  return t - (x < double(t));
}

}  // namespace millsim
