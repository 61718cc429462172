// Sweep files (sweep/SweepFile.h; issue 46): the grid's cells and their
// commands, and every mistake refused with its line, column and what was
// expected, before anything runs.
#include <gtest/gtest.h>

#include <fstream>

#include "TestFiles.h"
#include "sweep/SweepCells.h"
#include "sweep/SweepFile.h"

using namespace millsim::sweep;
using millsim::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

struct Folder {
  ScratchDir dir;
  Folder() {
    fs::create_directories(dir.path() / "logs");
    for (const char* f : {"scene.x3d", "path.csv", "logs/run_2.csv", "logs/run_10.csv", "logs/run_1.csv"})
      std::ofstream(dir.path() / f) << "x\n";
  }
  fs::path sweep(const std::string& text) const { return dir.write("grid.json", text); }
  Sweep read(const std::string& text, bool yes = false) const {
    SweepContext context;
    context.renderers = {"LineProxyRenderer", "BarbicRenderer"};
    context.yes = yes;
    return readSweep(sweep(text), context);
  }
  std::string error(const std::string& text, bool yes = false) const {
    try {
      read(text, yes);
    } catch (const SweepError& e) {
      return e.what();
    }
    return "(no error)";
  }
};

const std::string kReplay = R"({"verb": "replay", "fixed": {"scene": "scene.x3d", "trajectory": "path.csv"},)";

}  // namespace

TEST(SweepFile, CellsVaryTheLastAxisFastestAndCarryTheirCommand) {
  Folder f;
  const Sweep s = f.read(kReplay + R"(
    "grid": {"renderer": ["LineProxyRenderer", "BarbicRenderer"], "rate": [990, 1000.5, 1010], "set": ["MillTool.tipRadius=0.001"]}})");
  EXPECT_EQ(s.name, "grid");
  ASSERT_EQ(s.cellCount(), 6u);
  const Cell c = cellAt(s, 4);
  EXPECT_EQ(c.id, "0004");
  EXPECT_EQ(c.values, (std::vector<std::string>{"BarbicRenderer", "1000.5", "MillTool.tipRadius=0.001"}));
  const std::string scene = (fs::weakly_canonical(f.dir.path()) / "scene.x3d").string();
  const std::string path = (fs::weakly_canonical(f.dir.path()) / "path.csv").string();
  EXPECT_EQ(c.args, (std::vector<std::string>{"replay", scene, "--trajectory", path, "--renderer", "BarbicRenderer", "--rate",
                                              "1000.5", "--set", "MillTool.tipRadius=0.001", "--log", "log.csv", "--report",
                                              "report.json"}));
  EXPECT_EQ(shellQuoted({"a b", "it's", "x=1"}), "'a b' 'it'\\''s' x=1");
}

TEST(SweepFile, ANameFromTheFileIsOneWord) {
  Folder f;
  SweepContext context;
  const Sweep s = readSweep(f.dir.write("my grid #2.json", kReplay + R"("grid": {"rate": [1000]}})"), context);
  EXPECT_EQ(s.name, "my_grid__2");
}

TEST(SweepFile, AGlobOfSessionLogsIsOneAxisInNaturalOrder) {
  Folder f;
  const Sweep s = f.read(R"({"verb": "replay", "fixed": {"scene": "scene.x3d"}, "grid": {"trajectory": {"glob": "logs/*.csv"}}})");
  ASSERT_EQ(s.cellCount(), 3u);
  std::vector<std::string> shown;
  for (const std::string& v : s.axes[0].values) shown.push_back(shownValue(s, s.axes[0], v));
  EXPECT_EQ(shown, (std::vector<std::string>{"logs/run_1.csv", "logs/run_2.csv", "logs/run_10.csv"}));
}

TEST(SweepFile, MistakesAreRefusedWithTheirLineAndWhatWasExpected) {
  Folder f;
  auto expectError = [&](const std::string& text, const std::string& want, bool yes = false) {
    const std::string e = f.error(text, yes);
    EXPECT_NE(e.find(want), std::string::npos) << "got: " << e << "\nwanted: " << want;
  };
  expectError("{\"verb\": \"replay\",\n  \"grid\": {\"rate\": [1000,]}}", "grid.json:2:26: not JSON: syntax error while parsing value - unexpected ']'");
  expectError(R"({"verb": "bench resolution", "grid": {"renderer": ["BarbicRenderer"]}})",
              "grid.json:1:10: unknown verb 'bench resolution'; expected replay, bench physical, bench procedure, bench "
              "stability or bench zwidth (MillSim has no `bench resolution` yet)");
  expectError(kReplay + "\n \"grid\": {\"rate\": [1000]}, \"colour\": 1}",
              "grid.json:2:28: unknown key \"colour\"; expected sweep, verb, fixed, grid or slurm");
  expectError(kReplay + "\n \"grid\": {\"rates\": [1000]}}",
              "grid.json:2:11: unknown parameter \"rates\" of replay; expected scene, trajectory, renderer, rate or set");
  expectError(kReplay + "\n \"grid\": {\"renderer\": [\"Barbic\"]}}",
              "grid.json:2:24: unknown renderer 'Barbic'; registered: LineProxyRenderer and BarbicRenderer");
  expectError(kReplay + "\n \"grid\": {}}", "grid.json:2:10: the grid is empty");
  expectError(kReplay + "\n \"grid\": {\"rate\": []}}", "grid.json:2:19: an empty list: a grid axis needs at least one value");
  expectError(kReplay + "\n \"grid\": {\"rate\": [0]}}", "grid.json:2:20: \"rate\" 0 is outside 1 to 20000 (haptic rate, Hz)");
  expectError(kReplay + "\n \"grid\": {\"rate\": [1000, 1000]}}", "grid.json:2:26: '1000' is given twice for \"rate\"");
  expectError(kReplay + "\n \"grid\": {\"rate\": [1000, 1e3]}}", "grid.json:2:26: '1e3' is given twice for \"rate\"");
  expectError(R"({"verb": "bench stability", "fixed": {"seed": 1.5}, "grid": {"mass": [0.1]}})",
              "grid.json:1:47: \"seed\" 1.5 is not a whole number");
  expectError("{\"verb\": \"replay\", \"grid\": [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]}",
              "lists and objects nested deeper than 64");
  expectError(kReplay + "\n \"grid\": {\"scene\": [\"scene.x3d\"]}}",
              "grid.json:2:11: \"scene\" is both fixed (line 1) and on the grid");
  expectError(R"({"verb": "replay", "grid": {"trajectory": ["path.csv"]}})",
              "grid.json:1:1: replay needs \"scene\" (the X3D scene), in \"fixed\" or on the grid");
  expectError(R"({"verb": "replay", "fixed": {"scene": "../scene.x3d"}, "grid": {"trajectory": ["path.csv"]}})",
              "'../scene.x3d' lies outside the sweep's folder");
  expectError(R"({"verb": "replay", "fixed": {"scene": "nope.x3d"}, "grid": {"trajectory": ["path.csv"]}})",
              "grid.json:1:39: no such file 'nope.x3d'");
  expectError(R"({"verb": "replay", "fixed": {"scene": "scene.x3d"}, "grid": {"trajectory": {"glob": "../*.csv"}}})",
              "must name files below the sweep's folder");
  expectError(kReplay + R"("grid": {"set": ["tipRadius=1"]}})", "'tipRadius=1' is not TYPE.FIELD=VALUE");
  expectError(kReplay + R"("grid": {"rate": [1000]}, "slurm": {"max_parallel": 0}})",
              "\"max_parallel\" is how many cells run at once: a whole number from 1 to 100000");
  // A grid of 101 × 100 cells needs --yes; one of 10⁷ is refused even so.
  std::string sets, rates, many;
  for (int i = 0; i < 101; ++i) sets += std::string(i ? "," : "") + "\"MillTool.tipRadius=" + std::to_string(i + 1) + "e-5\"";
  for (int i = 0; i < 100; ++i) rates += std::string(i ? "," : "") + std::to_string(900 + i);
  const std::string big = kReplay + "\"grid\": {\"set\": [" + sets + "], \"rate\": [" + rates + "]}}";
  expectError(big, "the grid has 10100 cells (101 set × 100 rate), more than 10000: pass --yes to run them all");
  EXPECT_EQ(f.read(big, true).cellCount(), 10100u);
  for (int i = 0; i < 1001; ++i) many += std::string(i ? "," : "") + "\"MillTool.tipRadius=" + std::to_string(i + 1) + "e-6\"";
  for (int i = 0; i < 1000; ++i) rates += "," + std::to_string(2000 + i);
  expectError(kReplay + "\"grid\": {\"set\": [" + many + "], \"rate\": [" + rates + "], \"renderer\": [\"BarbicRenderer\", \"LineProxyRenderer\"]}}",
              "the grid has more than 1000000 cells (1001 set × 1100 rate × 2 renderer); split the sweep", true);
}

TEST(SweepCells, ACellIsDoneOnlyWithExitZeroForTheCommandItNowHas) {
  Folder f;
  const Sweep s = f.read(kReplay + R"("grid": {"rate": [990, 1000]}})");
  const fs::path out = defaultOutput(s);
  const Cell c = cellAt(s, 1);
  EXPECT_EQ(stateOf(out, c), CellState::Pending);
  fs::create_directories(cellFolder(out, c));
  writeStatus(cellFolder(out, c), {1, 0.5, "h", "local", shellQuoted(c.args), "t"});
  EXPECT_EQ(stateOf(out, c), CellState::Failed);
  writeStatus(cellFolder(out, c), {0, 0.5, "h", "local", shellQuoted(c.args), "t"});
  EXPECT_EQ(stateOf(out, c), CellState::Done);
  writeStatus(cellFolder(out, c), {0, 0.5, "h", "local", "replay something else", "t"});
  EXPECT_EQ(stateOf(out, c), CellState::Stale);
  std::ofstream(cellFolder(out, c) / "status.json") << "{ torn";
  EXPECT_EQ(stateOf(out, c), CellState::Pending);
}
