#pragma once
// Where a renderer puts a tool that starts inside material: a run that starts
// there, or a renderer swapped in while the hand presses (whose new
// algorithm starts from the device pose). Left at the device pose, #1 felt
// nothing and #3, its burr centre past the surface, pulled the hand in (its
// contacts' normals point away from the burr centre). The tool starts instead
// where the renderer's own contact test first finds it free along a
// direction — the tool's axis, the way a burr comes out of the hole it is
// in — and the renderer goes on from there as if the hand had pushed in:
// the force it renders is the one it holds at that device pose.
#include <algorithm>

namespace millsim {

// inside(s): whether the tool moved s (m) along the direction is in material.
// Returns 0 if free already, else an s at which it is free with the tool
// inside at most `tolerance` less (doubling from `step`, then bisection), or
// a negative value if it is inside all the way to `reach` (or the lengths
// are not positive: a scene without volumes has no voxel size).
template <class Inside> double firstFreeAlong(Inside&& inside, double step, double reach, double tolerance) {
  if (!inside(0.0)) return 0.0;
  if (!(step > 0.0) || !(reach > 0.0) || !(tolerance > 0.0) || !(reach < 1e3)) return -1.0;
  double lo = 0.0, hi = std::min(step, reach);
  while (inside(hi)) {
    if (hi >= reach) return -1.0;
    lo = hi;
    hi = std::min(2.0 * hi, reach);
  }
  while (hi - lo > tolerance) {
    const double mid = 0.5 * (lo + hi);
    (inside(mid) ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace millsim
