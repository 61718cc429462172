#pragma once
// The standard X3D node names (X3D 4.0, a superset of 3.3), generated from the
// X3D Unified Object Model by scripts/gen-x3d-tables. The loader tells a
// standard node MillSim does not implement (a warning; the element is skipped)
// from a name that is no X3D at all (an error).
#include <cstddef>
#include <string_view>

namespace millsim {

struct StandardNodeName {
  std::string_view name;       // e.g. "Cone"
  std::string_view component;  // e.g. "Geometry3D"
};

// Null when `name` is not a concrete X3D 4.0 node.
const StandardNodeName* findStandardNode(std::string_view name);
std::size_t standardNodeCount();

}  // namespace millsim
