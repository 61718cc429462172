// millsim run SCENE.x3d: runs a scene's device at its haptic rate in real
// time on a dedicated thread, logs every frame, and prints the rate and force
// statistics. With a display it opens the window (navigation, cut planes, HUD,
// keys 1–3 swap the renderer live); without one it draws offscreen. The scene
// thread (this one) drains logs, copies the newest frame into the device
// node's fields, feeds the HUD and carries out the window's commands; it
// never holds the haptic thread up.
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <optional>
#include <thread>
#include <tuple>

#include "Commands.h"
#include "LessonReport.h"
#include "NumberArgs.h"
#include "ImageArgs.h"
#include "SaveVolume.h"
#include "RunControls.h"
#include "RunGraphics.h"
#include "RunHud.h"
#include "RunSound.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/AnyDevice.h"
#include "millsim/devices/MouseDevice.h"
#include "millsim/run/FrameLog.h"
#include "millsim/run/LiveUpdates.h"
#include "millsim/run/RendererPool.h"
#include "millsim/run/RunSetup.h"
#include "millsim/graphics/DrawnFields.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/lesson/RegionAccounting.h"
#include "millsim/std/EventClock.h"
#include "millsim/std/WorldInfo.h"
#include "millsim/window/WindowModule.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::app {

namespace {

std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) { gInterrupted.store(true); }

void printSummary(std::ostream& os, const LoopStats& s, const std::string& renderer, const std::string& device,
                  double rate) {
  os << std::fixed;
  os << "ran " << s.frames << " frames in " << std::setprecision(2) << s.elapsed << " s with " << renderer << " on "
     << device << " (desired " << std::setprecision(0) << rate << " Hz)\n";
  os << "  haptic rate: mean " << std::setprecision(1) << s.meanRate() << " Hz, p1 " << s.p1Rate()
     << " Hz, missed deadlines " << s.missedDeadlines << " of " << s.frames << " ("
     << std::setprecision(2) << (s.frames ? 100.0 * double(s.missedDeadlines) / double(s.frames) : 0.0) << " %)\n";
  os << "  compute per frame: mean " << std::setprecision(1) << s.computeUs.mean() << " µs, p99 "
     << s.computeUs.percentile(0.99) << " µs, max " << s.computeUs.max() << " µs (wall); on the thread's CPU p99 "
     << s.computeCpuUs.percentile(0.99) << " µs, max " << s.computeCpuUs.max() << " µs; " << s.preemptedFrames
     << " frames lost the CPU for over " << std::setprecision(0) << LoopStats::kPreemptedUs << " µs\n";
  os << "  peak force " << std::setprecision(3) << s.peakForce << " N, peak torque " << std::setprecision(4)
     << s.peakTorque << " N·m, frames in contact " << s.contactFrames << ", most contacts " << s.maxContacts << "\n";
  os << "  removed volume " << std::setprecision(3) << s.removedVolume * 1e9 << " mm³\n";
  os << "  safety: clamped " << s.safety.clamped << ", late frames blended " << s.safety.hiccups << ", watchdog trips "
     << s.safety.watchdogTrips << ", non-finite "
     << s.safety.nonFinite << "; device: sequence gaps " << s.device.sequenceGaps << ", checksum errors "
     << s.device.checksumErrors << "; log records dropped " << s.recordsDropped << "\n";
  os << "  real-time priority: "
     << (s.realTimePriority ? "SCHED_FIFO"
                            : "not granted (normal priority); to grant it, raise the rtprio limit (ulimit -r 99, or "
                              "'@audio - rtprio 99' in /etc/security/limits.conf) or give the binary CAP_SYS_NICE "
                              "(setcap cap_sys_nice+ep millsim)")
     << "\n";
  os.unsetf(std::ios::fixed);
}

// "MillSim — <WorldInfo title, else the file name>"
std::string windowTitle(const Scene& scene, const std::string& file) {
  for (const WorldInfo* info : scene.nodesOfType<WorldInfo>())
    if (!info->title.get().empty()) return "MillSim — " + info->title.get();
  return "MillSim — " + std::filesystem::path(file).filename().string();
}

}  // namespace

void addRunCommand(CLI::App& app, const GlobalOptions& global, int& result) {
  auto* cmd = app.add_subcommand("run", "Run a scene's device and renderer in real time (1 kHz haptic thread)");
  struct Args {
    bool strict = false;
    std::string scene, log, renderer, trajectory, screenshot, size;
    double duration = 0.0;
    bool noGraphics = false, noWindow = false;
    std::string soundOut, saveVolume, report;
    bool noSound = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("scene", args->scene, "X3D scene file")->required();
  addStrictFlag(cmd, args->strict);
  cmd->add_option("--duration", args->duration,
                  "Seconds to run (default: the device's trajectory; a hardware device runs until Ctrl-C)")
      ->check(finiteIn(0.001, 1e6, "s"));
  cmd->add_option("--log", args->log, "Log CSV to write (one row per haptic frame, with period_us)");
  cmd->add_option("--renderer", args->renderer, "Use a default renderer of this type instead of the scene's");
  cmd->add_option("--trajectory", args->trajectory, "Trajectory CSV for a simulated device instead of its url");
  cmd->add_flag("--no-graphics", args->noGraphics, "Run without a graphics thread (no window, no GL context, no meshes)");
  cmd->add_flag("--no-window", args->noWindow,
                "Draw offscreen (OSMesa) even when a display is available (the window opens when DISPLAY or "
                "WAYLAND_DISPLAY is set)");
  cmd->add_option("--screenshot", args->screenshot, "PNG of the last graphics frame (the window's, with its HUD), written at the end");
  cmd->add_option("--size", args->size, "Window or frame size WIDTHxHEIGHT (default 1024x768 in a window, else 512x512)");
  cmd->add_option("--sound-out", args->soundOut, "WAV file of the milling sound (16-bit PCM mono, the run's length)");
  cmd->add_flag("--no-sound", args->noSound, "Do not play the milling sound live");
  cmd->add_option("--save-volume", args->saveVolume,
                  "At the end, write the milled volume to this .vdb file (a VolumeObject url loads it back)");
  cmd->add_option("--report", args->report,
                  "At the end, write the lesson report (JSON: removed volume, peak force, targets, forbidden "
                  "regions, score)");
  cmd->callback([args, &global, &result] {
    LoadOptions lo;
    lo.plugins.allowAnyPath = global.allowPluginPath;
    lo.strict = args->strict;
    LoadResult r = loadSceneFile(args->scene, builtinRegistry(), lo);
    std::cerr << r.report();
    if (!r.ok()) {
      result = kExitBadInput;
      return;
    }
    std::unique_ptr<HapticLoop> loop;
    CompiledRun run;
    double duration = 0.0;
    RunGraphicsOptions graphicsOptions;
    RunControls controls;
    std::unique_ptr<PointerInput> pointer;
    std::unique_ptr<RendererPool> pool;
    std::unique_ptr<RegionAccounting> regions;
    std::unique_ptr<RunSound> sound;
    try {
      if (!args->soundOut.empty()) checkWritable(args->soundOut, "--sound-out");
      if (!args->saveVolume.empty()) checkSaveVolume(*r.scene, args->saveVolume);
      if (!args->report.empty()) checkWritable(args->report, "--report");
      if (args->noGraphics && !args->screenshot.empty())
        throw std::invalid_argument("--screenshot needs graphics; drop --no-graphics");
      if (!args->noGraphics) {
        graphicsOptions.window = !args->noWindow && displayAvailable();
        if (!args->noWindow && !graphicsOptions.window)
          std::cout << "millsim run: no display (DISPLAY and WAYLAND_DISPLAY are unset): drawing offscreen, no window\n";
        const std::string size = !args->size.empty() ? args->size : graphicsOptions.window ? "1024x768" : "512x512";
        std::tie(graphicsOptions.width, graphicsOptions.height) = parseSize(size);
        if (!args->screenshot.empty()) checkWritable(args->screenshot, "--screenshot");
        graphicsOptions.screenshot = args->screenshot;
      }
      run = compileRun(*r.scene, args->renderer);
      std::optional<Trajectory> trajectory;
      if (!args->trajectory.empty()) trajectory = Trajectory::load(args->trajectory);
      DriverOptions driverOptions{trajectory ? &*trajectory : nullptr, nullptr};
      // A MouseDevice follows the window's mouse; an AnyDevice does when it finds no ARES.
      auto* any = dynamic_cast<AnyDevice*>(run.device);
      const MouseDevice* mouse = any ? &any->mouse() : dynamic_cast<MouseDevice*>(run.device);
      if (mouse && graphicsOptions.window) {
        pointer = std::make_unique<PointerInput>(mouse->startPose());
        driverOptions.pointer = pointer.get();
        graphicsOptions.pointer = pointer.get();
        graphicsOptions.pointerStart = mouse->startPose();
        graphicsOptions.pointerDepthStep = mouse->depthStep.get();
      }
      auto driver = run.device->openDriver(driverOptions);
      if (any) {
        any->openedDevice.set(any->followsMouse() ? "MouseDevice" : "AresDevice");
        std::cout << "AnyDevice: " << (any->followsMouse() ? "no ARES found; following the mouse" : "opened the ARES")
                  << "\n";
        if (!any->followsMouse()) graphicsOptions.pointer = nullptr;  // the ARES moves the tool, not the mouse
      }
      duration = args->duration > 0.0 ? args->duration : driver->naturalDuration();
      if (graphicsOptions.window) {
        // Every renderer compiled now, on this thread: a key swaps to a ready one.
        const auto t0 = std::chrono::steady_clock::now();
        pool = std::make_unique<RendererPool>(*r.scene, run, run.algorithm.get());
        std::cout << "prepared " << pool->size() << " renderers for live swapping in " << std::fixed
                  << std::setprecision(2) << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
                  << " s\n";
        std::cout.unsetf(std::ios::fixed);
        graphicsOptions.renderers = pool->typeNames();
        graphicsOptions.title = windowTitle(*r.scene, args->scene);
        graphicsOptions.controls = &controls;
        if (const char* stall = std::getenv("MILLSIM_TEST_STALL_WINDOW_MS")) graphicsOptions.stallMs = std::atoi(stall);
      }
      loop = std::make_unique<HapticLoop>(*run.scene, std::move(run.algorithm), std::move(driver), run.settings);
      // Assessment counts on this (the scene) thread, from blocks the loop publishes.
      regions = std::make_unique<RegionAccounting>(*r.scene);
      if (!regions->empty())
        for (std::size_t i = 0; i < regions->volumeCount(); ++i) loop->publishBlocks(i, regions->channel(i));
      sound = std::make_unique<RunSound>(RunSoundOptions{args->soundOut, !args->noSound, run.settings.rate}, std::cerr);
    } catch (const std::exception& e) {
      std::cerr << "millsim run: error: " << e.what() << "\n";
      result = kExitBadInput;
      return;
    }
    std::ofstream log;
    if (!args->log.empty()) {
      log.open(args->log, std::ios::binary);
      if (!log) {
        std::cerr << "millsim run: error: " << args->log << ": cannot write the log file\n";
        result = kExitBadInput;
        return;
      }
    }
    FrameLogWriter writer(args->log.empty() ? nullptr : &log);
    HudFeed hud(run.settings.rate);
    if (pool) writer.observe([&hud](const FrameRecord& f) { hud.add(f); });
    writer.observe([&sound](const FrameRecord& f) { sound->add(f); });
    const std::string deviceName =
        run.device->typeName() + (run.device->defName().empty() ? "" : " '" + run.device->defName() + "'");
    if (std::isinf(duration))
      std::cout << "running " << deviceName << (pool ? " until the window is closed or Ctrl-C\n" : " until Ctrl-C\n")
                << std::flush;

    // The scene's events (TimeSensors, KeySensors and what they drive) tick on
    // this thread, in the run's own time; the first tick, at 0, is before
    // graphics reads the scene, so the first frame shows it.
    EventClock events(*r.scene);
    events.tick(0.0);
    DrawnFields drawn(*r.scene);
    ShapeMeshCache shapeMeshes;  // an animated scene's views share the meshes of unchanged geometry

    // Graphics first: its context and meshes are ready (or it failed)
    // before the first haptic frame, and the scene is not touched by this
    // thread until then.
    std::unique_ptr<RunGraphics> graphics;
    if (!args->noGraphics) {
      try {
        graphics = std::make_unique<RunGraphics>(*r.scene, *run.scene, *loop, run.tool, graphicsOptions);
        graphics->start();
      } catch (const std::exception& e) {
        std::cerr << "millsim run: error: graphics: " << e.what()
                  << (graphicsOptions.window ? " (run with --no-window to draw offscreen, or --no-graphics)"
                                             : " (run with --no-graphics to go without)")
                  << "\n";
        result = kExitBadInput;
        return;
      }
    }

    gInterrupted.store(false);
    auto previousInt = std::signal(SIGINT, onInterrupt);
    auto previousTerm = std::signal(SIGTERM, onInterrupt);
    loop->start(duration);
    const auto runStart = std::chrono::steady_clock::now();
    // The scene thread's part: drain the log, update the device fields, tick
    // the scene's events, and with a window, feed its HUD and do what its keys asked.
    std::string status;
    LiveUpdates live(run, *loop);
    while (!loop->finished()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (gInterrupted.load() || controls.closed()) loop->stop();
      if (writer.drain(*loop) > 0) {
        publishToDevice(*run.device, writer.last(), run.settings.rate);
        regions->update(writer.last().t);
        regions->publishFields();
        publishRemovedVolumes(run);  // each VolumeObject's removedVolume follows the milling
      }
      sound->pump();
      for (const WindowCommand& c : controls.take()) {
        if (c.kind == WindowCommand::Kind::SelectRenderer && pool) status = pool->select(std::size_t(c.index), *loop);
        // The keys set fields; LiveUpdates carries them to the haptic thread, as for a route.
        if (c.kind == WindowCommand::Kind::ToggleEnabled) run.device->enabled.set(!run.device->enabled.get());
        if (c.kind == WindowCommand::Kind::ToggleMillable)
          for (VolumeObject* v : r.scene->nodesOfType<VolumeObject>()) v->millable.set(!v->millable.get());
        // B: the next burr shape, same dimensions; the pool swaps to it below (or refuses it).
        if (c.kind == WindowCommand::Kind::NextBurrShape && run.device->tool.get()) {
          MillTool& t = *run.device->tool.get();
          t.shape.set(std::string(nextBurrShape(t.geometry().shape)));
          // A cone needs its narrow end narrower than the head: halve it if a round burr's dimensions do not say so.
          if (t.tipEndRadius.get() > t.tipRadius.get()) t.tipEndRadius.set(0.5f * t.tipRadius.get());
        }
        if (c.kind == WindowCommand::Kind::Key && events.hasKeySensors())
          events.key(KeyEvent{c.press, c.character, c.index, KeyEvent::Modifier(int(c.modifier))});
      }
      if (!events.empty())
        events.tick(std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart).count());
      if (std::string s = live.poll(); !s.empty()) status = s;
      // What graphics draws follows the events, routes and keys: a new view when a drawn field changed.
      if (graphics && drawn.changed()) {
        graphics->publishView(readSceneView(*r.scene, nullptr, &shapeMeshes));
        drawn.mark();
      }
      if (!pool) {
        loop->collectRetired();
        continue;
      }
      pool->collect(*loop);
      if (std::string s = pool->followDeviceField(*loop); !s.empty()) status = s;
      if (std::string s = pool->followRendererFields(*loop); !s.empty()) status = s;
      if (std::string s = pool->followTool(*loop); !s.empty()) status = s;
      HudState h = hud.state(status);
      h.swapPending = std::string(h.renderer) != pool->typeName(pool->current());
      controls.setHud(h);
    }
    loop->join();
    writer.drain(*loop);
    regions->update(writer.last().t);
    regions->publishFields();
    sound->finish(std::cerr);
    RunGraphicsStats graphicsStats;
    std::string graphicsError;
    if (graphics) {
      try {
        graphicsStats = graphics->stop();
      } catch (const std::exception& e) {
        graphicsError = e.what();
      }
    }
    std::signal(SIGINT, previousInt);
    std::signal(SIGTERM, previousTerm);
    if (log.is_open()) {
      log.close();
      if (!log) {
        std::cerr << "millsim run: error: " << args->log << ": writing the log failed\n";
        result = kExitFailure;
        return;
      }
    }
    const LoopStats s = loop->stats();
    publishRemovedVolumes(run);
    printSummary(std::cout, s, run.rendererName, deviceName, run.settings.rate);
    sound->printSummary(std::cout);
    if (!args->report.empty()) {
      try {
        const LessonReport report{args->scene, run.rendererName, s.elapsed, s.removedVolume, s.peakForce,
                                  s.peakTorque, regions->results()};
        writeReport(args->report, report);
        std::cout << describeReport(report, false) << "  report written to " << args->report << "\n";
      } catch (const std::exception& e) {
        std::cerr << "millsim run: error: " << e.what() << "\n";
        result = kExitFailure;
        return;
      }
    }
    if (!args->saveVolume.empty()) {
      try {
        std::cout << saveVolume(*r.scene, args->saveVolume);
      } catch (const std::exception& e) {
        std::cerr << "millsim run: error: " << e.what() << "\n";
        result = kExitFailure;
        return;
      }
    }
    if (graphics) {
      std::cout << std::fixed << std::setprecision(1) << (graphicsStats.window ? "  window: " : "  graphics: ")
                << graphicsStats.frames << " frames at "
                << graphicsOptions.width << "x" << graphicsOptions.height << ", mean " << graphicsStats.meanMs
                << " ms, p95 " << graphicsStats.p95Ms << " ms, with re-meshing " << graphicsStats.meanUpdateMs
                << " ms (" << graphicsStats.updateFrames << " frames); first mesh " << graphicsStats.meshSeconds * 1e3
                << " ms; first frame " << graphicsStats.firstFrameSeconds * 1e3 << " ms after start; "
                << graphicsStats.gl << "\n";
      std::cout.unsetf(std::ios::fixed);
      if (!args->screenshot.empty() && graphicsError.empty()) std::cout << "  screenshot: " << args->screenshot << "\n";
    }
    if (!graphicsError.empty()) {
      std::cerr << "millsim run: error: " << graphicsError << "\n";
      result = kExitFailure;
      return;
    }
    if (!sound->ok()) {
      result = kExitFailure;
      return;
    }
    if (!loop->failure().empty()) {
      // The loop has already zeroed the output and released the device.
      std::cerr << "millsim run: error: " << loop->failure()
                << (args->log.empty() ? "" : " (the log up to that frame is in " + args->log + ")") << "\n";
      result = kExitFailure;
      return;
    }
    result = kExitOk;
  });
}

}  // namespace millsim::app
