// millsim replay SCENE.x3d --trajectory T.csv --log LOG.csv: steps the scene's
// device renderer open-loop through a trajectory in simulated time; given a
// run's log instead, it steps through that run's recorded frames (review).
// --sound-out writes the milling sound in the same simulated time, so it too is
// the same bytes on every run.
#include <fstream>
#include <iostream>
#include <optional>

#include "Commands.h"
#include "StderrProgress.h"
#include "ImageArgs.h"
#include "NumberArgs.h"
#include "TrajectoryReach.h"
#include "RunSummary.h"
#include "SaveMesh.h"
#include "SaveVolume.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/session/Session.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::app {

void addReplayCommand(CLI::App& app, const GlobalOptions& global, int& result) {
  auto* cmd = app.add_subcommand("replay", "Replay a trajectory through the scene's haptics renderer (deterministic)");
  struct Args {
    bool strict = false;
    std::vector<std::string> sets;
    std::string scene, trajectory, log, soundOut, saveVolume, saveMesh, report;
    struct {
      std::string renderer;
      double rate = 0.0;
      bool timing = false;
    } options;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("scene", args->scene, "X3D scene file")->required();
  addStrictFlag(cmd, args->strict);
  addSetOption(cmd, args->sets);
  cmd->add_option("--trajectory", args->trajectory,
                  "Trajectory CSV (t,x,y,z,qw,qx,qy,qz,button), or the --log of a `millsim run` to review that run "
                  "frame by frame")
      ->required();
  cmd->add_option("--log", args->log, "Log CSV to write (one row per haptic frame)");
  cmd->add_option("--sound-out", args->soundOut, "WAV file of the milling sound (16-bit PCM mono, the replay's length)");
  cmd->add_option("--renderer", args->options.renderer,
                  "Use a default renderer of this type instead of the scene's (e.g. SurfacePointRenderer)");
  cmd->add_option("--rate", args->options.rate, "Haptic rate in Hz (default: the device's desiredHapticsRate)")
      ->check(finiteIn(1, 20000, "Hz (the range of desiredHapticsRate)"));
  cmd->add_option("--save-volume", args->saveVolume,
                  "At the end, write the milled volume to this .vdb file (a VolumeObject url loads it back)");
  cmd->add_option("--save-mesh", args->saveMesh,
                  "At the end, write the milled surface in millimetres: .stl the whole, .obj (with an .mtl) or "
                  ".ply a solid per tissue in its colour (a VolumeObject url loads it back with meshUnit='0.001')");
  cmd->add_option("--report", args->report,
                  "Write the lesson report (JSON: removed volume, peak force, targets, forbidden regions, score)");
  cmd->add_flag("--timing", args->options.timing,
                "Log measured compute time per frame (frame_us); without it the log is byte-identical run to run");
  cmd->callback([args, &global, &result] {
    LoadOptions lo;
    lo.plugins.allowAnyPath = global.allowPluginPath;
    lo.strict = args->strict;
    applySetOptions(lo, args->sets);
    StderrProgress progress;
    lo.progress = &progress;
    LoadResult r = loadSceneFile(args->scene, builtinRegistry(), lo);
    std::cerr << r.report();
    if (!r.ok()) {
      result = kExitBadInput;
      return;
    }
    try {
      if (!args->soundOut.empty()) checkWritable(args->soundOut, "--sound-out");
      if (!args->saveVolume.empty()) checkSaveVolume(*r.scene, args->saveVolume);
      if (!args->saveMesh.empty()) checkSaveMesh(*r.scene, args->saveMesh);
      if (!args->report.empty()) checkWritable(args->report, "--report");
      // A trajectory, or a run's frame log: that replays the run's own frames (review).
      const std::string text = readTrajectoryText(args->trajectory);
      std::optional<RecordedRun> recorded;
      std::optional<Trajectory> trajectory;
      if (RecordedRun::isFrameLog(text))
        recorded = RecordedRun::parse(text, args->trajectory);
      else
        trajectory = Trajectory::parse(text, args->trajectory);
      if (trajectory) warnOutOfReach(*r.scene, *trajectory, args->trajectory, "replay");
      std::ofstream log;
      if (!args->log.empty()) {
        log.open(args->log, std::ios::binary);
        if (!log) throw std::runtime_error(args->log + ": cannot write the log file");
      }
      SessionOptions o;
      o.renderer = args->options.renderer;
      o.rate = args->options.rate;
      o.timing = args->options.timing;
      o.log = args->log.empty() ? nullptr : &log;
      o.soundOut = args->soundOut;
      if (recorded)
        std::cout << "replaying a recorded run: " << recorded->frames().size() << " frames from "
                  << args->trajectory << "\n";
      auto session = recorded ? Session::review(*r.scene, *recorded, o) : Session::replay(*r.scene, *trajectory, o);
      const SessionResult s = session->runSimulated();
      if (log.is_open()) log.close();
      printReplaySummary(std::cout, s, o.timing);
      result = finishOutputs(std::cout, std::cerr, s, *r.scene,
                             {"replay", args->scene, args->log, args->report, args->saveVolume, args->saveMesh}, !log.fail());
      return;
    } catch (const std::exception& e) {
      std::cerr << "millsim replay: error: " << e.what() << "\n";
      result = kExitBadInput;
    }
  });
}

}  // namespace millsim::app
