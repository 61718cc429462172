// The bare command loads no voxel code (issue 15, part 5): `millsim --version`
// and `millsim nodes` run in the command itself, which links only
// libmillsim_scene, and never map libmillsim or OpenVDB (27 MB resident on
// Debian); every verb that loads a scene opens libmillsim_cli, and with it
// libmillsim and OpenVDB. Runs the built command with the dynamic loader's
// own record of the files it loads (LD_DEBUG=files).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "TestFiles.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;

struct CommandRun {
  int exitCode = -1;
  std::string loaded;  // every "file=NAME" the dynamic loader reported, one per line
};

// Runs the millsim command with `args` and returns its exit code and the files the loader loaded.
CommandRun runCommand(const std::vector<std::string>& args) {
  const millsim::test::ScratchDir scratch;
  const fs::path debug = scratch.path() / "ld";
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  env.push_back("LD_DEBUG=files");
  env.push_back("LD_DEBUG_OUTPUT=" + debug.string());
  std::vector<std::string> argv{MILLSIM_COMMAND};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> argp, envp;
  for (auto& a : argv) argp.push_back(a.data());
  for (auto& e : env) envp.push_back(e.data());
  argp.push_back(nullptr);
  envp.push_back(nullptr);

  posix_spawn_file_actions_t quiet;
  posix_spawn_file_actions_init(&quiet);
  posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  CommandRun run;
  const int spawned = posix_spawn(&pid, argp[0], &quiet, nullptr, argp.data(), envp.data());
  posix_spawn_file_actions_destroy(&quiet);
  EXPECT_EQ(spawned, 0) << "cannot start " << argp[0];
  if (spawned != 0) return run;
  int status = 0;
  waitpid(pid, &status, 0);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  // The loader writes ld.<pid>.
  std::ifstream in(debug.string() + "." + std::to_string(pid));
  std::string line;
  while (std::getline(in, line))
    if (const auto at = line.find("file="); at != std::string::npos)
      run.loaded += line.substr(at + 5, line.find_first_of(" \t", at + 5) - at - 5) + "\n";
  return run;
}

bool loads(const CommandRun& run, const std::string& prefix) {
  std::istringstream lines(run.loaded);
  std::string name;
  while (std::getline(lines, name))
    if (fs::path(name).filename().string().rfind(prefix, 0) == 0) return true;
  return false;
}

TEST(BareCommand, VersionAndNodesLoadNeitherLibmillsimNorOpenVdb) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--version"}, {"nodes"}, {"nodes", "--markdown"}}) {
    const CommandRun run = runCommand(args);
    SCOPED_TRACE("millsim " + args.front());
    EXPECT_EQ(run.exitCode, 0);
    EXPECT_TRUE(loads(run, "libmillsim_scene")) << "the loader's record is empty or wrong:\n" << run.loaded;
    EXPECT_FALSE(loads(run, "libopenvdb")) << run.loaded;
    EXPECT_FALSE(loads(run, "libmillsim.so")) << run.loaded;
    EXPECT_FALSE(loads(run, "libmillsim_cli")) << run.loaded;
  }
}

TEST(BareCommand, AVerbThatLoadsASceneOpensTheVerbsWithOpenVdb) {
  const CommandRun run = runCommand({"check", std::string(MILLSIM_SOURCE_DIR) + "/x3d/default.x3d"});
  EXPECT_EQ(run.exitCode, 0);
  EXPECT_TRUE(loads(run, "libmillsim_cli")) << run.loaded;
  EXPECT_TRUE(loads(run, "libmillsim.so")) << run.loaded;
  EXPECT_TRUE(loads(run, "libopenvdb")) << run.loaded;
}

}  // namespace
