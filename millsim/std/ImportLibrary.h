#pragma once
#include "millsim/core/NodeKinds.h"

namespace millsim {

// Loads a plugin library that adds node types (see docs/plugins.md). Only the
// scene's folder and MILLSIM_PLUGIN_PATH are searched.
class ImportLibrary : public ChildNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  MFString url{this, "url", Access::InitializeOnly, {}, "Library file names; the first that loads is used."};
  // H3DAPI scenes name their libraries here; the same path rules apply.
  MFString library{this, "library", Access::InitializeOnly, {},
                   "H3DAPI's spelling of url: library file names tried after url's, with the same path rules."};
};

}  // namespace millsim
