#pragma once
// AssessmentRegion: the part of a lesson's volumes a teacher marks — the
// union of the Box, Sphere and Cylinder shapes among its children (under
// Transforms, in the frame where the region sits) and of the named tissues.
// MillingTarget and ForbiddenRegion are the two kinds; RegionAccounting
// counts what the burr removed inside each, on the scene thread.
#include "millsim/core/NodeKinds.h"

namespace millsim {

class AssessmentRegion : public ChildNode {
public:
  SFString name{this, "name", Access::InitializeOnly, "", "The region's name in reports."};
  MFNodeOf<ChildNode> children{this, "children", Access::InitializeOnly,
                               "Shapes (Box, Sphere, Cylinder; under Transforms) whose union is the region."};
  MFString tissues{this, "tissues", Access::InitializeOnly, {},
                   "Names of Tissues (of any VolumeObject) that are part of the region."};
  SFBool visible{this, "visible", Access::InputOutput, false,
                 "Draw the region's shapes see-through (their own Appearance, at least 65 % transparent) over the tooth; "
                 "regions are not drawn by default."};
  SFFloat removedVolume{this, "removedVolume", Access::OutputOnly, 0.f, "Material removed inside the region (m³)."};

  bool showsDescendants() const override { return visible.get(); }
  bool showsDescendantsTranslucent() const override { return true; }
  void initialize(DiagnosticSink& sink) override;
};

}  // namespace millsim
