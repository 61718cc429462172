#pragma once
// Node names of H3DAPI (and its MedX3D and haptics add-ons) that are not X3D.
// Scenes written for H3DLoad use them; MillSim says so instead of "unknown
// node type", and names what it offers in their place.
#include <string_view>

namespace millsim {

enum class H3dNodeKind { Renderer, Device, Other };

struct H3dNodeName {
  std::string_view name;
  H3dNodeKind kind;
};

// Null when `name` is not an H3DAPI/MedX3D node name MillSim knows of.
const H3dNodeName* findH3dNode(std::string_view name);

}  // namespace millsim
