#pragma once
// Reading PNGs and comparing a render with a reference image, for the scene
// tests. The tolerance is two numbers: a pixel differs when any channel is off
// by more than kChannelTolerance, and an image matches when at most
// kMaxDifferingFraction of its pixels differ. llvmpipe is deterministic on one
// machine; across CPUs (other SIMD widths) and Mesa versions edge pixels of
// triangles and the last bit of lighting move, which these bounds absorb,
// while a moved tool, a missing hole or a changed colour are far beyond them.
// Measured: two runs on one machine differ in no pixel; the default lesson at
// 5.75 s against its 6 s reference (the shaft leaning 2.5° less) differs in
// 0.58 % of the pixels and fails.
#include <filesystem>
#include <string>

#include "millsim/graphics/Image.h"

namespace millsim::test {

inline constexpr int kChannelTolerance = 24;           // of 255
inline constexpr double kMaxDifferingFraction = 0.002;  // 0.2 % of the pixels (524 at 512x512)

// Throws std::runtime_error naming the file.
Image readPng(const std::filesystem::path& path);

struct ImageDifference {
  std::size_t differing = 0, total = 0;
  int maxChannel = 0;
  double fraction() const { return total ? double(differing) / double(total) : 1.0; }
  bool matches() const { return total > 0 && fraction() <= kMaxDifferingFraction; }
};
// Sizes must agree (else every pixel differs). `diff`, if given, receives a
// picture of where they differ (red) over a dimmed copy of `actual`.
ImageDifference compareImages(const Image& actual, const Image& reference, Image* diff = nullptr);

// Set MILLSIM_UPDATE_REFERENCES=1 to (re)write reference images instead of
// comparing against them (then review the new PNGs and commit them).
bool updatingReferences();

}  // namespace millsim::test
