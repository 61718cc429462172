#pragma once
// Loading the graphics library at run time. The millsim command does not link
// libmillsim_graphics (nor, through it, OSMesa): a verb that draws loads it
// with loadGraphicsModule(), so that every other verb runs where OSMesa is not
// installed, and a verb that draws says clearly why it cannot.
//
//   const GraphicsModule& g = loadGraphicsModule();   // throws GraphicsError
//   auto renderer = g.createRenderer(scene, options);  // see SceneRenderer.h
//
// Programs that always draw (tests, benchmarks) link millsim_graphics and call
// createSceneRenderer() directly.
#include <filesystem>
#include <memory>

#include "millsim/graphics/Image.h"

namespace millsim {

class Scene;
class SceneRenderer;
struct RendererOptions;

// Bumped whenever SceneRenderer or this table change incompatibly.
inline constexpr int kGraphicsAbiVersion = 1;

struct GraphicsModule {
  int abiVersion;
  std::unique_ptr<SceneRenderer> (*createRenderer)(const Scene& scene, const RendererOptions& options);
  void (*writePng)(const Image& image, const std::filesystem::path& path);
};

// Opens the library once per process (MILLSIM_GRAPHICS_LIBRARY overrides its
// path; by default it is looked for next to libmillsim). Throws GraphicsError
// with the loader's message, e.g. "libOSMesa.so.8: cannot open shared object file".
const GraphicsModule& loadGraphicsModule();

}  // namespace millsim
