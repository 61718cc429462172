// A node type from outside MillSim, loaded by <ImportLibrary url='"libmillsim_sample_plugin.so"'/>.
// It uses only MillSim's public headers and the two plugin entry points.
#include <millsim/core/NodeKinds.h>
#include <millsim/core/NodeRegistry.h>
#include <millsim/core/Plugin.h>

namespace sample {

// Marks a point of interest on the tooth (e.g. for a lesson's instructions).
class Landmark : public millsim::ChildNode {
public:
  static const millsim::NodeType& type() {
    static const millsim::NodeType t = millsim::makeNodeType<Landmark>(
        "Landmark", "children", "Sample plugin", "A named point of interest.");
    return t;
  }
  const millsim::NodeType& nodeType() const override { return type(); }

  millsim::SFString label{this, "label", millsim::Access::InputOutput, "", "Name shown to the student."};
  millsim::SFVec3f position{this, "position", millsim::Access::InputOutput, glm::vec3(0.f), "Where it is (m)."};
  millsim::SFFloat radius{this, "radius", millsim::Access::InputOutput, 0.001f, "Marker size (m).",
                          millsim::Range::positive()};
};

}  // namespace sample

extern "C" int millsim_plugin_abi_version() { return millsim::kPluginAbiVersion; }
extern "C" void millsim_register_nodes(millsim::NodeRegistry& registry) { registry.add(sample::Landmark::type()); }
