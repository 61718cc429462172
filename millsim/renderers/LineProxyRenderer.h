#pragma once
// Algorithm #1 of the paper (§4): a constraint-based proxy method with the tool
// approximated by vertices on its centreline. The burr centre's proxy gives
// the force (eq. 6); the shaft's intersection point with the surface, found by
// the fraction method (eq. 1–4) on first contact and then tracked by the
// probe–proxy algorithm (§4.3.2), gives the torque (eq. 7–11). The drawn tool
// is offset from the proxies by the radii along the surface normal (eq. 12–13).
// By default the burr and the shaft are felt at their surfaces, and the shaft
// pushes as well as turns (feelBurrSurface, feelShaftSurface; docs/algorithms.md).
#include "millsim/haptics/HapticsRenderer.h"

namespace millsim {

class LineProxyRenderer : public HapticsRendererNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }
  RendererTraits traits() const override;
  FrameCostEstimate estimateFrameCost(const FrameCostContext& context) const override;

  SFInt32 vertexCount{this, "vertexCount", Access::InputOutput, 51,
                      "Vertices on the centreline, the burr centre included (paper: 51).", Range::closed(2, 1000)};
  SFInt32 translationSteps{this, "translationSteps", Access::InputOutput, 10,
                           "NUMBER_OF_TRANSLATION_STEPS of the first-contact search (eq. 3).", Range::closed(1, 100)};
  SFInt32 rotationSteps{this, "rotationSteps", Access::InputOutput, 10,
                        "NUMBER_OF_ROTATION_STEPS of the first-contact search (eq. 4).", Range::closed(1, 100)};
  SFFloat springConstant{this, "springConstant", Access::InputOutput, 2000.f,
                         "k_spring of eq. 6 and eq. 10 (N/m).",
                         Range::openClosed(0, 1e6).in(quantity::linearStiffness).usually(100, 20000)};
  SFInt32 proxyIterations{this, "proxyIterations", Access::InputOutput, 6,
                          "Tangent-plane steps per frame of the probe-proxy algorithm.", Range::closed(1, 100)};

  SFBool feelBurrSurface{this, "feelBurrSurface", Access::InitializeOnly, true,
                         "Hold the burr's surface out of material (its centre's proxy on the scene dilated by "
                         "tipRadius); false: the paper's centre vertex, felt only once the centre is inside."};

  SFBool feelShaftSurface{this, "feelShaftSurface", Access::InitializeOnly, true,
                          "Feel the shaft's surface: its deepest line in material pushes the tool out by "
                          "springConstant times its depth (force and torque); false: the paper's centreline "
                          "vertices, felt once the shaft has sunk its radius, and torque only (eq. 7-11)."};

  SFBool holdWholeTool{this, "holdWholeTool", Access::InitializeOnly, false,
                       "With feelBurrSurface and feelShaftSurface: the burr's proxy also keeps the shaft out of "
                       "material, a god object for the whole tool at the device's orientation (the shaft's "
                       "contact a plane found each frame where the tool rested): a tool wedged in a hole is "
                       "lifted as a rigid one is. Not for milling: a burr in its own pit with the shaft on a "
                       "rim jams and jumps (docs/algorithms.md). false: the shaft pushes from the burr's proxy "
                       "by its depth there, its share capped at that depth (ContactShares.h)."};

  SFFloat feedResistance{this, "feedResistance", Access::InputOutput, 200.f,
                         "Milling: the burr advances into material at force / feedResistance (N·s/m).",
                         Range::openClosed(0, 1e6).in(quantity::linearDamping)};

  std::unique_ptr<HapticAlgorithm> compile(const ToolGeometry& tool, HapticScene& scene) const override;
  std::string cannotCarry(const ToolGeometry& tool) const override;
};

}  // namespace millsim
