#pragma once
// MillTool: the milling burr — a cutting head (a sphere by default, or a
// cylinder, taper or inverted cone: millsim/haptics/BurrHead.h says exactly
// where each head sits) and a cylindrical shaft.
// Frame: the device pose is the pose of the burr centre; the shaft runs from
// the burr centre along the tool's local +Y for shaftLength. A non-round head
// is centred on the burr centre and spans y in [−tipLength/2, +tipLength/2],
// its cutting end at −tipLength/2.
#include <string>
#include <string_view>

#include "millsim/core/NodeKinds.h"
#include "millsim/haptics/BurrHead.h"

namespace millsim {

struct ToolGeometry {
  double tipRadius = 1.0e-3;
  double shaftRadius = 0.5e-3;
  double shaftLength = 20e-3;
  // The head (BurrHead.h); the defaults keep the round burr of every existing scene.
  BurrShape shape = BurrShape::Round;
  double tipLength = 2.0e-3;
  double tipEndRadius = 0.5e-3;

  BurrHead head() const { return {shape, tipRadius, tipLength, tipEndRadius}; }
  bool round() const { return shape == BurrShape::Round; }
  bool operator==(const ToolGeometry&) const = default;
};

// The tool as one CSV cell of a frame log: "shape tipRadius tipLength
// tipEndRadius shaftRadius shaftLength" (m, numbers that read back exactly),
// so a review mills with the burr each frame was milled with.
std::string toolCell(const ToolGeometry& tool);
// Reads a toolCell; false if `cell` is not one.
bool parseToolCell(std::string_view cell, ToolGeometry& tool);

class MillTool : public Node {
public:
  static constexpr std::string_view kindName = "MillTool";
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFString shape{this, "shape", Access::InputOutput, "round",
                 "The cutting head: \"round\" (a sphere), \"cylinder\" (flat-ended), \"taper\" (narrow at the "
                 "cutting end) or \"inverted-cone\" (wide at the cutting end). Non-round heads are centred on the "
                 "burr centre along local Y, cutting end at -tipLength/2. Live in the window of millsim run (key B, or "
                 "any MillTool field): the renderer is compiled again for the new burr and cross-faded in."};
  SFFloat tipRadius{this, "tipRadius", Access::InputOutput, 1.0e-3f,
                    "Radius of the burr sphere, or the widest radius of a non-round head (m).",
                    Range::openClosed(0, 0.01).in(quantity::length)};
  SFFloat tipLength{this, "tipLength", Access::InputOutput, 2.0e-3f,
                    "Length of a non-round head along local Y, centred on the burr centre (m); round ignores it.",
                    Range::openClosed(0, 0.02).in(quantity::length)};
  SFFloat tipEndRadius{this, "tipEndRadius", Access::InputOutput, 0.5e-3f,
                       "Radius of the narrow end of a taper (its cutting end) or inverted-cone (its shank end) "
                       "head (m); at most tipRadius. Round and cylinder ignore it.",
                       Range::closed(0, 0.01).in(quantity::length)};
  SFFloat shaftRadius{this, "shaftRadius", Access::InputOutput, 0.5e-3f, "Radius of the shaft (m).",
                      Range::openClosed(0, 0.01).in(quantity::length)};
  SFFloat shaftLength{this, "shaftLength", Access::InputOutput, 20e-3f,
                      "Length of the shaft from the burr centre along local +Y (m).", Range::openClosed(0, 0.5).in(quantity::length)};

  // The geometry; an unknown shape (refused by initialize()) reads as round.
  ToolGeometry geometry() const {
    ToolGeometry g{tipRadius.get(), shaftRadius.get(), shaftLength.get()};
    if (!parseBurrShape(shape.get(), g.shape)) g.shape = BurrShape::Round;
    g.tipLength = tipLength.get();
    g.tipEndRadius = tipEndRadius.get();
    return g;
  }
  // Sets the fields to `g` (a review's recorded burr, a refused swap's kept one).
  void setGeometry(const ToolGeometry& g) {
    shape.set(std::string(burrShapeName(g.shape)));
    tipRadius.set(float(g.tipRadius));
    tipLength.set(float(g.tipLength));
    tipEndRadius.set(float(g.tipEndRadius));
    shaftRadius.set(float(g.shaftRadius));
    shaftLength.set(float(g.shaftLength));
  }
  void initialize(DiagnosticSink& sink) override;
  // What is wrong with the current field values as a burr (empty: nothing).
  // initialize() reports it at load; a live change (a burr swap) is refused with it.
  std::string problem() const;
};

}  // namespace millsim
