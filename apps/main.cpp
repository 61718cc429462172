// millsim: load, check and run MillSim scenes.
#include <exception>
#include <iostream>
#include <new>

#include "Commands.h"
#include "MillSimVersion.h"

int main(int argc, char** argv) {
  using namespace millsim::app;
  CLI::App app{"MillSim: 6-DOF haptic milling on X3D scenes.", "millsim"};
  app.set_version_flag("--version", std::string("millsim ") + MILLSIM_VERSION);
  app.require_subcommand(1);
  GlobalOptions global;
  app.add_flag("--allow-plugin-path", global.allowPluginPath,
               "Let ImportLibrary load libraries by absolute path or with '..' in the path");

  int result = kExitOk;
  addBenchCommand(app, result);
  addCheckCommand(app, global, result);
  addNodesCommand(app, result);
  addPhantomCommand(app, result);
  addReplayCommand(app, global, result);
  addRenderCommand(app, global, result);
  addReportCommand(app, result);
  addRunCommand(app, global, result);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, version or the usage error
    return code == 0 ? kExitOk : kExitBadInput;
  } catch (const std::bad_alloc&) {
    // The verbs report their own errors; what still escapes must not abort the process.
    std::cerr << "millsim: error: out of memory\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "millsim: error: " << e.what() << "\n";
    return kExitFailure;
  }
  return result;
}
