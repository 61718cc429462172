#pragma once
// libmillsim_cli: every verb of the millsim command that loads a scene's
// voxels or runs it (check, replay, run, render, bench, report, phantom) and
// so needs libmillsim and OpenVDB. The command itself links only
// libmillsim_scene and opens this library on demand (main.cpp), so that
// `millsim --version` and `millsim nodes` map no OpenVDB.

namespace millsim::app {

// Bumped whenever this table changes incompatibly.
inline constexpr int kCliAbiVersion = 1;

struct CliModule {
  int abiVersion;
  int (*main)(int argc, char** argv);  // the whole command line, every verb
};

}  // namespace millsim::app
