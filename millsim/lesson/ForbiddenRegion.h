#pragma once
// ForbiddenRegion: a region the trainee must not cut (the pulp, a nerve canal).
#include "millsim/lesson/AssessmentRegion.h"

namespace millsim {

class ForbiddenRegion : public AssessmentRegion {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFBool violated{this, "violated", Access::OutputOnly, false, "Whether the burr has removed material inside."};
  SFTime firstViolationTime{this, "firstViolationTime", Access::OutputOnly, Time{-1.0},
                            "When the burr first removed material inside (s from the run's start); -1: never."};
};

}  // namespace millsim
