#pragma once
// MillTool: the milling burr — a sphere at the tip and a cylindrical shaft.
// Frame: the device pose is the pose of the burr centre; the shaft runs from
// the burr centre along the tool's local +Y for shaftLength.
#include "millsim/core/NodeKinds.h"

namespace millsim {

struct ToolGeometry {
  double tipRadius = 1.0e-3;
  double shaftRadius = 0.5e-3;
  double shaftLength = 20e-3;
};

class MillTool : public Node {
public:
  static constexpr std::string_view kindName = "MillTool";
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat tipRadius{this, "tipRadius", Access::InputOutput, 1.0e-3f, "Radius of the burr sphere (m).",
                    Range::openClosed(0, 0.01)};
  SFFloat shaftRadius{this, "shaftRadius", Access::InputOutput, 0.5e-3f, "Radius of the shaft (m).",
                      Range::openClosed(0, 0.01)};
  SFFloat shaftLength{this, "shaftLength", Access::InputOutput, 20e-3f,
                      "Length of the shaft from the burr centre along local +Y (m).", Range::openClosed(0, 0.5)};

  ToolGeometry geometry() const { return {tipRadius.get(), shaftRadius.get(), shaftLength.get()}; }
  void initialize(DiagnosticSink& sink) override;
};

}  // namespace millsim
