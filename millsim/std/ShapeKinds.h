#pragma once
// The X3D abstract node kinds that a Shape's geometry and appearance ask for
// beyond core's (millsim/core/NodeKinds.h): vertex data of mesh geometry,
// font styles, textures and lights. Kept here so that adding one does not
// rebuild every node.
#include "millsim/core/NodeKinds.h"

namespace millsim {

class CoordinateNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DCoordinateNode";
};

class NormalNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DNormalNode";
};

class ColorKindNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DColorNode";
};

class TextureCoordinateNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DTextureCoordinateNode";
};

class FontStyleNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DFontStyleNode";
};

class TextureNode : public Node {
public:
  static constexpr std::string_view kindName = "X3DTextureNode";
};

}  // namespace millsim
