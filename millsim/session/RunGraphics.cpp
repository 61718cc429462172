#include "millsim/session/RunGraphics.h"

#include <chrono>

#include "millsim/graphics/FrameTimer.h"
#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/GraphicsModule.h"
#include "millsim/graphics/SceneRenderer.h"
#include "millsim/volume/BlockChannel.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/window/AppWindow.h"
#include "millsim/window/WindowModule.h"
#include "millsim/session/RunControls.h"

namespace millsim {

namespace {
using Clock = std::chrono::steady_clock;
// Blocks the ring holds per volume: a burr stamp changes at most a few dozen
// 8³ blocks, and the graphics thread drains every ~33 ms (33 frames); when it
// is full the haptic side keeps the rest pending and retries (BlockChannel.h).
constexpr std::size_t kChannelBlocks = 2048;
}  // namespace

RunGraphics::RunGraphics(const Scene& scene, VoxelScene& haptic, HapticLoop& loop, const ToolGeometry& tool,
                         const RunGraphicsOptions& options)
    : scene_(scene), haptic_(haptic), loop_(loop), tool_(tool), options_(options) {}

RunGraphics::~RunGraphics() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void RunGraphics::start() {
  startTime_ = Clock::now();
  if (options_.window)
    (void)loadWindowModule();  // fails fast without SDL2 or libGL
  else
    (void)loadGraphicsModule();  // fails fast without OSMesa
  for (std::size_t i = 0; i < haptic_.volumeCount(); ++i) {
    replicas_.push_back(std::make_unique<VolumeReplica>(*haptic_.volume(i).voxels));
    channels_.push_back(std::make_unique<BlockChannel>(kChannelBlocks));
    loop_.publishBlocks(i, *channels_.back());
  }
  thread_ = std::thread([this] { options_.window ? runWindow() : run(); });
  while (state_.load(std::memory_order_acquire) == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (state_.load() == 2) {
    thread_.join();
    throw GraphicsError(error_);
  }
}

void RunGraphics::run() {
  std::unique_ptr<SceneRenderer> renderer;
  try {
    const GraphicsModule& graphics = loadGraphicsModule();
    RendererOptions ro;
    ro.width = options_.width;
    ro.height = options_.height;
    for (const auto& r : replicas_) ro.voxels.push_back(&r->volume());
    const auto t0 = Clock::now();
    renderer = graphics.createRenderer(scene_, ro);
    stats_.meshSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
    stats_.gl = renderer->glDescription();
  } catch (const std::exception& e) {
    error_ = e.what();
    state_.store(2, std::memory_order_release);
    return;
  }
  state_.store(1, std::memory_order_release);

  paceFrames(
      [&](std::size_t i, const std::vector<BlockOrigin>& blocks) { renderer->volumeChanged(i, blocks); },
      [&] {
        if (views_.hasNew()) renderer->sceneChanged(views_.read());
        const FrameRecord& f = loop_.newest().read();
        renderer->render(f.frame > 0 || f.t > 0.0 ? std::optional<ToolView>(toolView(f.tool, f.out)) : std::nullopt);
        renderer->readPixels();  // finish the frame, as a display copy would
      },
      [&] { return renderer->readPixels(); });
}

void RunGraphics::runWindow() {
  std::unique_ptr<AppWindow> window;
  try {
    WindowOptions wo;
    wo.width = options_.width;
    wo.height = options_.height;
    wo.title = options_.title;
    wo.renderers = options_.renderers;
    wo.pointer = options_.pointer != nullptr;
    wo.pointerStart = options_.pointerStart;
    wo.pointerDepthStep = options_.pointerDepthStep;
    wo.toolRadius = tool_.tipRadius;
    for (const auto& r : replicas_) wo.voxels.push_back(&r->volume());
    const auto t0 = Clock::now();
    window = loadWindowModule().open(scene_, wo);
    stats_.meshSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
    stats_.gl = window->glDescription();
    stats_.window = true;
    // The mouse's tool is where the window put it before the first haptic frame.
    if (options_.pointer) options_.pointer->set(window->pointer().pose, false);
  } catch (const std::exception& e) {
    error_ = e.what();
    state_.store(2, std::memory_order_release);
    return;
  }
  state_.store(1, std::memory_order_release);

  paceFrames([&](std::size_t i, const std::vector<BlockOrigin>& blocks) { window->volumeChanged(i, blocks); },
             [&] {
               if (!window->pollEvents()) options_.controls->close();
               options_.controls->post(window->takeCommands());
               if (views_.hasNew()) window->sceneChanged(views_.read());
               if (options_.pointer) {
                 const PointerState p = window->pointer();
                 options_.pointer->set(p.pose, p.button);
               }
               const FrameRecord& f = loop_.newest().read();
               std::vector<ToolView> tools;
               if (f.frame > 0 || f.t > 0.0) {
                 tools.push_back(toolView(f.tool, f.out));
                 if (options_.pointer)  // the mouse's own pose, where the renderer's tool is held back
                   tools.push_back(ToolView{f.tool, f.device, false, glm::dvec3(0.0), true});
               }
               window->draw(tools, options_.controls->hud());
               if (options_.stallMs > 0) std::this_thread::sleep_for(std::chrono::milliseconds(options_.stallMs));
             },
             [&] { return window->readPixels(); });
  window.reset();  // closes the window on its own thread
}

void RunGraphics::paceFrames(const std::function<void(std::size_t, const std::vector<BlockOrigin>&)>& volumeChanged,
                             const std::function<void()>& drawFrame, const std::function<Image()>& screenshot) {
  FrameTimer all, updates;
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / options_.rate));
  auto next = Clock::now();
  auto frame = [&] {
    const auto t0 = Clock::now();
    bool changed = false;
    for (std::size_t i = 0; i < replicas_.size(); ++i) {
      const auto& blocks = replicas_[i]->apply(*channels_[i]);
      if (!blocks.empty()) {
        volumeChanged(i, blocks);
        changed = true;
      }
    }
    drawFrame();
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    if (stats_.firstFrameSeconds == 0.0) {
      stats_.firstFrameSeconds = std::chrono::duration<double>(Clock::now() - startTime_).count();
      stats_.meshSeconds += s;  // a volume is meshed at the level of detail it is first drawn at (VolumeMesh)
    }
    all.add(s);
    if (changed) updates.add(s);
  };
  while (!stop_.load(std::memory_order_acquire)) {
    frame();
    next += period;
    const auto now = Clock::now();
    if (next < now) next = now;  // behind: draw again at once, never queue frames
    std::this_thread::sleep_until(next);
  }
  frame();  // the final state, after the haptic loop ended
  if (!options_.screenshot.empty()) {
    try {
      loadGraphicsModule().writePng(screenshot(), options_.screenshot);
    } catch (const std::exception& e) {
      error_ = e.what();
    }
  }
  stats_.frames = long(all.count());
  stats_.width = options_.width;
  stats_.height = options_.height;
  stats_.screenshot = options_.screenshot.string();
  stats_.meanMs = all.mean() * 1e3;
  stats_.p95Ms = all.p95() * 1e3;
  stats_.updateFrames = long(updates.count());
  stats_.meanUpdateMs = updates.mean() * 1e3;
}

RunGraphicsStats RunGraphics::stop() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  if (!error_.empty()) throw GraphicsError(error_);
  return stats_;
}

}  // namespace millsim
