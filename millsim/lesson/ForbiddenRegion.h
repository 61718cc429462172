#pragma once
// ForbiddenRegion: a region the trainee must not cut (the pulp, a nerve canal).
#include "millsim/lesson/AssessmentRegion.h"

namespace millsim {

class ForbiddenRegion : public AssessmentRegion {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFBool violated{this, "violated", Access::OutputOnly, false,
                  "Whether the burr has removed material inside, or its head has entered one of the region's soft "
                  "tissues (Tissue soft: the pulp, below the isoValue)."};
  SFTime firstViolationTime{this, "firstViolationTime", Access::OutputOnly, Time{-1.0},
                            "When the burr first removed material inside or entered a soft tissue of the region (s "
                            "from the run's start); -1: never."};
  SFFloat depth{this, "depth", Access::OutputOnly, 0.f,
                "How far the burr's head reached past the surface of the region's soft tissues (m, to a voxel)."};
  SFFloat sweptVolume{this, "sweptVolume", Access::OutputOnly, 0.f,
                      "Volume of the region's soft tissues the burr's head has swept (m³)."};
};

}  // namespace millsim
