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
};

}  // namespace millsim
