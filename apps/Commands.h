#pragma once
// The verbs of the millsim command. Each adds its sub-command to the app and
// returns the exit code through `result` when it runs.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "millsim/x3d/X3DLoader.h"

namespace millsim::app {

// Exit codes: 0 success, 1 failure while running, 2 bad input (scene, files, arguments).
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

struct GlobalOptions {
  bool allowPluginPath = false;
};

// --strict on the verbs that load a scene: warnings (an unsupported X3D node
// skipped, an unquoted MFString read as one string, ...) become errors.
inline void addStrictFlag(CLI::App* cmd, bool& strict) {
  cmd->add_flag("--strict", strict, "Treat every warning of the scene loader as an error (exit 2)");
}

// --set TYPE.FIELD=VALUE on the verbs that load a scene (repeatable): the
// field of every node of that type, set before the node initialises (SI units).
inline void addSetOption(CLI::App* cmd, std::vector<std::string>& sets) {
  cmd->add_option("--set", sets,
                  "TYPE.FIELD=VALUE: set a field of every node of that type before it initialises (repeatable; SI "
                  "units), e.g. BarbicRenderer.pointShellScale=2 or VolumeObject.voxelSize='0.00005 0.00005 0.00005'")
      ->check(CLI::Validator(
          [](std::string& v) {
            return parseFieldOverride(v) ? std::string() : "expected TYPE.FIELD=VALUE, e.g. MillTool.tipRadius=0.0008";
          },
          "TYPE.FIELD=VALUE"));
}
inline void applySetOptions(LoadOptions& options, const std::vector<std::string>& sets) {
  for (const std::string& s : sets) options.overrides.push_back(*parseFieldOverride(s));
}

void addBenchCommand(CLI::App& app, int& result);
void addCheckCommand(CLI::App& app, const GlobalOptions& global, int& result);
void addDevicesCommand(CLI::App& app, int& result);
void addNodesCommand(CLI::App& app, int& result);
void addPhantomCommand(CLI::App& app, int& result);
void addReplayCommand(CLI::App& app, const GlobalOptions& global, int& result);
void addRenderCommand(CLI::App& app, const GlobalOptions& global, int& result);
void addReportCommand(CLI::App& app, int& result);
void addRunCommand(CLI::App& app, const GlobalOptions& global, int& result);
void addSweepCommand(CLI::App& app, int& result);

}  // namespace millsim::app
