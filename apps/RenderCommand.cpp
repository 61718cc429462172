// millsim render SCENE.x3d --out SHOT.png: replays the device's trajectory up
// to a time (milling included) and draws the scene offscreen to a PNG.
#include <unistd.h>

#include <charconv>
#include <filesystem>
#include <iostream>

#include "Commands.h"
#include "StderrProgress.h"
#include "NumberArgs.h"
#include "TrajectoryReach.h"
#include "ImageArgs.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/TrajectoryDevice.h"
#include "millsim/graphics/GlContext.h"
#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/GraphicsModule.h"
#include "millsim/graphics/SceneRenderer.h"
#include "millsim/run/RunSetup.h"
#include "millsim/session/Replay.h"
#include "millsim/std/EventClock.h"
#include "millsim/std/Viewpoint.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::app {


void addRenderCommand(CLI::App& app, const GlobalOptions& global, int& result) {
  auto* cmd = app.add_subcommand("render", "Draw the scene offscreen (OSMesa) to a PNG, after replaying its trajectory");
  struct Args {
    bool strict = false;
    std::string scene, out, size = "512x512", trajectory, viewpoint;
    double at = std::numeric_limits<double>::infinity();
    ReplayOptions options;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("scene", args->scene, "X3D scene file")->required();
  addStrictFlag(cmd, args->strict);
  cmd->add_option("--out", args->out, "PNG file to write")->required();
  cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT (default 512x512)");
  cmd->add_option("--trajectory", args->trajectory,
                  "Trajectory CSV to replay (default: the scene device's url, if any)");
  cmd->add_option("--at", args->at, "Trajectory time to stop at, in seconds (default: its end); without a trajectory, the time the scene's TimeSensors have reached")
      ->check(finiteIn(0, 1e6, "s"));
  cmd->add_option("--renderer", args->options.renderer, "Use a default haptics renderer of this type");
  cmd->add_option("--viewpoint", args->viewpoint, "DEF name of the Viewpoint to look through (default: the first)");
  cmd->callback([args, &global, &result] {
    result = kExitBadInput;
    try {
      const auto [width, height] = parseSize(args->size);
      checkWritable(args->out, "--out");
      const GraphicsModule& graphics = loadGraphicsModule();  // before the slow part: is OSMesa there?

      LoadOptions lo;
      lo.plugins.allowAnyPath = global.allowPluginPath;
      lo.strict = args->strict;
      StderrProgress progress;
      lo.progress = &progress;
      LoadResult r = loadSceneFile(args->scene, builtinRegistry(), lo);
      std::cerr << r.report();
      if (!r.ok()) return;
      if (!args->viewpoint.empty() && !dynamic_cast<const Viewpoint*>(r.scene->def(args->viewpoint).get()))
        throw std::invalid_argument("--viewpoint: the scene has no Viewpoint with DEF name '" + args->viewpoint + "'");

      // The tool is drawn where the renderer's last frame put it.
      std::optional<ToolView> tool;
      std::shared_ptr<const Trajectory> trajectory;
      if (!args->trajectory.empty()) {
        trajectory = std::make_shared<const Trajectory>(Trajectory::load(args->trajectory));
        warnOutOfReach(*r.scene, *trajectory, args->trajectory, "render");
      }
      else if (HapticsDevice* device = findDevice(*r.scene))
        trajectory = device->trajectory();
      if (trajectory) {
        const double from = trajectory->startTime(), to = trajectory->endTime();
        if (std::isfinite(args->at) && (args->at < from || args->at > to))
          throw std::invalid_argument("--at " + formatNumber(args->at) + " s is outside the trajectory; expected a time in [" +
                                      formatNumber(from) + ", " + formatNumber(to) + "] s");
        args->options.until = args->at;
        const ReplaySummary s = replay(*r.scene, *trajectory, nullptr, args->options);
        HapticsDevice* device = findDevice(*r.scene);
        const ToolGeometry geometry = device && device->tool.get() ? device->tool.get()->geometry() : ToolGeometry{};
        tool = toolView(geometry, s.last);
        std::cout << "replayed " << s.stats.frames << " frames with " << s.rendererName << ", removed "
                  << s.stats.removedVolume * 1e9 << " mm³\n";
      } else {
        // No trajectory: the scene's events alone, in simulated time from 0 (replay ticks them otherwise).
        EventClock events(*r.scene);
        if (std::isfinite(args->at) && events.empty())
          throw std::invalid_argument(
              "--at needs a trajectory or a scene that animates: pass --trajectory, give the scene's device a url, "
              "or add a TimeSensor");
        events.advanceTo(std::isfinite(args->at) ? args->at : 0.0);
      }

      RendererOptions ro;
      ro.width = width;
      ro.height = height;
      ro.viewpoint = args->viewpoint;
      auto renderer = graphics.createRenderer(*r.scene, ro);
      renderer->render(tool);
      graphics.writePng(renderer->readPixels(), args->out);
      std::cout << "wrote " << args->out << " (" << width << "x" << height << ", "
                << renderer->stats().triangles << " triangles)\n";
      result = kExitOk;
    } catch (const std::exception& e) {
      std::cerr << "millsim render: error: " << e.what() << "\n";
    }
  });
}

}  // namespace millsim::app
