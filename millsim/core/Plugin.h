#pragma once
// Plugins: shared libraries that add node types. A plugin exports two C
// functions and nothing else is required of it:
//
//   extern "C" int millsim_plugin_abi_version() { return millsim::kPluginAbiVersion; }
//   extern "C" void millsim_register_nodes(millsim::NodeRegistry& r) { r.add(MyNode::type()); }
//
// Scenes load plugins with <ImportLibrary url='"libmynodes.so"'/>. Libraries are
// looked up only in the scene's folder and in MILLSIM_PLUGIN_PATH; absolute
// paths and '..' are refused unless the caller allows them. Loaded libraries
// stay loaded for the life of the process (their code backs the nodes).
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "millsim/core/NodeRegistry.h"

namespace millsim {

// Bumped whenever a class a plugin derives from or calls changes layout
// incompatibly (Node, Field, NodeRegistry, the renderer contract, the device
// nodes). 2: HapticScene became an interface and HapticsRendererNode gained traits().
inline constexpr int kPluginAbiVersion = 2;

struct PluginError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct PluginPolicy {
  bool allowAnyPath = false;                        // millsim --allow-plugin-path
  std::vector<std::filesystem::path> searchPath;    // after the scene's folder
};

// The directories listed in MILLSIM_PLUGIN_PATH (colon-separated).
std::vector<std::filesystem::path> pluginPathFromEnvironment();

// Finds the library file for `url`, or throws PluginError saying where it looked.
std::filesystem::path resolvePlugin(const std::string& url, const std::filesystem::path& sceneDir,
                                    const PluginPolicy& policy);

// Opens the library, checks its ABI version and lets it register its node
// types into `registry`. Throws PluginError.
void loadPlugin(const std::filesystem::path& library, NodeRegistry& registry);

}  // namespace millsim
