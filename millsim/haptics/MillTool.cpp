#include "millsim/haptics/MillTool.h"

namespace millsim {

const NodeType& MillTool::type() {
  static const NodeType t = makeNodeType<MillTool>("MillTool", "tool", "MillSim haptics",
                                                   "The burr: a cutting head (round, cylinder, taper or inverted-cone) at the tip and a shaft along local +Y.");
  return t;
}

void MillTool::initialize(DiagnosticSink& sink) {
  BurrShape parsed;
  if (!parseBurrShape(shape.get(), parsed)) {
    sink.error(location(), "MillTool shape \"" + shape.get() + "\" is not one of: " + std::string(kBurrShapeNames));
    return;
  }
  if ((parsed == BurrShape::Taper || parsed == BurrShape::InvertedCone) && tipEndRadius.get() > tipRadius.get())
    sink.error(location(), "MillTool tipEndRadius " + formatNumber(tipEndRadius.get()) + " is larger than tipRadius " +
                               formatNumber(tipRadius.get()) + "; tipRadius is the " + shape.get() +
                               " head's widest radius");
  if (shaftRadius.get() > tipRadius.get())
    sink.warning(location(), "MillTool shaftRadius " + formatNumber(shaftRadius.get()) + " is larger than tipRadius " +
                                 formatNumber(tipRadius.get()) + "; the shaft will touch before the burr");
}

}  // namespace millsim
