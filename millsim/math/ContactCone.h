#pragma once
// Exact answers for a rigid body held by a few planar contacts (each a unit
// normal n_j out of the material): the nearest translation out of all of them,
// and a force split into non-negative pushes along them. Both are small
// convex problems whose solution lies on some subset of at most three
// contacts (three independent normals span space); with no more than
// kMaxConeContacts contacts every subset is tried, in order of size, and the
// first that meets the optimality (KKT) conditions is the answer: exact to
// rounding, a fixed bound on work, no iteration count to tune, no allocation.
// Used by #3's rigidContact (BarbicRenderer), whose burr and shaft contacts
// a rigid tool would be translated out of together.
#include <glm/vec3.hpp>

namespace millsim {

constexpr int kMaxConeContacts = 6;

// The shortest translation s with n_j·s ≥ d_j for every j < count (d_j > 0:
// contact j is d_j deep; ≤ 0: it is that far clear and must stay clear).
// False when none exists: contacts that face each other deeper than they are
// apart (a jam, as a peg wedged across a hole); s is then left untouched.
bool nearestTranslationOut(const glm::dvec3* normals, const double* depths, int count, glm::dvec3& s);

// Non-negative shares λ_j (written to `shares`) with Σ λ_j n_j nearest to
// `force` (least squares): how a force that holds a body against its contacts
// is carried by each of them. A contact the force pulls away from gets 0.
void splitAlongNormals(const glm::dvec3* normals, int count, const glm::dvec3& force, double* shares);

}  // namespace millsim
