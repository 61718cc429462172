#pragma once
// Algorithm #3 of the paper (§6), after Barbič & James (2008): the tool is a
// signed distance field, the milled object a point shell (points on the
// iso-surface, one per surface voxel of a volume `pointShellScale` times coarser,
// two for a voxel-thin sheet; see millsim/haptics/PointShellQuery.h), culled by box–box tests
// of the shell's bucket hierarchy against the tool's oriented bounding box.
// Every frame, penalty forces of the points inside the tool and a 6-DOF
// virtual coupling to the device are linearised and the 6×6 quasi-static
// system (net force and torque on the tool = 0) is solved for the tool's
// change of pose. The user feels the coupling between the new tool pose and
// the device — by default with what the tool's penalty penetration takes
// away added back, as a rigid contact would push (rigidContact) — and the
// tool is drawn where it is coupled, on the surface.
#include "millsim/haptics/HapticsRenderer.h"

namespace millsim {

class BarbicRenderer : public HapticsRendererNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }
  RendererTraits traits() const override;
  FrameCostEstimate estimateFrameCost(const FrameCostContext& context) const override;

  SFInt32 pointShellScale{this, "pointShellScale", Access::InitializeOnly, 1,
                          "Point shell scaling factor: 1 is every surface voxel (the default: a burr on a coarser "
                          "shell rests on a few points and slides into the pocket between them); the paper chose 3.",
                          Range::closed(1, 8)};
  SFFloat contactStiffness{this, "contactStiffness", Access::InitializeOnly, 5000.f,
                           "Penalty stiffness per shell point at scale 1 (N/m); a point of a scale-s shell stands "
                           "for s² fine points and gets s² times this.",
                           Range::openClosed(0, 1e7).in(quantity::linearStiffness)};
  SFFloat couplingStiffness{this, "couplingStiffness", Access::InitializeOnly, 2000.f,
                            "Virtual coupling spring between tool and device (N/m): the stiffness the user feels.",
                            Range::openClosed(0, 1e6).in(quantity::linearStiffness).usually(100, 20000)};
  SFFloat couplingDamping{this, "couplingDamping", Access::InitializeOnly, 1.f,
                          "Virtual coupling damper on the tool's velocity relative to the device's (N·s/m).",
                          Range::closed(0, 1e4).in(quantity::linearDamping)};
  SFFloat angularCouplingStiffness{this, "angularCouplingStiffness", Access::InitializeOnly, 0.1f,
                                   "Virtual coupling torsion spring (N·m/rad).", Range::openClosed(0, 1000).in(quantity::angularStiffness)};
  SFFloat angularCouplingDamping{this, "angularCouplingDamping", Access::InitializeOnly, 5e-4f,
                                 "Virtual coupling torsion damper (N·m·s/rad).", Range::closed(0, 100).in(quantity::angularDamping)};
  SFFloat sdfVoxelSize{this, "sdfVoxelSize", Access::InitializeOnly, 0.05e-3f,
                       "Cell size of the tool's precomputed distance grid (m).", Range::closed(1e-5, 1e-3).in(quantity::length)};
  SFBool sampledSdf{this, "sampledSdf", Access::InitializeOnly, false,
                    "Feel the sampled distance grid (the paper's method) instead of the exact analytic distance."};
  SFFloat maxStep{this, "maxStep", Access::InitializeOnly, 0.1e-3f,
                  "Largest tool motion per frame (m, at the shaft's far end for rotations) while material is "
                  "within reach: the tool cannot tunnel through thin walls.",
                  Range::openClosed(0, 0.01).in(quantity::length)};
  SFInt32 maxTestedPoints{this, "maxTestedPoints", Access::InitializeOnly, 20000,
                          "Work budget: past this many candidate points a frame uses the coarser fallback shell.",
                          Range::closed(1, 1e6)};
  SFInt32 maxContacts{this, "maxContacts", Access::InitializeOnly, 1000,
                      "Contact budget: past this many contacts a frame uses the coarser fallback shell, then stops "
                      "adding contacts.",
                      Range::closed(1, 1e5)};
  SFBool culling{this, "culling", Access::InitializeOnly, true,
                 "Cull the point shell with box tests against the tool's oriented box; false tests every point "
                 "(the paper's timings imply this; for comparison only)."};
  SFBool rigidContact{this, "rigidContact", Access::InitializeOnly, true,
                      "Feel the contact as rigid: the coupling's wrench plus what its springs would add if the tool "
                      "were moved (translated and turned, at least cost to them) out of its burr's and its shaft's "
                      "penalty penetrations (stretching them at most six times the deeper one), what a tool held at "
                      "the surface would give. FALSE: the paper's coupling wrench, short by that penetration (12 % "
                      "RMS force error at 0.1 mm voxels)."};
  SFFloat feedResistance{this, "feedResistance", Access::InitializeOnly, 200.f,
                         "Milling: the burr advances from the tool towards the device at force / feedResistance "
                         "(N·s/m).",
                         Range::openClosed(0, 1e6).in(quantity::linearDamping)};

  std::unique_ptr<HapticAlgorithm> compile(const ToolGeometry& tool, HapticScene& scene) const override;
};

}  // namespace millsim
