// The millsim command with all its verbs (CliModule.h), run by main.cpp.
#include "CliApp.h"
#include "CliModule.h"

namespace millsim::app {

namespace {

int cliMain(int argc, char** argv) {
  CLI::App app;
  describeApp(app);
  GlobalOptions global;
  app.add_flag("--allow-plugin-path", global.allowPluginPath,
               "Let ImportLibrary load libraries by absolute path or with '..' in the path");

  int result = kExitOk;
  addBenchCommand(app, result);
  addCheckCommand(app, global, result);
  addDevicesCommand(app, result);
  addNodesCommand(app, result);
  addPhantomCommand(app, result);
  addReplayCommand(app, global, result);
  addRenderCommand(app, global, result);
  addReportCommand(app, result);
  addSweepCommand(app, result);
  addRunCommand(app, global, result);
  return parseAndRun(app, argc, argv, result);
}

const CliModule kModule{kCliAbiVersion, &cliMain};

}  // namespace

}  // namespace millsim::app

// Typed as the loader calls it (SiblingLibrary: const void* (*)()): a call through
// another function type is undefined behaviour (clang's -fsanitize=function).
extern "C" __attribute__((visibility("default"))) const void* millsim_cli_module() {
  return &millsim::app::kModule;
}
