// The offscreen SceneRenderer (SceneRenderer.h): an OSMesa context and the
// SceneDrawer that the window uses too.
#include <stdexcept>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>

#include "millsim/core/Scene.h"
#include "millsim/graphics/GlContext.h"
#include "millsim/graphics/SceneRenderer.h"
#include "millsim/std/Viewpoint.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

namespace {

const Node* findViewpoint(const Scene& scene, const std::string& name) {
  if (name.empty()) return nullptr;
  const auto node = scene.def(name);
  if (!dynamic_cast<const Viewpoint*>(node.get())) {
    std::string names;
    for (const auto& [def, n] : scene.defs)
      if (dynamic_cast<const Viewpoint*>(n.get())) names += (names.empty() ? "" : ", ") + def;
    throw std::invalid_argument("no Viewpoint named '" + name + "' in the scene (named viewpoints: " +
                                (names.empty() ? "none" : names) + ")");
  }
  return node.get();
}

SceneView viewWithVoxels(const Scene& scene, const RendererOptions& options) {
  SceneView view = readSceneView(scene, findViewpoint(scene, options.viewpoint));
  if (!options.voxels.empty() && options.voxels.size() != view.volumes.size())
    throw std::invalid_argument("RendererOptions::voxels has " + std::to_string(options.voxels.size()) +
                                " volumes but the scene has " + std::to_string(view.volumes.size()));
  for (std::size_t i = 0; i < options.voxels.size(); ++i) {
    const VoxelVolume* v = options.voxels[i];
    if (!v || v->dims() != view.volumes[i].voxels->dims() || v->voxelSize() != view.volumes[i].voxels->voxelSize())
      throw std::invalid_argument("RendererOptions::voxels[" + std::to_string(i) +
                                  "] is null or not shaped like the scene's volume");
    view.volumes[i].voxels = v;
  }
  return view;
}

class GlSceneRenderer final : public SceneRenderer {
public:
  GlSceneRenderer(const Scene& scene, const RendererOptions& options)
      : context_(options.width, options.height), drawer_(std::make_unique<SceneDrawer>(viewWithVoxels(scene, options))) {
    drawer_->setLevelOfDetail(options.levelOfDetail);
    drawer_->setCapCuts(options.capCuts);
    drawer_->aim(options.width, options.height);
    GlContext::check("setting up the renderer");
  }
  // GL objects are deleted with the context current.
  ~GlSceneRenderer() override {
    context_.makeCurrent();
    drawer_.reset();
  }

  std::size_t addVolume(const VoxelVolume& voxels, const glm::dmat4& localToWorld, double iso) override {
    context_.makeCurrent();
    return drawer_->addVolume(voxels, localToWorld, iso);
  }
  std::size_t volumeCount() const override { return drawer_->volumeCount(); }
  void volumeChanged(std::size_t index, const std::vector<BlockOrigin>& blocks) override {
    if (blocks.empty()) return;
    context_.makeCurrent();
    drawer_->volumeChanged(index, blocks);
  }
  void rebuildVolume(std::size_t index) override {
    context_.makeCurrent();
    drawer_->rebuildVolume(index);
  }

  bool sceneChanged(const SceneView& fresh) override { return drawer_->adoptView(fresh); }
  void setView(const ViewSpec& view) override { drawer_->setView(view); }
  ViewSpec view() const override { return drawer_->view(); }
  Camera camera() const override { return drawer_->camera(); }

  void render(const std::optional<ToolView>& tool) override {
    context_.makeCurrent();
    std::vector<ToolView> tools;
    if (tool) tools.push_back(*tool);
    drawer_->draw(context_.width(), context_.height(), tools);
    glFinish();
    GlContext::check("rendering a frame");
  }
  Image readPixels() override {
    context_.makeCurrent();
    return SceneDrawer::readPixels(context_.width(), context_.height());
  }
  std::vector<float> readDepth() override {
    context_.makeCurrent();
    return SceneDrawer::readDepth(context_.width(), context_.height());
  }
  RendererStats stats() const override { return drawer_->stats(); }
  std::string glDescription() const override { return context_.description(); }

private:
  GlContext context_;
  std::unique_ptr<SceneDrawer> drawer_;
};

}  // namespace

std::unique_ptr<SceneRenderer> createSceneRenderer(const Scene& scene, const RendererOptions& options) {
  return std::make_unique<GlSceneRenderer>(scene, options);
}

}  // namespace millsim
