// The OpenGL implementation of SceneRenderer (see SceneRenderer.h).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/gtc/matrix_transform.hpp>

#include "millsim/core/Scene.h"
#include "millsim/graphics/GlContext.h"
#include "millsim/graphics/GlMesh.h"
#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/SceneRenderer.h"
#include "millsim/graphics/ShadedProgram.h"
#include "millsim/graphics/VolumeMesh.h"
#include "millsim/std/Viewpoint.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

namespace {

// The tool's look: a steel-blue burr and a grey shaft, hues no tooth has.
const DrawMaterial kBurr{glm::vec3(0.45f, 0.55f, 0.85f), glm::vec3(0.6f), glm::vec3(0.f), 0.25f, 0.4f};
const DrawMaterial kShaft{glm::vec3(0.55f, 0.58f, 0.66f), glm::vec3(0.5f), glm::vec3(0.f), 0.25f, 0.3f};
const DrawMaterial kMarker{glm::vec3(1.f, 0.05f, 0.05f), glm::vec3(0.3f), glm::vec3(0.25f, 0.f, 0.f), 0.3f, 0.2f};
const DrawMaterial kTissue{glm::vec3(1.f), glm::vec3(0.22f), glm::vec3(0.f), 0.22f, 0.25f};

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

class GlSceneRenderer final : public SceneRenderer {
public:
  GlSceneRenderer(const Scene& scene, const RendererOptions& options)
      : context_(options.width, options.height),
        scene_(readSceneView(scene, findViewpoint(scene, options.viewpoint))),
        view_(scene_.view) {
    if (!options.voxels.empty() && options.voxels.size() != scene_.volumes.size())
      throw std::invalid_argument("RendererOptions::voxels has " + std::to_string(options.voxels.size()) +
                                  " volumes but the scene has " + std::to_string(scene_.volumes.size()));
    for (std::size_t i = 0; i < options.voxels.size(); ++i) {
      const VoxelVolume* v = options.voxels[i];
      if (!v || v->dims() != scene_.volumes[i].voxels->dims() ||
          v->voxelSize() != scene_.volumes[i].voxels->voxelSize())
        throw std::invalid_argument("RendererOptions::voxels[" + std::to_string(i) +
                                    "] is null or not shaped like the scene's volume");
      scene_.volumes[i].voxels = v;
    }
    program_ = std::make_unique<ShadedProgram>();
    std::vector<Vertex> v;
    std::vector<std::uint32_t> idx;
    unitSphere(v, idx);
    sphere_.upload(v, idx);
    unitCylinder(v, idx);
    cylinder_.upload(v, idx);
    unitBox(v, idx);
    box_.upload(v, idx);
    for (const DrawVolume& dv : scene_.volumes) {
      meshes_.push_back(std::make_unique<VolumeMesh>(*dv.voxels, float(dv.iso)));
      meshes_.back()->build();
    }
    camera_ = frameCamera(std::nullopt);
    GlContext::check("setting up the renderer");
  }
  // GL objects (members) are deleted after this body: with the context current.
  ~GlSceneRenderer() override { context_.makeCurrent(); }

  std::size_t addVolume(const VoxelVolume& voxels, const glm::dmat4& localToWorld, double iso) override {
    context_.makeCurrent();
    scene_.volumes.push_back({&voxels, localToWorld, iso, {}});
    meshes_.push_back(std::make_unique<VolumeMesh>(voxels, float(iso)));
    meshes_.back()->build();
    return meshes_.size() - 1;
  }
  std::size_t volumeCount() const override { return meshes_.size(); }

  void volumeChanged(std::size_t index, const std::vector<BlockOrigin>& blocks) override {
    if (blocks.empty()) return;
    context_.makeCurrent();
    mesh(index).update(blocks);
  }
  void rebuildVolume(std::size_t index) override {
    context_.makeCurrent();
    mesh(index).build();
  }

  void setView(const ViewSpec& view) override { view_ = view; }
  ViewSpec view() const override { return view_; }
  Camera camera() const override { return camera_; }

  void render(const std::optional<ToolView>& tool) override {
    context_.makeCurrent();
    camera_ = frameCamera(tool);
    glViewport(0, 0, context_.width(), context_.height());
    glClearColor(scene_.background.r, scene_.background.g, scene_.background.b, 1.f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);  // open iso-surfaces and cut-planes show their insides
    for (int i = 0; i < kMaxClipPlanes; ++i) glEnable(GLenum(GL_CLIP_DISTANCE0 + i));

    // Headlight from the eye; fill light from the camera's upper left.
    const glm::dmat3 cameraAxes = glm::mat3_cast(view_.orientation);
    const glm::vec3 head(glm::normalize(cameraAxes * glm::dvec3(0.0, 0.0, 1.0)));
    const glm::vec3 fill(glm::normalize(cameraAxes * glm::dvec3(-0.6, 0.8, 0.4)));
    program_->use(camera_, head, fill);

    for (std::size_t i = 0; i < meshes_.size(); ++i) {
      program_->setObject(scene_.volumes[i].localToWorld, kTissue, nullptr, true, scene_.volumes[i].clipPlanes);
      meshes_[i]->draw();
    }
    for (const DrawShape& s : scene_.shapes) {
      program_->setObject(s.model, s.material, &s.material.diffuse, false, s.clipPlanes);
      (s.kind == DrawShape::Kind::Sphere ? sphere_ : s.kind == DrawShape::Kind::Cylinder ? cylinder_ : box_).draw();
    }
    if (tool) drawTool(*tool);
    glBindVertexArray(0);
    glFinish();
    GlContext::check("rendering a frame");
  }

  Image readPixels() override {
    context_.makeCurrent();
    Image img;
    img.width = context_.width();
    img.height = context_.height();
    img.rgba.resize(std::size_t(img.width) * std::size_t(img.height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
    flipRows(img.rgba.data(), std::size_t(img.width) * 4, img.height);
    return img;
  }

  std::vector<float> readDepth() override {
    context_.makeCurrent();
    std::vector<float> depth(std::size_t(context_.width()) * std::size_t(context_.height()));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, context_.width(), context_.height(), GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    flipRows(reinterpret_cast<std::uint8_t*>(depth.data()), std::size_t(context_.width()) * sizeof(float),
             context_.height());
    return depth;
  }

  RendererStats stats() const override {
    RendererStats s;
    for (const auto& m : meshes_) {
      s.triangles += m->triangles();
      s.chunks += m->chunks();
      s.chunkUploads += m->uploads();
    }
    return s;
  }
  std::string glDescription() const override { return context_.description(); }

private:
  VolumeMesh& mesh(std::size_t index) {
    if (index >= meshes_.size())
      throw std::out_of_range("volume index " + std::to_string(index) + " is out of range (the renderer has " +
                              std::to_string(meshes_.size()) + " volumes)");
    return *meshes_[index];
  }

  static void flipRows(std::uint8_t* data, std::size_t rowBytes, int rows) {
    std::vector<std::uint8_t> tmp(rowBytes);
    for (int y = 0; y < rows / 2; ++y) {
      std::uint8_t* a = data + std::size_t(y) * rowBytes;
      std::uint8_t* b = data + std::size_t(rows - 1 - y) * rowBytes;
      std::copy(a, a + rowBytes, tmp.data());
      std::copy(b, b + rowBytes, a);
      std::copy(tmp.data(), tmp.data() + rowBytes, b);
    }
  }

  // Near and far planes hug what there is to see (scene bounds and tool), so
  // that a 24-bit depth buffer resolves a tooth seen from a few centimetres.
  Camera frameCamera(const std::optional<ToolView>& tool) const {
    glm::dvec3 lo = scene_.boundsMin, hi = scene_.boundsMax;
    bool any = !scene_.volumes.empty() || !scene_.shapes.empty();
    if (tool) {
      const double reach = tool->geometry.shaftLength + tool->geometry.tipRadius;
      const glm::dvec3 a = tool->pose.position - reach, b = tool->pose.position + reach;
      lo = any ? glm::min(lo, a) : a;
      hi = any ? glm::max(hi, b) : b;
      any = true;
    }
    double farthest = 1.0, nearest = 0.0;
    if (any) {
      farthest = 0.0;
      for (int c = 0; c < 8; ++c) {
        const glm::dvec3 corner(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
        farthest = std::max(farthest, glm::length(corner - view_.position));
      }
      nearest = glm::length(glm::max(glm::max(lo - view_.position, view_.position - hi), glm::dvec3(0.0)));
    }
    const double farDistance = std::max(farthest * 1.05, 1e-3);
    const double nearDistance = std::max(nearest * 0.5, farDistance * 1e-4);
    return makeCamera(view_, context_.width(), context_.height(), nearDistance, farDistance);
  }

  void drawTool(const ToolView& t) {
    const ClipPlanes none;
    const glm::dmat4 pose =
        glm::translate(glm::dmat4(1.0), t.pose.position) * glm::mat4_cast(glm::normalize(t.pose.orientation));
    program_->setObject(glm::scale(pose, glm::dvec3(t.geometry.tipRadius)), kBurr, &kBurr.diffuse, false, none);
    sphere_.draw();
    const glm::dmat4 shaft = glm::scale(glm::translate(pose, glm::dvec3(0.0, t.geometry.shaftLength / 2, 0.0)),
                                        glm::dvec3(t.geometry.shaftRadius, t.geometry.shaftLength,
                                                   t.geometry.shaftRadius));
    program_->setObject(shaft, kShaft, &kShaft.diffuse, false, none);
    cylinder_.draw();
    if (t.hasIntersection) {
      // As thick as the shaft and drawn over everything: the point is where
      // the shaft enters the tooth, so the tooth would hide it (paper, Fig. 14).
      const double r = std::max(t.geometry.shaftRadius, 0.5 * t.geometry.tipRadius);
      program_->setObject(glm::scale(glm::translate(glm::dmat4(1.0), t.intersection), glm::dvec3(r)), kMarker,
                          &kMarker.diffuse, false, none);
      glDisable(GL_DEPTH_TEST);
      sphere_.draw();
      glEnable(GL_DEPTH_TEST);
    }
  }

  GlContext context_;
  SceneView scene_;
  ViewSpec view_;
  Camera camera_;
  std::unique_ptr<ShadedProgram> program_;
  GlMesh sphere_{false}, cylinder_{false}, box_{false};
  std::vector<std::unique_ptr<VolumeMesh>> meshes_;
};

}  // namespace

std::unique_ptr<SceneRenderer> createSceneRenderer(const Scene& scene, const RendererOptions& options) {
  return std::make_unique<GlSceneRenderer>(scene, options);
}

}  // namespace millsim
