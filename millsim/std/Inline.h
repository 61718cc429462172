#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// Includes another X3D file. The loader reads it (url relative to the including
// file) and puts its Scene's nodes in `loaded`. DEF names inside stay private to it.
class Inline : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString url{this, "url", Access::InputOutput, {}, "Files to include; the first that loads is used."};
  SFBool load{this, "load", Access::InputOutput, true, "Whether to include the file at all."};
  MFNodeOf<ChildNode> loaded{this, "loaded", Access::OutputOnly, "The included scene's top-level nodes."};
  SFTime autoRefresh{this, "autoRefresh", Access::InputOutput, Time{0}, "Seconds between reloads; 0 = never. Accepted; not acted on by MillSim.",
                     Range::closed(0, 1e9)};
  SFTime autoRefreshTimeLimit{this, "autoRefreshTimeLimit", Access::InputOutput, Time{3600},
                              "Seconds after which reloading stops. Accepted; not acted on by MillSim.", Range::closed(0, 1e9)};
  SFVec3f bboxCenter{this, "bboxCenter", Access::InitializeOnly, glm::vec3(0.f),
                     "Centre of a bounding box hint (m). Accepted; not acted on by MillSim.", Range::closed(-1e4, 1e4).in(quantity::length)};
  SFVec3f bboxSize{this, "bboxSize", Access::InitializeOnly, glm::vec3(-1.f),
                   "Size of a bounding box hint (m); -1 -1 -1 means none. Accepted; not acted on by MillSim.", Range::closed(-1, 1e4).in(quantity::lengthOrNone)};
  SFString description{this, "description", Access::InputOutput, "", "Text describing the included scene. Accepted; not acted on by MillSim."};
  SFBool global{this, "global", Access::InputOutput, false, "Whether lights inside affect the whole scene. Accepted; not acted on by MillSim."};
  SFBool bboxDisplay{this, "bboxDisplay", Access::InputOutput, false, "Whether to draw the bounding box. Accepted; not acted on by MillSim."};
  SFBool visible{this, "visible", Access::InputOutput, true, "Whether to draw the children. Accepted; not acted on by MillSim."};
};

}  // namespace millsim
