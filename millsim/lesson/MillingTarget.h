#pragma once
// MillingTarget: a region the trainee is to remove (a cavity preparation).
#include "millsim/lesson/AssessmentRegion.h"

namespace millsim {

class MillingTarget : public AssessmentRegion {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFFloat fraction{this, "fraction", Access::OutputOnly, 0.f,
                   "Removed material inside the region over the material it held at the start (0 to 1)."};
};

}  // namespace millsim
