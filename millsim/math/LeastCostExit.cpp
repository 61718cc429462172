#include "millsim/math/LeastCostExit.h"

#include <algorithm>
#include <cmath>

namespace millsim {

bool pushesOut(const double (&gram)[2][2], const double* depths, int count, double* lambda) {
  count = std::clamp(count, 0, 2);
  if (count == 0) return true;
  for (int i = 0; i < count; ++i)
    if (!std::isfinite(depths[i]) || !(gram[i][i] > 0.0) || !std::isfinite(gram[i][i])) return false;
  const double scale = count == 2 ? std::max(std::abs(depths[0]), std::abs(depths[1])) : std::abs(depths[0]);
  const double tolerance = 1e-9 * scale;
  auto clears = [&](const double* l) {
    for (int i = 0; i < count; ++i) {
      double reach = 0.0;
      for (int j = 0; j < count; ++j) reach += gram[i][j] * l[j];
      if (!(reach >= depths[i] - tolerance)) return false;
    }
    return true;
  };
  // One contact pushing alone, the deeper first; then both together.
  const int first = count == 2 && depths[1] > depths[0] ? 1 : 0;
  for (int pass = 0; pass < count; ++pass) {
    const int i = pass == 0 ? first : 1 - first;
    double l[2] = {0.0, 0.0};
    l[i] = std::max(depths[i], 0.0) / gram[i][i];
    if (clears(l)) {
      for (int j = 0; j < count; ++j) lambda[j] = l[j];
      return true;
    }
  }
  if (count < 2) return false;
  // Both touching: A·λ = d, with unit-free conditioning (det over the diagonal's product).
  const double det = gram[0][0] * gram[1][1] - gram[0][1] * gram[1][0];
  if (!(det > 1e-12 * gram[0][0] * gram[1][1])) return false;
  const double l[2] = {(gram[1][1] * depths[0] - gram[0][1] * depths[1]) / det,
                       (gram[0][0] * depths[1] - gram[1][0] * depths[0]) / det};
  if (!(l[0] >= 0.0 && l[1] >= 0.0)) return false;
  lambda[0] = l[0], lambda[1] = l[1];
  return true;
}

}  // namespace millsim
