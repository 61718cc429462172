// millsim: load, check and run MillSim scenes.
//
// The command links only libmillsim_scene (the node graph, no OpenVDB).
// `millsim --version` and `millsim nodes` run here; every other command line
// goes to libmillsim_cli, opened next to libmillsim_scene, which holds all the
// verbs and links libmillsim and OpenVDB (27 MB resident on Debian, paid by
// no verb that loads no voxels).
#include <cstring>

#include "CliApp.h"
#include "CliModule.h"
#include "millsim/core/SiblingLibrary.h"

int main(int argc, char** argv) {
  using namespace millsim::app;
  const bool versionOnly = argc == 2 && std::strcmp(argv[1], "--version") == 0;
  if (versionOnly || (argc >= 2 && std::strcmp(argv[1], "nodes") == 0)) {
    CLI::App app;
    describeApp(app);
    int result = kExitOk;
    addNodesCommand(app, result);
    return parseAndRun(app, argc, argv, result);
  }
  std::string error;
  const auto* cli = static_cast<const CliModule*>(
      millsim::openSiblingLibrary("libmillsim_cli.so", "MILLSIM_CLI_LIBRARY", "millsim_cli_module", kCliAbiVersion,
                                  "command", "it is built and installed with the millsim command", error));
  if (!cli) {
    std::cerr << "millsim: error: " << error << "\n";
    return kExitFailure;
  }
  return cli->main(argc, argv);
}
