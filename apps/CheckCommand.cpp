// millsim check SCENE.x3d: load and validate a scene, print its node tree,
// and say whether its device can be opened here and how stiff contact will
// feel at the hand.
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "Commands.h"
#include "StderrProgress.h"
#include "VolumeReport.h"
#include "millsim/core/FieldValues.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/run/RunSetup.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::app {

namespace {

// The device line, and the felt stiffness: a renderer's stiffness k reaches
// the hand as positionScale² · k (docs/devices.md, Workspace mapping). A
// warning (returned) when that exceeds what the device's library says it
// renders stably. A missing device is reported, not refused: `millsim run`
// says so again when it tries.
std::string describeDevice(const std::string& file, const Scene& scene, std::string& warning) {
  const HapticsDevice* device = findDevice(scene);
  if (!device) return {};
  std::ostringstream out;
  const std::string name = device->typeName() + (device->defName().empty() ? "" : " '" + device->defName() + "'");
  const std::optional<DeviceProbe> probe = device->probe();
  if (probe) out << "device: " << name << (probe->opens ? ": opens " : ": cannot be opened here: ") << probe->what << "\n";
  const HapticsRendererNode* renderer = device->hapticsRenderer.get().get();
  const std::string field = renderer ? renderer->traits().stiffnessField : std::string();
  const Field* k = field.empty() ? nullptr : renderer->field(field);
  if (!k) return out.str();
  const double stiffness = std::strtod(k->toString().c_str(), nullptr);
  const double scale = device->positionScale.get();
  const double felt = scale * scale * stiffness;
  out << "felt stiffness: " << formatNumber(felt) << " N/m (" << renderer->typeName() << " " << field << " "
      << formatNumber(stiffness) << " N/m";
  if (scale != 1.0) out << " x positionScale² " << formatNumber(scale * scale);
  out << ")";
  if (probe && probe->maxStiffness > 0.0) {
    out << "; the device renders up to " << formatNumber(probe->maxStiffness) << " N/m";
    if (felt > probe->maxStiffness)
      warning = file + ": warning: " + name + " would be asked for " + formatNumber(felt) + " N/m, more than the " +
                formatNumber(probe->maxStiffness) + " N/m its library says it renders stably: lower " + field +
                " to " + formatNumber(probe->maxStiffness / (scale * scale)) + " N/m or less, or positionScale\n";
  }
  out << "\n";
  return out.str();
}

}  // namespace

void addCheckCommand(CLI::App& app, const GlobalOptions& global, int& result) {
  auto* cmd = app.add_subcommand("check", "Load a scene, report every problem, and print its node tree");
  auto scene = std::make_shared<std::string>();
  auto strict = std::make_shared<bool>(false);
  cmd->add_option("scene", *scene, "X3D scene file")->required();
  addStrictFlag(cmd, *strict);
  auto sets = std::make_shared<std::vector<std::string>>();
  addSetOption(cmd, *sets);
  cmd->callback([scene, strict, sets, &global, &result] {
    LoadOptions options;
    options.strict = *strict;
    applySetOptions(options, *sets);
    options.plugins.allowAnyPath = global.allowPluginPath;
    StderrProgress progress;
    options.progress = &progress;
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
    std::string warning;
    std::cout << describeDevice(*scene, *r.scene, warning);
    std::cerr << warning;
    result = *strict && !warning.empty() ? kExitBadInput : kExitOk;
  });
}

}  // namespace millsim::app
