// millsim check SCENE.x3d: load and validate a scene, print its node tree.
#include <iostream>

#include "Commands.h"
#include "VolumeReport.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::app {

void addCheckCommand(CLI::App& app, const GlobalOptions& global, int& result) {
  auto* cmd = app.add_subcommand("check", "Load a scene, report every problem, and print its node tree");
  auto scene = std::make_shared<std::string>();
  auto strict = std::make_shared<bool>(false);
  cmd->add_option("scene", *scene, "X3D scene file")->required();
  addStrictFlag(cmd, *strict);
  cmd->callback([scene, strict, &global, &result] {
    LoadOptions options;
    options.strict = *strict;
    options.plugins.allowAnyPath = global.allowPluginPath;
    LoadResult r = loadSceneFile(*scene, builtinRegistry(), options);
    std::cerr << r.report();
    if (!r.ok()) {
      result = kExitBadInput;
      return;
    }
    std::cout << describeScene(*r.scene);
    std::cout << describeVolumes(*r.scene);
    std::cout << "nodes: " << r.scene->nodeCount() << ", DEF names: " << r.scene->defs.size()
              << ", routes: " << r.scene->routes.size() << ", plugins: " << r.scene->plugins.size() << "\n";
    result = kExitOk;
  });
}

}  // namespace millsim::app
