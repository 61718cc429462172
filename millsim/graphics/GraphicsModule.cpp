// The table loadGraphicsModule() finds in libmillsim_graphics.
#include "millsim/graphics/GraphicsModule.h"

#include "millsim/graphics/SceneRenderer.h"

namespace {

std::unique_ptr<millsim::SceneRenderer> create(const millsim::Scene& scene, const millsim::RendererOptions& options) {
  return millsim::createSceneRenderer(scene, options);
}

void png(const millsim::Image& image, const std::filesystem::path& path) { millsim::writePng(image, path); }

const millsim::GraphicsModule kModule{millsim::kGraphicsAbiVersion, &create, &png};

}  // namespace

// Typed as the loader calls it (SiblingLibrary: const void* (*)()): a call through
// another function type is undefined behaviour (clang's -fsanitize=function).
extern "C" __attribute__((visibility("default"))) const void* millsim_graphics_module() {
  return &kModule;
}
