// The SDL2 window (AppWindow.h) and the table loadWindowModule() finds.
#include <SDL.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <utility>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>
#include <backends/imgui_impl_sdl.h>

#include "millsim/graphics/Examine.h"
#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/PointerTool.h"
#include "millsim/graphics/SceneDrawer.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/volume/VoxelVolume.h"
#include "millsim/window/AppWindow.h"
#include "millsim/window/Hud.h"
#include "millsim/window/WindowModule.h"

namespace millsim {

namespace {

// A command with its other fields at their defaults (no partial aggregate
// initialiser, which -Wmissing-field-initializers reports).
WindowCommand command(WindowCommand::Kind kind, int index = 0) {
  WindowCommand c{};
  c.kind = kind;
  c.index = index;
  return c;
}

using Clock = std::chrono::steady_clock;

std::string sdlError(const char* what) { return std::string(what) + ": " + SDL_GetError(); }

SceneView viewWithVoxels(const Scene& scene, const WindowOptions& options) {
  SceneView view = readSceneView(scene);
  if (!options.voxels.empty() && options.voxels.size() != view.volumes.size())
    throw GraphicsError("the window got " + std::to_string(options.voxels.size()) + " volumes for a scene with " +
                        std::to_string(view.volumes.size()));
  for (std::size_t i = 0; i < options.voxels.size(); ++i) view.volumes[i].voxels = options.voxels[i];
  return view;
}

class SdlWindow final : public AppWindow {
public:
  SdlWindow(const Scene& scene, const WindowOptions& options)
      : options_(options), pointerTool_(options.pointerStart, options.pointerDepthStep) {
    if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) throw GraphicsError(sdlError("cannot open a window (SDL video)"));
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
    SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 24);
    window_ = SDL_CreateWindow(options.title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, options.width,
                               options.height, SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE | SDL_WINDOW_SHOWN);
    if (!window_) {
      SDL_QuitSubSystem(SDL_INIT_VIDEO);
      throw GraphicsError(sdlError("cannot create the window"));
    }
    context_ = SDL_GL_CreateContext(window_);
    if (!context_) {
      const std::string e = sdlError("cannot create an OpenGL 3.3 core context for the window");
      SDL_DestroyWindow(window_);
      SDL_QuitSubSystem(SDL_INIT_VIDEO);
      throw GraphicsError(e);
    }
    SDL_GL_MakeCurrent(window_, context_);
    // Vsync where the display has it; the window thread paces itself anyway.
    if (SDL_GL_SetSwapInterval(1) != 0) SDL_GL_SetSwapInterval(0);

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // never write imgui.ini into the user's folder
    const char* font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    if (std::filesystem::exists(font)) {
      static const ImWchar ranges[] = {0x0020, 0x00FF, 0x2070, 0x209F, 0x2190, 0x21FF, 0};  // Latin-1, ⁰…, arrows
      io.Fonts->AddFontFromFileTTF(font, 15.f, nullptr, ranges);
    }
    ImGui::StyleColorsDark();
    ImGui_ImplSDL2_InitForOpenGL(window_, context_);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    drawer_ = std::make_unique<SceneDrawer>(viewWithVoxels(scene, options));
    const SceneView& sv = drawer_->scene();
    navigate_ = sv.navigation != "NONE";
    resetView(-1);
    if (options.pointer && pointerStartUnset()) {
      // Above the scene's centre, the burr just clear of its top.
      Pose p;
      p.position = glm::dvec3(sv.centre().x, sv.boundsMax.y + 2.0 * options.toolRadius, sv.centre().z);
      pointerTool_.setPose(p);
    }
  }

  ~SdlWindow() override {
    SDL_GL_MakeCurrent(window_, context_);
    drawer_.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplSDL2_Shutdown();
    ImGui::DestroyContext();
    SDL_GL_DeleteContext(context_);
    SDL_DestroyWindow(window_);
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
  }

  bool pollEvents() override {
    SDL_Event e;
    while (SDL_PollEvent(&e)) {
      ImGui_ImplSDL2_ProcessEvent(&e);
      switch (e.type) {
        case SDL_QUIT: open_ = false; break;
        case SDL_WINDOWEVENT:
          if (e.window.event == SDL_WINDOWEVENT_CLOSE) open_ = false;
          break;
        case SDL_KEYDOWN:
          key(e.key.keysym);
          forwardKey(e.key, true);
          break;
        case SDL_KEYUP: forwardKey(e.key, false); break;
        case SDL_MOUSEBUTTONDOWN:
        case SDL_MOUSEBUTTONUP: button(e.button); break;
        case SDL_MOUSEMOTION: motion(e.motion); break;
        case SDL_MOUSEWHEEL: wheel(e.wheel); break;
        default: break;
      }
    }
    return open_;
  }

  std::vector<WindowCommand> takeCommands() override { return std::exchange(commands_, {}); }
  PointerState pointer() const override { return {pointerTool_.pose(), leftHeld_ || spaceMilling_}; }

  void sceneChanged(const SceneView& fresh) override {
    drawer_->adoptView(fresh);
    activeCut_ = std::clamp(activeCut_, 0, std::max(int(drawer_->cutPlanes().size()) - 1, 0));
  }

  void volumeChanged(std::size_t index, const std::vector<BlockOrigin>& blocks) override {
    SDL_GL_MakeCurrent(window_, context_);
    drawer_->volumeChanged(index, blocks);
  }

  void draw(const std::vector<ToolView>& tools, const HudState& hud) override {
    const auto t0 = Clock::now();
    lastTools_ = tools;
    lastHud_ = hud;
    render(tools, hud);
    SDL_GL_SwapWindow(window_);
    frameMs_ = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  }

  Image readPixels() override {
    render(lastTools_, lastHud_);
    glFinish();
    Image img = SceneDrawer::readPixels(width_, height_);
    SDL_GL_SwapWindow(window_);
    return img;
  }

  int width() const override { return width_; }
  int height() const override { return height_; }
  std::string glDescription() const override {
    auto str = [](GLenum e) {
      const auto* s = reinterpret_cast<const char*>(glGetString(e));
      return std::string(s ? s : "?");
    };
    return str(GL_VERSION) + ", " + str(GL_RENDERER);
  }

private:
  bool pointerStartUnset() const {
    return options_.pointerStart.position == glm::dvec3(0.0) &&
           options_.pointerStart.orientation == glm::dquat(1.0, 0.0, 0.0, 0.0);
  }

  void render(const std::vector<ToolView>& tools, const HudState& hud) {
    SDL_GL_MakeCurrent(window_, context_);
    SDL_GL_GetDrawableSize(window_, &width_, &height_);
    width_ = std::max(width_, 1);
    height_ = std::max(height_, 1);
    drawer_->setView(examine_.view());
    drawer_->draw(width_, height_, tools);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplSDL2_NewFrame();
    ImGui::NewFrame();
    if (showHud_) {
      HudExtras extras{options_.renderers, viewName(), frameMs_, options_.pointer};
      drawHud(hud, extras);
      drawHelpLine(extras);
      const SceneView& sv = drawer_->scene();
      bool capped = drawer_->capCuts();
      drawCutPanel(drawer_->cutPlanes(), activeCut_, sv.centre(), 0.5 * glm::length(sv.boundsMax - sv.boundsMin), capped);
      drawer_->setCapCuts(capped);
    }
    ImGui::Render();
    glViewport(0, 0, width_, height_);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }

  std::string viewName() const {
    const SceneView& sv = drawer_->scene();
    if (viewIndex_ >= 0) return sv.viewpoints[std::size_t(viewIndex_)].name;
    if (framedByKey_ || sv.framed) return "framed";
    return sv.viewpoints.empty() ? "framed" : sv.viewpoints.front().name;
  }

  // index −1: the scene's starting view (its first Viewpoint, or framed).
  void resetView(int index) {
    const SceneView& sv = drawer_->scene();
    viewIndex_ = index;
    framedByKey_ = false;
    if (index < 0) {
      const bool hasCentre = !sv.viewpoints.empty() && sv.viewpoints.front().hasCenterOfRotation && !sv.framed;
      examine_.reset(sv.view, hasCentre ? sv.viewpoints.front().centerOfRotation : sv.centre());
      return;
    }
    const NamedView& v = sv.viewpoints[std::size_t(index)];
    examine_.reset(v.view, v.hasCenterOfRotation ? v.centerOfRotation : sv.centre());
  }

  void frameAll() {
    const SceneView& sv = drawer_->scene();
    if (!sv.hasBounds()) return;
    const ViewSpec current = examine_.view();
    examine_.reset(frameBounds(sv.boundsMin, sv.boundsMax, current.orientation, current.fieldOfView), sv.centre());
    framedByKey_ = true;
  }

  // Every key (but Escape, and auto-repeats) also goes to the scene's
  // KeySensors as X3D names it: a character, an action key code or a modifier.
  void forwardKey(const SDL_KeyboardEvent& e, bool press) {
    if (e.repeat || ImGui::GetIO().WantCaptureKeyboard || e.keysym.sym == SDLK_ESCAPE) return;
    WindowCommand c = command(WindowCommand::Kind::Key);
    c.press = press;
    const SDL_Keycode s = e.keysym.sym;
    if (s >= SDLK_F1 && s <= SDLK_F12) c.index = int(s - SDLK_F1) + 1;
    else if (s == SDLK_HOME) c.index = 13;
    else if (s == SDLK_END) c.index = 14;
    else if (s == SDLK_PAGEUP) c.index = 15;
    else if (s == SDLK_PAGEDOWN) c.index = 16;
    else if (s == SDLK_UP) c.index = 17;
    else if (s == SDLK_DOWN) c.index = 18;
    else if (s == SDLK_LEFT) c.index = 19;
    else if (s == SDLK_RIGHT) c.index = 20;
    else if (s == SDLK_LSHIFT || s == SDLK_RSHIFT) c.modifier = WindowCommand::Modifier::Shift;
    else if (s == SDLK_LCTRL || s == SDLK_RCTRL) c.modifier = WindowCommand::Modifier::Control;
    else if (s == SDLK_LALT || s == SDLK_RALT) c.modifier = WindowCommand::Modifier::Alt;
    else if (s >= 32 && s < 127) {
      char ch = char(s);
      if (ch >= 'a' && ch <= 'z' && ((e.keysym.mod & KMOD_SHIFT) != 0) != ((e.keysym.mod & KMOD_CAPS) != 0))
        ch = char(ch - 'a' + 'A');
      c.character = std::string(1, ch);
    } else {
      return;  // a key X3D has no name for
    }
    commands_.push_back(std::move(c));
  }

  void key(const SDL_Keysym& k) {
    if (ImGui::GetIO().WantCaptureKeyboard) return;
    const int n = int(drawer_->scene().viewpoints.size());
    switch (k.sym) {
      case SDLK_ESCAPE: open_ = false; break;
      case SDLK_h: showHud_ = !showHud_; break;
      case SDLK_f:
      case SDLK_HOME: frameAll(); break;
      case SDLK_r: resetView(-1); break;
      case SDLK_PAGEDOWN:
        if (n > 0) resetView(viewIndex_ < 0 ? (n > 1 ? 1 : 0) : (viewIndex_ + 1) % n);
        break;
      case SDLK_PAGEUP:
        if (n > 0) resetView(viewIndex_ <= 0 ? n - 1 : viewIndex_ - 1);
        break;
      case SDLK_c: {
        const int i = drawer_->addUserCut(examine_.view().position - drawer_->scene().centre());
        CutPlane& c = drawer_->cutPlanes()[std::size_t(i)];
        c.enabled = !c.enabled;
        activeCut_ = i;
        break;
      }
      case SDLK_TAB:
        if (!drawer_->cutPlanes().empty()) activeCut_ = (activeCut_ + 1) % int(drawer_->cutPlanes().size());
        break;
      case SDLK_k: drawer_->setCapCuts(!drawer_->capCuts()); break;
      case SDLK_SPACE: spaceMilling_ = !spaceMilling_; break;
      case SDLK_e: commands_.push_back(command(WindowCommand::Kind::ToggleEnabled)); break;
      case SDLK_m: commands_.push_back(command(WindowCommand::Kind::ToggleMillable)); break;
      case SDLK_b: commands_.push_back(command(WindowCommand::Kind::NextBurrShape)); break;
      default:
        if (k.sym >= SDLK_1 && k.sym <= SDLK_9 && int(k.sym - SDLK_1) < int(options_.renderers.size()))
          commands_.push_back(command(WindowCommand::Kind::SelectRenderer, int(k.sym - SDLK_1)));
        if (k.sym >= SDLK_F1 && k.sym <= SDLK_F6) {
          const std::size_t i = std::size_t(k.sym - SDLK_F1);
          if (i < drawer_->cutPlanes().size()) drawer_->cutPlanes()[i].enabled = !drawer_->cutPlanes()[i].enabled;
        }
        break;
    }
  }

  void button(const SDL_MouseButtonEvent& b) {
    const bool down = b.type == SDL_MOUSEBUTTONDOWN;
    if (down && ImGui::GetIO().WantCaptureMouse) return;
    if (b.button == SDL_BUTTON_LEFT) leftHeld_ = down && options_.pointer && !(SDL_GetModState() & KMOD_ALT);
    if (b.button == SDL_BUTTON_LEFT) leftDrag_ = down;
    if (b.button == SDL_BUTTON_MIDDLE) middleDrag_ = down;
    if (b.button == SDL_BUTTON_RIGHT) rightDrag_ = down;
  }

  void motion(const SDL_MouseMotionEvent& m) {
    if (ImGui::GetIO().WantCaptureMouse && !leftDrag_ && !middleDrag_ && !rightDrag_) return;
    const SDL_Keymod mod = SDL_GetModState();
    // Window pixels to drawable pixels (they differ on high-DPI screens).
    int ww = 1, wh = 1;
    SDL_GetWindowSize(window_, &ww, &wh);
    const double sx = double(width_) / std::max(ww, 1), sy = double(height_) / std::max(wh, 1);
    const double dx = m.xrel * sx, dy = m.yrel * sy;
    const Camera& camera = drawer_->camera();
    if (options_.pointer) {
      if (rightDrag_) {
        pointerTool_.turn(camera, dx, dy);
        return;
      }
      if (!(mod & KMOD_ALT) && !middleDrag_) {
        // SDL's first report is where the cursor was when the window appeared
        // under it, not a move: followed, it took the burr from where the
        // scene starts it (MouseDevice.position) to wherever the cursor was.
        if (std::exchange(awaitingFirstMove_, false)) return;
        pointerTool_.follow(camera, m.x * sx, m.y * sy);
        return;
      }
    }
    if ((mod & KMOD_CTRL) && leftDrag_) {
      moveCut(dx, dy);
      return;
    }
    if (!navigate_) return;
    // Without the mouse as a tool: drag turns, Shift+drag or middle-drag pans.
    // With it the left button mills, so Alt+drag or middle-drag turns and
    // Shift with either pans (the help line says the same, Hud.cpp).
    const bool shift = (mod & KMOD_SHIFT) != 0;
    const bool pan = options_.pointer ? shift && (leftDrag_ || middleDrag_) : middleDrag_ || (leftDrag_ && shift);
    if (pan)
      examine_.pan(dx, dy, height_);
    else if (leftDrag_ || (options_.pointer && middleDrag_))
      examine_.rotate(dx, dy, height_);
  }

  void wheel(const SDL_MouseWheelEvent& w) {
    if (ImGui::GetIO().WantCaptureMouse) return;
    const double notches = w.preciseY != 0.f ? double(w.preciseY) : double(w.y);
    if (options_.pointer && (SDL_GetModState() & KMOD_CTRL)) {
      pointerTool_.push(drawer_->camera(), -notches);
      return;
    }
    if (SDL_GetModState() & KMOD_CTRL) {
      moveCut(0.0, -notches * 10.0);
      return;
    }
    if (navigate_) examine_.zoom(notches);
  }

  // Ctrl+drag: up/down slides the active cut along its normal (a window
  // height = the scene's size), left/right turns it about the view's up axis.
  void moveCut(double dx, double dy) {
    auto& planes = drawer_->cutPlanes();
    if (planes.empty() || activeCut_ < 0 || activeCut_ >= int(planes.size())) return;
    CutPlane& c = planes[std::size_t(activeCut_)];
    const SceneView& sv = drawer_->scene();
    const double size = std::max(glm::length(sv.boundsMax - sv.boundsMin), 1e-4);
    glm::dvec3 n(c.plane);
    double offset = glm::dot(n, sv.centre()) + c.plane.w;
    offset += -dy / std::max(height_, 1) * size;
    const glm::dvec3 up = glm::mat3_cast(examine_.view().orientation) * glm::dvec3(0.0, 1.0, 0.0);
    n = glm::normalize(glm::angleAxis(dx * 3.14159265 / std::max(height_, 1), up) * n);
    c.plane = glm::dvec4(n, offset - glm::dot(n, sv.centre()));
  }

  WindowOptions options_;
  SDL_Window* window_ = nullptr;
  SDL_GLContext context_ = nullptr;
  std::unique_ptr<SceneDrawer> drawer_;
  ExamineNavigator examine_;
  PointerTool pointerTool_;
  bool awaitingFirstMove_ = true;
  std::vector<WindowCommand> commands_;
  std::vector<ToolView> lastTools_;
  HudState lastHud_;
  int width_ = 1, height_ = 1;
  int viewIndex_ = -1, activeCut_ = 0;
  bool open_ = true, showHud_ = true, navigate_ = true, framedByKey_ = false;
  bool leftDrag_ = false, middleDrag_ = false, rightDrag_ = false, leftHeld_ = false, spaceMilling_ = false;
  double frameMs_ = 0.0;
};

std::unique_ptr<AppWindow> open(const Scene& scene, const WindowOptions& options) {
  return std::make_unique<SdlWindow>(scene, options);
}

const WindowModule kModule{kWindowAbiVersion, &open};

}  // namespace

}  // namespace millsim

// Typed as the loader calls it (SiblingLibrary: const void* (*)()): a call through
// another function type is undefined behaviour (clang's -fsanitize=function).
extern "C" __attribute__((visibility("default"))) const void* millsim_window_module() {
  return &millsim::kModule;
}
