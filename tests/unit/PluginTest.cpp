// ImportLibrary: a node type from a plugin library, and the path rules.
#include <gtest/gtest.h>

#include "TestFiles.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/core/Plugin.h"
#include "millsim/session/Session.h"
#include "millsim/x3d/X3DLoader.h"

#include <algorithm>

using namespace millsim;
using millsim::test::ScratchDir;
using millsim::test::x3d;

namespace {
const std::filesystem::path kPluginDir = MILLSIM_BINARY_DIR "/tests/plugins";
const std::string kPlugin = "libmillsim_sample_plugin.so";

LoadOptions withSearchPath(std::vector<std::filesystem::path> dirs, bool allowAny = false) {
  LoadOptions o;
  o.plugins.searchPath = std::move(dirs);
  o.plugins.allowAnyPath = allowAny;
  return o;
}
}  // namespace

TEST(Plugins, NodeFromAPluginFoundOnTheSearchPath) {
  ScratchDir dir;
  auto scene = dir.write("s.x3d", x3d(R"(<ImportLibrary url='"libmillsim_sample_plugin.so"'/>
<Landmark DEF="L" label="mesial cusp" position="0 0.004 0" radius="0.0005"/>)"));
  auto r = loadSceneFile(scene, builtinRegistry(), withSearchPath({kPluginDir}));
  ASSERT_TRUE(r.ok()) << r.report();
  auto n = r.scene->def("L");
  ASSERT_TRUE(n);
  EXPECT_EQ(n->typeName(), "Landmark");
  EXPECT_EQ(n->field("label")->toString(), "mesial cusp");
  EXPECT_EQ(r.scene->plugins.size(), 1u);
  // The plugin's types live in this scene's registry, not in the built-in one.
  EXPECT_EQ(builtinRegistry().find("Landmark"), nullptr);
}

// H3DAPI writes ImportLibrary library="..." (unquoted, one name): read as url, with a warning for the quotes.
TEST(Plugins, H3dApiLibraryFieldLoadsWithTheSamePathRules) {
  ScratchDir dir;
  auto scene = dir.write("s.x3d", x3d(R"(<ImportLibrary library="libmillsim_sample_plugin.so"/><Landmark/>)"));
  auto r = loadSceneFile(scene, builtinRegistry(), withSearchPath({kPluginDir}));
  ASSERT_TRUE(r.ok()) << r.report();
  EXPECT_EQ(r.scene->plugins.size(), 1u);
  EXPECT_NE(r.report().find("unquoted MFString value for field 'library'"), std::string::npos) << r.report();
  const std::string abs = (kPluginDir / kPlugin).string();
  auto absScene = dir.write("abs.x3d", x3d("<ImportLibrary library='\"" + abs + "\"'/>"));
  auto refused = loadSceneFile(absScene, builtinRegistry(), withSearchPath({}));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.report().find("refusing plugin path"), std::string::npos) << refused.report();
}

TEST(Plugins, ShortNamesAreExpandedAndTheSceneFolderIsSearched) {
  ScratchDir dir;
  std::filesystem::copy_file(kPluginDir / kPlugin, dir.path() / kPlugin);
  auto scene = dir.write("s.x3d", x3d(R"(<ImportLibrary url='"millsim_sample_plugin"'/><Landmark/>)"));
  auto r = loadSceneFile(scene, builtinRegistry(), withSearchPath({}));
  EXPECT_TRUE(r.ok()) << r.report();
}

TEST(Plugins, PluginFieldsAreValidatedLikeBuiltIns) {
  ScratchDir dir;
  auto scene = dir.write("s.x3d", x3d(R"(<ImportLibrary url='"libmillsim_sample_plugin.so"'/>
<Landmark radius="-1"/>)"));
  auto r = loadSceneFile(scene, builtinRegistry(), withSearchPath({kPluginDir}));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.report().find("outside the expected range > 0"), std::string::npos) << r.report();
}

TEST(Plugins, AbsoluteAndParentPathsAreRefusedUnlessAllowed) {
  ScratchDir dir;
  const std::string abs = (kPluginDir / kPlugin).string();
  auto absScene = dir.write("abs.x3d", x3d("<ImportLibrary url='\"" + abs + "\"'/>"));
  auto r = loadSceneFile(absScene, builtinRegistry(), withSearchPath({}));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.report().find("refusing plugin path"), std::string::npos) << r.report();
  EXPECT_NE(r.report().find("--allow-plugin-path"), std::string::npos);

  auto sub = dir.path() / "sub";
  std::filesystem::create_directories(sub);
  std::filesystem::copy_file(kPluginDir / kPlugin, dir.path() / kPlugin);
  auto upScene = dir.write("sub/up.x3d", x3d("<ImportLibrary url='\"../" + kPlugin + "\"'/>"));
  auto up = loadSceneFile(upScene, builtinRegistry(), withSearchPath({}));
  ASSERT_FALSE(up.ok());
  EXPECT_NE(up.report().find("refusing plugin path"), std::string::npos);

  EXPECT_TRUE(loadSceneFile(absScene, builtinRegistry(), withSearchPath({}, true)).ok());
  EXPECT_TRUE(loadSceneFile(upScene, builtinRegistry(), withSearchPath({}, true)).ok());
}

TEST(Plugins, MissingOrForeignLibrariesAreClearErrors) {
  ScratchDir dir;
  auto missing = dir.write("m.x3d", x3d(R"(<ImportLibrary url='"libnothere.so"'/>)"));
  auto r = loadSceneFile(missing, builtinRegistry(), withSearchPath({}));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.report().find("not found; looked in"), std::string::npos) << r.report();

  dir.write("libfake.so", "not an ELF file");
  auto fake = dir.write("f.x3d", x3d(R"(<ImportLibrary url='"libfake.so"'/>)"));
  auto f = loadSceneFile(fake, builtinRegistry(), withSearchPath({}));
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.report().find("cannot load plugin"), std::string::npos) << f.report();
}

TEST(Plugins, EnvironmentSearchPathIsColonSeparated) {
  setenv("MILLSIM_PLUGIN_PATH", "/a:/b/c::/d", 1);
  auto dirs = pluginPathFromEnvironment();
  unsetenv("MILLSIM_PLUGIN_PATH");
  ASSERT_EQ(dirs.size(), 3u);
  EXPECT_EQ(dirs[1], "/b/c");
}

// A plugin's renderer (SpherePenaltyRenderer, tests/plugin) takes a device's
// hapticsRenderer like a built-in one: it pushes the burr out of the tooth,
// mills it, and a live run prepares it beside the built-in ones.
TEST(Plugins, APluginRendererRendersAndMillsThroughASession) {
  ScratchDir dir;
  (void)dir.write("press.csv", "t,x,y,z,qw,qx,qy,qz,button\n0,0,0.0125,0,1,0,0,0,0\n"
                                                  "0.4,0,0.0088,0,1,0,0,0,0\n0.41,0,0.0088,0,1,0,0,0,1\n"
                                                  "0.6,0,0.0085,0,1,0,0,0,1\n");
  auto scene = dir.write("s.x3d", x3d(R"(<ImportLibrary url='"libmillsim_sample_plugin.so"'/>
<VolumeObject url='"phantom:tooth"' isoValue="700"/>
<TrajectoryDevice url='"press.csv"'>
  <MillTool tipRadius="0.0006" shaftRadius="0.0004" shaftLength="0.015"/>
  <SpherePenaltyRenderer stiffness="800"/>
</TrajectoryDevice>)"));
  auto r = loadSceneFile(scene, builtinRegistry(), withSearchPath({kPluginDir}));
  ASSERT_TRUE(r.ok()) << r.report();
  SessionOptions options;
  options.prepareRenderers = true;
  auto session = Session::openDevice(*r.scene, options);
  EXPECT_EQ(session->rendererName(), "SpherePenaltyRenderer");
  const auto prepared = session->preparedRenderers();
  EXPECT_NE(std::find(prepared.begin(), prepared.end(), "SpherePenaltyRenderer"), prepared.end());
  EXPECT_EQ(prepared.size(), 4u) << "the three built-in renderers and the plugin's";
  double pressing = 0.0;  // the largest upward force before the burr spins
  session->observe([&](const FrameRecord& f) {
    if (!f.button) pressing = std::max(pressing, f.force.y);
  });
  while (session->stepSimulated() && session->loop().stats().frames < 600) {
  }
  const SessionResult s = session->finish();
  EXPECT_GT(s.stats.contactFrames, 0);
  EXPECT_GT(pressing, 0.1) << "pressed into the occlusal surface, it pushes up (N)";
  EXPECT_GT(s.stats.removedVolume, 0.0) << "and the burr mills";
}
