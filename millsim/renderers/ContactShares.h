#pragma once
// How much each of a tool's contacts pushes when several touch at once
// (#2's contacts, #1's burr and shaft; docs/algorithms.md, Algorithm #2,
// "Force and torque"). Each contact i is a plane the tool is pushed out of:
// unit normal n_i out of the material, depth d_i > 0 (m). The push is
// δ = Σ λ_i n_i with shares λ_i that solve
//
//     min ½|Σ λ_i n_i|² − Σ λ_i d_i   over 0 ≤ λ_i ≤ d_i,
//
// the dual of a rigid tool's nearest translation out of every plane (n_i·δ ≥
// d_i), with each share capped at its own depth:
//  - one contact, or contacts at right angles: k·d_i each, as summed;
//  - contacts less than 90° apart share: a burr in a bowl with its shaft on
//    the rim, or burr and shaft both on one face, are pushed out once, not
//    twice (summing k·d_i·n_i pushed up to twice too hard there);
//  - in a wedge (the burr on a hole's wall, the leaning shaft on the opposite
//    rim) a rigid tool would be lifted by shares many times the depths, and
//    every ripple of the tracked normals came through amplified (0.13–0.45 N
//    frame to frame in the §8.2 procedure): the cap keeps each contact's
//    push to its own depth there, the sum.
#include "millsim/renderers/DeepestPoint.h"

namespace millsim {

// Writes the shares λ (n of them, n ≤ kMaxPointContacts) for contacts with
// unit normals and depths (m; a contact with depth ≤ 0 gets no share).
// Projected Gauss–Seidel to a relative 1e-9, at most 200 sweeps; no allocation.
void contactShares(const glm::dvec3* normals, const double* depths, int n, double* shares);

// #1's two contacts: the burr's push (its proxy − the device) and a shaft
// contact found with the tool at the burr's proxy (unit normal, depth there).
// Both are measured at the device's pose — moving the tool back by the
// burr's push deepens the shaft by that push along its normal — and share as
// above. The burr pushes `burr` along its push's direction, the shaft `shaft`
// along its normal (m each).
struct BurrShaftShares {
  double burr = 0.0, shaft = 0.0;
};
BurrShaftShares burrAndShaftShares(const glm::dvec3& burrPush, const glm::dvec3& shaftNormal, double shaftDepth);

}  // namespace millsim
