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
  std::string loaded;  // the path of every object the dynamic loader initialised, one per line
};

// Runs the millsim command with `args` and returns its exit code and the files the loader loaded.
CommandRun runCommand(const std::vector<std::string>& args, const std::string& libraryPath = "") {
  const millsim::test::ScratchDir scratch;
  const fs::path debug = scratch.path() / "ld";
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  env.push_back("LD_DEBUG=files");
  env.push_back("LD_DEBUG_OUTPUT=" + debug.string());
  if (!libraryPath.empty()) env.push_back("LD_LIBRARY_PATH=" + libraryPath);
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
  // One "calling init: PATH" line per object loaded (the "file=" lines repeat).
  const std::string init = "calling init: ";
  while (std::getline(in, line))
    if (const auto at = line.find(init); at != std::string::npos) run.loaded += line.substr(at + init.size()) + "\n";
  return run;
}

// How many times the loader loaded a file whose name starts with `prefix`.
int loadCount(const CommandRun& run, const std::string& prefix) {
  std::istringstream lines(run.loaded);
  std::string name;
  int n = 0;
  while (std::getline(lines, name))
    if (fs::path(name).filename().string().rfind(prefix, 0) == 0) ++n;
  return n;
}
bool loads(const CommandRun& run, const std::string& prefix) { return loadCount(run, prefix) > 0; }

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

// A VolumeObject opens libmillsim for its voxels (VolumeModule.h). Where the
// process already has it — here a copy the verbs found first, through
// LD_LIBRARY_PATH — that copy is used, not a second one from next to
// libmillsim_scene (two copies would hold two sets of the voxel code's
// statics and type information).
TEST(BareCommand, AVolumeUsesTheLibmillsimAlreadyLoaded) {
  const millsim::test::ScratchDir copy;
  fs::copy_file(MILLSIM_VOLUME_LIBRARY, copy.path() / MILLSIM_VOLUME_SONAME);
  const CommandRun run = runCommand({"check", std::string(MILLSIM_SOURCE_DIR) + "/x3d/default.x3d"}, copy.path().string());
  EXPECT_EQ(run.exitCode, 0);
  EXPECT_EQ(loadCount(run, "libmillsim.so"), 1) << run.loaded;
  EXPECT_NE(run.loaded.find((copy.path() / MILLSIM_VOLUME_SONAME).string()), std::string::npos)
      << "the copy was not the one loaded:\n" << run.loaded;
}

}  // namespace
