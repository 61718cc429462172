// millsim run SCENE.x3d: runs a scene's device at its haptic rate in real
// time (a Session on its own real-time thread, millsim/session/Session.h),
// in a window when there is a display, and prints the rate and force
// statistics. This file is the command line around the Session.
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <tuple>

#include "Commands.h"
#include "StderrProgress.h"
#include "ImageArgs.h"
#include "NumberArgs.h"
#include "TrajectoryReach.h"
#include "RunSummary.h"
#include "SaveMesh.h"
#include "SaveVolume.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/graphics/GraphicsError.h"
#include "millsim/session/Session.h"
#include "millsim/window/WindowModule.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::app {

namespace {
std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) { gInterrupted.store(true); }
}  // namespace

void addRunCommand(CLI::App& app, const GlobalOptions& global, int& result) {
  auto* cmd = app.add_subcommand("run", "Run a scene's device and renderer in real time (1 kHz haptic thread)");
  struct Args {
    bool strict = false, noGraphics = false, noWindow = false, noSound = false;
    std::vector<std::string> sets;
    std::string scene, log, trajectory, device, size, soundOut, saveVolume, saveMesh, report;
    double duration = 0.0;
    SessionOptions session;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("scene", args->scene, "X3D scene file")->required();
  addStrictFlag(cmd, args->strict);
  addSetOption(cmd, args->sets);
  cmd->add_option("--duration", args->duration,
                  "Seconds to run (default: the device's trajectory; a hardware device runs until Ctrl-C)")
      ->check(finiteIn(0.001, 1e6, "s"));
  cmd->add_option("--log", args->log, "Log CSV to write (one row per haptic frame, with period_us)");
  cmd->add_option("--renderer", args->session.renderer, "Use a default renderer of this type instead of the scene's");
  cmd->add_option("--trajectory", args->trajectory,
                  "Trajectory CSV: a simulated device follows it instead of its url; any other device is replaced "
                  "by it for this run (played open loop, as replay does)");
  cmd->add_option("--device", args->device,
                  "Drive this run with a simulated device in place of the scene's (whose renderer, tool, limits and "
                  "calibration stay): trajectory (open loop), hand (a simulated hand pulled along the trajectory) "
                  "or mouse (the window's mouse)")
      ->check(CLI::IsMember({"trajectory", "hand", "mouse"}));
  cmd->add_flag("--no-graphics", args->noGraphics, "Run without a graphics thread (no window, no GL context, no meshes)");
  cmd->add_flag("--no-window", args->noWindow,
                "Draw offscreen (OSMesa) even when a display is available (the window opens when DISPLAY or "
                "WAYLAND_DISPLAY is set)");
  cmd->add_option("--screenshot", args->session.screenshot,
                  "PNG of the last graphics frame (the window's, with its HUD), written at the end");
  cmd->add_option("--size", args->size, "Window or frame size WIDTHxHEIGHT (default 1024x768 in a window, else 512x512)");
  cmd->add_option("--sound-out", args->soundOut, "WAV file of the milling sound (16-bit PCM mono, the run's length)");
  cmd->add_flag("--no-sound", args->noSound, "Do not play the milling sound live");
  cmd->add_option("--save-volume", args->saveVolume,
                  "At the end, write the milled volume to this .vdb file (a VolumeObject url loads it back)");
  cmd->add_option("--save-mesh", args->saveMesh,
                  "At the end, write the milled surface in millimetres: .stl the whole, .obj (with an .mtl) or "
                  ".ply a solid per tissue in its colour (a VolumeObject url loads it back with meshUnit='0.001')");
  cmd->add_option("--report", args->report,
                  "At the end, write the lesson report (JSON: removed volume, peak force, targets, forbidden "
                  "regions, score)");
  cmd->callback([args, &global, &result] {
    LoadOptions lo;
    lo.plugins.allowAnyPath = global.allowPluginPath;
    lo.strict = args->strict;
    applySetOptions(lo, args->sets);
    StderrProgress progress;
    lo.progress = &progress;
    LoadResult r = loadSceneFile(args->scene, builtinRegistry(), lo);
    std::cerr << r.report();
    result = kExitBadInput;
    if (!r.ok()) return;
    SessionOptions& o = args->session;
    std::ofstream log;
    std::unique_ptr<Session> session;
    try {
      if (!args->soundOut.empty()) checkWritable(args->soundOut, "--sound-out");
      if (!args->saveVolume.empty()) checkSaveVolume(*r.scene, args->saveVolume);
      if (!args->saveMesh.empty()) checkSaveMesh(*r.scene, args->saveMesh);
      if (!args->report.empty()) checkWritable(args->report, "--report");
      if (args->noGraphics && !o.screenshot.empty())
        throw std::invalid_argument("--screenshot needs graphics; drop --no-graphics");
      if (!args->noGraphics) {
        const bool window = !args->noWindow && displayAvailable();
        if (!args->noWindow && !window)
          std::cout << "millsim run: no display (DISPLAY and WAYLAND_DISPLAY are unset): drawing offscreen, no window\n";
        o.display = window ? SessionOptions::Display::Window : SessionOptions::Display::Offscreen;
        std::tie(o.width, o.height) = parseSize(!args->size.empty() ? args->size : window ? "1024x768" : "512x512");
        if (!o.screenshot.empty()) checkWritable(o.screenshot, "--screenshot");
        o.title = windowTitle(*r.scene, args->scene);
        if (const char* stall = std::getenv("MILLSIM_TEST_STALL_WINDOW_MS")) o.stallWindowMs = std::atoi(stall);
      }
      if (args->device == "mouse" && !args->trajectory.empty())
        throw std::invalid_argument("--device mouse follows the window's mouse, not --trajectory; drop one of them");
      o.deviceSource = args->device == "trajectory" ? SessionOptions::DeviceSource::Trajectory
                       : args->device == "hand"     ? SessionOptions::DeviceSource::Hand
                       : args->device == "mouse"    ? SessionOptions::DeviceSource::Mouse
                                                    : SessionOptions::DeviceSource::Scene;
      if (!args->trajectory.empty()) {
        o.trajectory = std::make_shared<const Trajectory>(Trajectory::load(args->trajectory));
        warnOutOfReach(*r.scene, *o.trajectory, args->trajectory, "run");
      }
      if (!args->log.empty()) {
        log.open(args->log, std::ios::binary);
        if (!log) throw std::runtime_error(args->log + ": cannot write the log file");
        o.log = &log;
      }
      o.soundOut = args->soundOut;
      o.liveSound = !args->noSound;
      o.notices = &std::cout;
      session = Session::openDevice(*r.scene, o);
      if (!session->preparedRenderers().empty())
        std::cout << "prepared " << session->preparedRenderers().size() << " renderers for live swapping\n";
    } catch (const std::exception& e) {
      std::cerr << "millsim run: error: " << e.what() << "\n";
      return;
    }
    const double duration = args->duration > 0.0 ? args->duration : session->naturalDuration();
    if (std::isinf(duration))
      std::cout << "running " << session->deviceName()
                << (o.display == SessionOptions::Display::Window ? " until the window is closed or Ctrl-C\n"
                                                                 : " until Ctrl-C\n")
                << std::flush;
    gInterrupted.store(false);
    auto previousInt = std::signal(SIGINT, onInterrupt);
    auto previousTerm = std::signal(SIGTERM, onInterrupt);
    SessionResult s;
    std::string notRun;  // why nothing ran (graphics could not start)
    try {
      s = session->runRealTime(duration, [] { return gInterrupted.load(); });
    } catch (const GraphicsError& e) {
      notRun = std::string("graphics: ") + e.what() +
               (o.display == SessionOptions::Display::Window
                    ? " (run with --no-window to draw offscreen, or --no-graphics)"
                    : " (run with --no-graphics to go without)");
    } catch (const std::exception& e) {
      notRun = e.what();
    }
    std::signal(SIGINT, previousInt);
    std::signal(SIGTERM, previousTerm);
    if (!notRun.empty()) {
      std::cerr << "millsim run: error: " << notRun << "\n";
      return;
    }
    if (log.is_open()) log.close();
    printRunSummary(std::cout, s);
    result = finishOutputs(std::cout, std::cerr, s, *r.scene, {"run", args->scene, args->log, args->report, args->saveVolume, args->saveMesh},
                           !log.fail());
  });
}

}  // namespace millsim::app
