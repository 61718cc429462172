#pragma once
// Tissue: one material of a VolumeObject (its `tissues` field) — enamel,
// dentin, pulp, bone — chosen by density or by a label volume, with the
// hardness that sets how fast the burr cuts it and the colour its cut
// surface is drawn in. docs/algorithms.md, "Tissue hardness".
#include "millsim/core/Node.h"

namespace millsim {

class Tissue : public Node {
public:
  static constexpr std::string_view kindName = "Tissue";
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFString name{this, "name", Access::InitializeOnly, "", "The tissue's name, as reports and regions refer to it."};
  SFVec2f densityRange{this, "densityRange", Access::InitializeOnly, glm::vec2(0.f),
                       "[min, max) of the volume's original density that is this tissue; 0 0: chosen by label, or "
                       "by name, instead.",
                       Range::closed(-1e9, 1e9)};
  SFInt32 label{this, "label", Access::InitializeOnly, -1,
                "Value of the VolumeObject's labelUrl volume that is this tissue; -1: chosen by densityRange, or "
                "with neither, by name: the part of a mesh url (an OBJ group, an STL solid) of the tissue's name.",
                Range::closed(-1, 1 << 20)};
  SFFloat hardness{this, "hardness", Access::InitializeOnly, 1.f,
                   "How hard the tissue is to cut, relative to 1 for the default material: the cutting front "
                   "recedes at force / (feedResistance x hardness); 0 is never cut.",
                   Range::closed(0, 1000)};
  SFColor color{this, "color", Access::InitializeOnly, Color{glm::vec3(0.85f, 0.8f, 0.7f)},
                "Colour of the tissue's surface in the graphics.", Range::closed(0, 1)};
  SFBool soft{this, "soft", Access::InitializeOnly, false,
              "A soft tissue (pulp, a canal, marrow): its voxels lie below the VolumeObject's isoValue, so the burr "
              "does not feel it and its hardness is not used (the burr clears its voxels as it passes); it is drawn in its colour where a cut exposes "
              "it, and a ForbiddenRegion naming it is violated when the burr's surface enters it. A tissue whose "
              "voxels are mostly below isoValue is soft whatever this says; true says it is meant (check warns "
              "of one that is neither marked soft nor forbidden)."};

  // True when the tissue is chosen by densityRange (an empty range means by label).
  bool byDensity() const { return densityRange.get().x < densityRange.get().y; }
  // Chosen by neither: by its name among a mesh's parts.
  bool byPartName() const { return !byDensity() && label.get() < 0; }
  void initialize(DiagnosticSink& sink) override;
};

}  // namespace millsim
