#pragma once
// The X3D abstract node kinds that node fields ask for. A node class derives
// from the kind it is; a field such as Group.children accepts only that kind.
#include "millsim/core/Node.h"

namespace millsim {

// Anything that may sit among a grouping node's children.
class ChildNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DChildNode";
};

class GeometryNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DGeometryNode";
};

class AppearanceNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DAppearanceNode";
};

class MaterialNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DMaterialNode";
};

// A metadata node (MetadataBoolean, ..., MetadataSet): what a node's
// `metadata` field and a MetadataSet's `value` hold.
class MetadataObject : public Node {
public:
  static constexpr std::string_view kindName = "X3DMetadataObject";
};

}  // namespace millsim
