#pragma once
// Algorithm #2 of the paper (§5): a penalty method with the tool approximated
// by points on its surface — vertices on the burr sphere, and slices of
// vertices around the shaft. Colliding sphere vertices give the force (eq.
// 14–16), colliding slice vertices give per-slice reactions and the torque
// (eq. 18–21); a sphere or slice whose centre is inside holds its previous
// value (eq. 17, 19). The tool is drawn where the device is. By default
// (deepestPoints) the points only find the contacts: each contact pushes k
// times the tool's deepest point's depth there, contacts less than 90° apart
// sharing one push as a rigid tool's (ContactShares.h, docs/algorithms.md).
#include "millsim/haptics/HapticsRenderer.h"

namespace millsim {

class SurfacePointRenderer : public HapticsRendererNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }
  RendererTraits traits() const override;
  FrameCostEstimate estimateFrameCost(const FrameCostContext& context) const override;

  SFInt32 sphereVertices{this, "sphereVertices", Access::InputOutput, 24,
                         "Vertices on the burr sphere (paper: 24), spread evenly (Fibonacci lattice).",
                         Range::closed(4, 1000)};
  SFInt32 slices{this, "slices", Access::InputOutput, 20, "Slices along the shaft (paper: 20).", Range::closed(1, 200)};
  SFInt32 verticesPerSlice{this, "verticesPerSlice", Access::InputOutput, 8,
                           "Vertices on each slice's circle (paper: 8).", Range::closed(3, 64)};
  // The paper's eq. 14 divides by the vertex count, so its felt stiffness is
  // k times the colliding fraction: it needs k about 8x higher (20000 N/m).
  SFFloat springConstant{this, "springConstant", Access::InputOutput, 2400.f,
                         "The spring (N/m): the felt stiffness with deepestPoints; k_spring of eq. 14 without "
                         "(then felt about k times the colliding fraction: 20000 N/m feels like 2400).",
                         Range::openClosed(0, 1e6).in(quantity::linearStiffness).usually(100, 20000)};

  SFBool deepestPoints{this, "deepestPoints", Access::InitializeOnly, true,
                       "Push the tool out by k times its depth: each contact (the burr's or shaft's deepest line "
                       "in material, tracked from frame to frame) pushes k times its depth along its normal, "
                       "contacts less than 90° apart sharing one push as a rigid tool's; false: the paper's sum of "
                       "colliding points (eq. 14-21: force as depth squared, shaft torque only)."};

  SFFloat feedResistance{this, "feedResistance", Access::InputOutput, 200.f,
                         "Milling: the burr cuts where the device is, and the material gives way at force / "
                         "(feedResistance x hardness) (N·s/m); MillSim's removal model, the paper removes at once.",
                         Range::openClosed(0, 1e6).in(quantity::linearDamping)};

  std::unique_ptr<HapticAlgorithm> compile(const ToolGeometry& tool, HapticScene& scene) const override;
};

}  // namespace millsim
