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
  SFFloat completeAt{this, "completeAt", Access::InitializeOnly, 0.9f,
                     "The fraction at which the target counts as done: the report's completed_s is the time every "
                     "target first reached its own.",
                     Range::openClosed(0, 1)};
  SFFloat overPreparationPenalty{this, "overPreparationPenalty", Access::InitializeOnly, 1.f,
                                 "How the score counts removal outside every target: it is multiplied by max(0, 1 - "
                                 "penalty x outside / the targets' starting material), so 1 (the default) gives 0 for "
                                 "removing outside as much as the targets held, and 0 ignores over-preparation. With "
                                 "several targets the largest penalty applies.",
                                 Range::closed(0, 100)};
};

}  // namespace millsim
