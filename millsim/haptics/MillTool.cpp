#include "millsim/haptics/MillTool.h"

namespace millsim {

const NodeType& MillTool::type() {
  static const NodeType t = makeNodeType<MillTool>("MillTool", "tool", "MillSim haptics",
                                                   "The burr: a sphere at the tip and a shaft along local +Y.");
  return t;
}

void MillTool::initialize(DiagnosticSink& sink) {
  if (shaftRadius.get() > tipRadius.get())
    sink.warning(location(), "MillTool shaftRadius " + formatNumber(shaftRadius.get()) + " is larger than tipRadius " +
                                 formatNumber(tipRadius.get()) + "; the shaft will touch before the burr");
}

}  // namespace millsim
