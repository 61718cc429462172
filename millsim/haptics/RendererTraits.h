#pragma once
// What a renderer node declares about itself, for the code that measures and
// tests it (measure/, tests/, `millsim bench`): which of its fields is the
// stiffness, which are resolutions and what values to sweep, which exact force
// law it approximates, and whether it keeps the tool out of material. A new
// renderer type, built in or from a plugin, is measured and tested correctly
// by overriding HapticsRendererNode::traits(), with no table to edit elsewhere.
// Fields are named, not pointed to, so this header needs nothing but strings.
#include <string>
#include <utility>
#include <vector>

namespace millsim {

// The force law of the renderer in the limit of exact geometry; the accuracy
// suite (measure/Accuracy.cpp, docs/accuracy.md) computes its reference with it.
enum class ReferenceKind {
  Proxy,    // a constrained proxy on a spring (Algorithm #1): k·(exact proxy − device), shaft torque eq. 7–11
  Penalty,  // penalty forces of points on the tool (Algorithm #2): eq. 14–21 in the continuum limit
  Coupling  // a tool body on a virtual coupling (Algorithm #3, and the default):
            // k·(burr centre pushed out of the exact surface − device)
};

struct RendererTraits {
  // The field that sets the rendered contact stiffness, in N/m (an SFFloat or
  // SFDouble). The Z-width sweep raises it; the accuracy reference uses its
  // value as k. Empty: the renderer names none, and the Z-width test fails.
  std::string stiffnessField;

  // Resolution fields (e.g. vertex or point counts) with the values, as X3D
  // text, that the accuracy suite's convergence sweep tries, in that order
  // (coarse to fine, unless the field's meaning is reversed). Each value must be
  // a number the field accepts. Empty: no sweep.
  std::vector<std::pair<std::string, std::vector<std::string>>> resolutionSweeps;

  // The law the accuracy suite's exact-geometry reference uses.
  ReferenceKind reference = ReferenceKind::Coupling;

  // True if the renderer constrains the tool outside material (a proxy or a
  // coupled tool body): it must never tunnel through a thin plate. False for
  // penalty methods, whose fall-through is measured, not forbidden.
  bool constrainsTool = false;

  // True if compile() reads nothing of the HapticScene (it builds no point
  // shell, samples no voxel): a running loop's scene thread may then compile
  // it again while the haptic thread mills, so a change to its fields is live
  // (RendererPool). False: a change takes effect at the next run. The
  // renderer contract test compiles it against a scene that fails on any read.
  bool compilesWithoutScene = false;
};

}  // namespace millsim
