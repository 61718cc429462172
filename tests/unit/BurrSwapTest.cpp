// Swapping the burr while running (issue 18, part 2): the B key or a MillTool
// field change hands the rendering algorithm, compiled again for the new burr,
// to the loop with that burr, cross-faded like a renderer swap; a renderer
// that cannot render the burr refuses it and the fields go back; a review of
// the run's log swaps at the same frame.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/RecordedRun.h"
#include "millsim/devices/TrajectoryDevice.h"
#include "millsim/run/FrameLog.h"
#include "millsim/run/RendererPool.h"
#include "millsim/session/Replay.h"
#include "millsim/run/RunSetup.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;

namespace {

const std::string kScene = MILLSIM_SOURCE_DIR "/x3d/default.x3d";

// Down into the occlusal surface with the burr on, then hold.
Trajectory plunge() {
  return Trajectory::parse("t,x,y,z,qw,qx,qy,qz,button\n0,0,0.0125,0,1,0,0,0,1\n0.15,0,0.0086,0,1,0,0,0,1\n"
                           "0.4,0,0.0082,0,1,0,0,0,1\n",
                           "plunge.csv");
}

// A live run in simulated time: the scene, its compiled run, the pool and the loop.
struct LiveRun {
  LoadResult loaded;
  CompiledRun run;
  std::unique_ptr<RendererPool> pool;
  std::unique_ptr<HapticLoop> loop;
  std::string log;

  explicit LiveRun(const std::string& renderer) : loaded(loadSceneFile(kScene, builtinRegistry())) {
    EXPECT_TRUE(loaded.ok()) << loaded.report();
    run = compileRun(*loaded.scene, renderer);
    run.settings.timing = false;  // frame_us 0, as a replay writes it
    pool = std::make_unique<RendererPool>(*loaded.scene, run, run.algorithm.get());
    loop = std::make_unique<HapticLoop>(*run.scene, std::move(run.algorithm), makeTrajectoryDriver(plunge(), false),
                                        run.settings);
    log = frameLogHeader();
  }
  MillTool& tool() { return *run.device->tool.get(); }
  // Steps `n` frames, keeping the log, and returns the last frame's record.
  FrameRecord step(int n) {
    FrameRecord last;
    for (int i = 0; i < n; ++i) {
      loop->stepSimulated();
      loop->records().drain([&](const FrameRecord& r) {
        appendFrameRow(log, r);
        last = r;
      });
      pool->collect(*loop);
    }
    return last;
  }
};

}  // namespace

TEST(BurrSwap, TheNewBurrMillsFromTheFrameTheSwapLands) {
  LiveRun live("SurfacePointRenderer");
  const FrameRecord before = live.step(200);
  ASSERT_TRUE(before.tool.round());
  ASSERT_GT(before.removedVolume, 0.0) << "the round burr is milling";

  live.tool().shape.set("cylinder");
  EXPECT_EQ(live.pool->followTool(*live.loop), "burr: cylinder, tip radius 0.6 mm");
  EXPECT_EQ(live.pool->tool().shape, BurrShape::Cylinder);
  const FrameRecord after = live.step(1);
  EXPECT_EQ(after.tool.shape, BurrShape::Cylinder) << "the frame after the swap mills with the cylinder";
  EXPECT_EQ(after.tool.tipLength, live.tool().geometry().tipLength);
  EXPECT_STREQ(after.renderer, "SurfacePointRenderer") << "the same renderer, compiled for the new burr";
  EXPECT_EQ(live.pool->followTool(*live.loop), "") << "nothing more to swap";

  // The flat cylinder end sweeps more than the ball's cap at the same plunge.
  const double atSwap = after.removedVolume;
  const FrameRecord end = live.step(200);
  EXPECT_EQ(end.tool.shape, BurrShape::Cylinder);
  EXPECT_GT(end.removedVolume, atSwap);
}

TEST(BurrSwap, ARendererThatCannotRenderTheBurrRefusesItAndTheFieldsGoBack) {
  LiveRun live("LineProxyRenderer");
  live.step(50);
  live.tool().shape.set("taper");
  const std::string said = live.pool->followTool(*live.loop);
  EXPECT_NE(said.find("LineProxyRenderer cannot render a taper burr"), std::string::npos) << said;
  EXPECT_NE(said.find("the round burr stays"), std::string::npos) << said;
  EXPECT_EQ(live.tool().shape.get(), "round") << "the scene graph says which burr mills";
  EXPECT_TRUE(live.step(1).tool.round());

  // An invalid burr is refused with the reason, whatever renders.
  live.tool().shape.set("inverted-cone");
  live.tool().tipEndRadius.set(0.002f);
  const std::string invalid = live.pool->followTool(*live.loop);
  EXPECT_NE(invalid.find("tipEndRadius 0.002 is larger than tipRadius 0.0006"), std::string::npos) << invalid;
  EXPECT_EQ(live.tool().shape.get(), "round");
  EXPECT_EQ(live.tool().tipEndRadius.get(), 0.0005f);
}

TEST(BurrSwap, APoolForANonRoundBurrKeepsTheRendererThatCannotRenderItAsARefusal) {
  LiveRun live("BarbicRenderer");
  live.tool().shape.set("cylinder");
  ASSERT_EQ(live.pool->followTool(*live.loop), "burr: cylinder, tip radius 0.6 mm");
  live.step(5);
  const std::size_t lineProxy = 0;  // key 1
  ASSERT_EQ(live.pool->typeName(lineProxy), "LineProxyRenderer");
  const std::string said = live.pool->select(lineProxy, *live.loop);
  EXPECT_NE(said.find("LineProxyRenderer cannot render this burr"), std::string::npos) << said;
  EXPECT_EQ(live.pool->select(1, *live.loop), "switched to SurfacePointRenderer") << "#2 was compiled for the cylinder";
  EXPECT_EQ(live.step(1).tool.shape, BurrShape::Cylinder);
  // Back to round: #1 can render it again.
  live.tool().shape.set("round");
  EXPECT_EQ(live.pool->followTool(*live.loop), "burr: round, tip radius 0.6 mm");
  live.step(120);  // past the cross-fade
  EXPECT_EQ(live.pool->select(lineProxy, *live.loop), "switched to LineProxyRenderer");
}

TEST(BurrSwap, AReviewSwapsTheBurrAtTheFrameTheRunDid) {
  LiveRun live("SurfacePointRenderer");
  live.step(150);
  live.tool().shape.set("cylinder");
  ASSERT_FALSE(live.pool->followTool(*live.loop).empty());
  live.step(150);
  live.loop->finish();
  live.loop->records().drain([&](const FrameRecord& r) { appendFrameRow(live.log, r); });

  const RecordedRun recorded = RecordedRun::parse(live.log, "run.csv");
  ASSERT_EQ(recorded.tools().size(), 2u);
  EXPECT_EQ(recorded.frames()[149].tool, 0);
  EXPECT_EQ(recorded.frames()[150].tool, 1) << "the log says at which frame the burr changed";

  LoadResult again = loadSceneFile(kScene, builtinRegistry());
  ASSERT_TRUE(again.ok());
  std::ostringstream review;
  replayRecorded(*again.scene, recorded, &review, ReplayOptions{});
  EXPECT_EQ(review.str(), live.log) << "the review equals the run, bit for bit, burr swap included";
}

TEST(BurrSwap, AMalformedToolCellNamesTheLine) {
  const std::string header = "t,x,y,z,qw,qx,qy,qz,fx,button,period_us,tool\n";
  try {
    RecordedRun::parse(header + "0,0,0,0,1,0,0,0,0,0,1000,round 0.0006 0.002 0.0005 0.0004 0.015\n" +
                           "0.001,0,0,0,1,0,0,0,0,0,1000,square 0.0006 0.002 0.0005 0.0004 0.015\n",
                       "run.csv");
    FAIL() << "a tool cell of an unknown shape was read";
  } catch (const TrajectoryError& e) {
    EXPECT_NE(std::string(e.what()).find("run.csv:3: column 'tool' is not a burr"), std::string::npos) << e.what();
  }
  ToolGeometry t;
  EXPECT_TRUE(parseToolCell(toolCell(ToolGeometry{}), t));
  EXPECT_TRUE(t == ToolGeometry{});
  EXPECT_FALSE(parseToolCell("round 0.001 0.002 0.0005 0.0004", t)) << "a missing number";
  EXPECT_FALSE(parseToolCell("round 0.001 0.002 0.0005 0.0004 0.02 7", t)) << "one too many";
  EXPECT_FALSE(parseToolCell("round nan 0.002 0.0005 0.0004 0.02", t));
}
