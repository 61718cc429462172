#include "millsim/math/ContactCone.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

namespace millsim {

namespace {

// Solves G λ = b for the Gram matrix G of the normals picked by `mask`
// (1–3 of them); false when they are (nearly) dependent.
bool solveOnSubset(const glm::dvec3* normals, const double* rhs, int count, unsigned mask, double* lambda) {
  int idx[3], m = 0;
  for (int j = 0; j < count; ++j)
    if (mask & (1u << j)) idx[m++] = j;
  glm::dmat3 g(1.0);  // unused rows/columns stay the identity
  glm::dvec3 b(0.0);
  for (int a = 0; a < m; ++a) {
    b[a] = rhs[idx[a]];
    for (int c = 0; c < m; ++c) g[c][a] = glm::dot(normals[idx[a]], normals[idx[c]]);
  }
  // Unit normals: a Gram determinant under 1e-9 means normals within about
  // 0.002° of dependent, where a smaller subset carries the same answer.
  const double det = glm::determinant(g);
  if (!(std::abs(det) > 1e-9)) return false;
  const glm::dvec3 x = glm::inverse(g) * b;
  for (int a = 0; a < m; ++a) lambda[idx[a]] = x[a];
  return true;
}

int bits(unsigned mask) {
  int n = 0;
  for (; mask; mask &= mask - 1) ++n;
  return n;
}

// The subsets of at most three contacts, smallest first, each with the
// non-negative λ that solve G λ = rhs on it and their combination Σ λ_j n_j;
// the first that `optimal(mask, λ, combination)` accepts is written to
// `lambda` (zero outside it). False if none is.
template <class Optimal>
bool firstOptimalSubset(const glm::dvec3* normals, const double* rhs, int count, double* lambda, Optimal optimal) {
  for (int size = 1; size <= std::min(3, count); ++size) {
    for (unsigned mask = 1; mask < (1u << count); ++mask) {
      if (bits(mask) != size) continue;
      double l[kMaxConeContacts] = {};
      if (!solveOnSubset(normals, rhs, count, mask, l)) continue;
      bool ok = true;
      glm::dvec3 combination(0.0);
      for (int j = 0; j < count && ok; ++j) {
        if (!(mask & (1u << j))) continue;
        ok = l[j] >= 0.0;  // a contact may only push
        combination += l[j] * normals[j];
      }
      if (ok && optimal(mask, combination)) {
        for (int j = 0; j < count; ++j) lambda[j] = l[j];
        return true;
      }
    }
  }
  return false;
}

}  // namespace

bool nearestTranslationOut(const glm::dvec3* normals, const double* depths, int count, glm::dvec3& s) {
  count = std::clamp(count, 0, kMaxConeContacts);
  double scale = 0.0;
  for (int j = 0; j < count; ++j) {
    if (!std::isfinite(depths[j])) return false;
    scale = std::max(scale, std::abs(depths[j]));
  }
  bool clear = true;
  for (int j = 0; j < count; ++j) clear &= depths[j] <= 0.0;
  if (clear) {
    s = glm::dvec3(0.0);
    return true;
  }
  // Optimal when the translation clears every contact, the inactive ones too.
  const double tolerance = 1e-9 * scale;
  double lambda[kMaxConeContacts];
  glm::dvec3 found(0.0);
  const bool ok = firstOptimalSubset(normals, depths, count, lambda, [&](unsigned, const glm::dvec3& t) {
    for (int j = 0; j < count; ++j)
      if (!(glm::dot(normals[j], t) >= depths[j] - tolerance)) return false;
    found = t;
    return true;
  });
  if (ok) s = found;
  return ok;
}

void splitAlongNormals(const glm::dvec3* normals, int count, const glm::dvec3& force, double* shares) {
  count = std::clamp(count, 0, kMaxConeContacts);
  for (int j = 0; j < count; ++j) shares[j] = 0.0;
  const double tolerance = 1e-9 * glm::length(force);
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) return;
  double along[kMaxConeContacts];
  bool pullsAll = true;
  for (int j = 0; j < count; ++j) {
    along[j] = glm::dot(normals[j], force);
    pullsAll &= along[j] <= tolerance;
  }
  if (pullsAll) return;  // no contact can carry any of it
  // Optimal when no contact outside the subset could take more of what is left.
  double lambda[kMaxConeContacts];
  if (firstOptimalSubset(normals, along, count, lambda, [&](unsigned mask, const glm::dvec3& carried) {
        const glm::dvec3 left = force - carried;
        for (int j = 0; j < count; ++j)
          if (!(mask & (1u << j)) && glm::dot(normals[j], left) > tolerance) return false;
        return true;
      }))
    for (int j = 0; j < count; ++j) shares[j] = lambda[j];
}

}  // namespace millsim
