#pragma once
// The least-cost way a rigid body held by springs leaves a few contacts: a
// small convex problem (a linear complementarity problem of at most two
// contacts) solved exactly by trying each set of active contacts, no
// iteration count to tune, no allocation. Used by #3's rigidContact
// (BarbicRenderer), whose burr and shaft contacts a rigid tool held by the
// virtual coupling would be moved out of together.

namespace millsim {

// The least-cost way out of at most two contacts for a body that may also
// turn: pushes λ_j ≥ 0 along the contacts' generalised normals g_j (a
// normal and its moment about the body's origin) that clear both, A·λ ≥ d,
// and push only where a contact stays touching (λ_j (A·λ − d)_j = 0), with
// A_ij = g_i·W·g_j the Gram matrix in the body's inverse metric W (for a
// body held by springs k and kr: n_i·n_j/k + (a_i×n_i)·(a_j×n_j)/kr).
// The body moves W·Σ λ_j g_j, and the springs then push with Σ λ_j g_j.
// False when no pushes clear both (contacts that face each other across a
// jam); `lambda` is then left untouched.
bool pushesOut(const double (&gram)[2][2], const double* depths, int count, double* lambda);

}  // namespace millsim
