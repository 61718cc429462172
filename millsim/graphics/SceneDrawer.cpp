// SceneDrawer (SceneDrawer.h): the scene's one OpenGL drawing.
#include "millsim/graphics/SceneDrawer.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <glm/gtc/matrix_transform.hpp>

#include "millsim/graphics/CutCap.h"
#include "millsim/graphics/FontAtlas.h"
#include "millsim/graphics/GlMesh.h"
#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/ImageFile.h"
#include "millsim/graphics/ShadedProgram.h"
#include "millsim/graphics/TextMesh.h"
#include "millsim/graphics/TriangleMesh.h"
#include "millsim/graphics/VolumeMesh.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

namespace {

// The tool's look: a steel-blue burr and a grey shaft, hues no tooth has; the
// device's ghost in green wire, the intersection marker red.
const DrawMaterial kBurr{glm::vec3(0.45f, 0.55f, 0.85f), glm::vec3(0.6f), glm::vec3(0.f), 0.25f, 0.4f};
const DrawMaterial kShaft{glm::vec3(0.55f, 0.58f, 0.66f), glm::vec3(0.5f), glm::vec3(0.f), 0.25f, 0.3f};
const DrawMaterial kGhost{glm::vec3(0.2f, 0.9f, 0.3f), glm::vec3(0.f), glm::vec3(0.1f, 0.4f, 0.1f), 0.5f, 0.1f};
const DrawMaterial kMarker{glm::vec3(1.f, 0.05f, 0.05f), glm::vec3(0.3f), glm::vec3(0.25f, 0.f, 0.f), 0.3f, 0.2f};
const DrawMaterial kTissue{glm::vec3(1.f), glm::vec3(0.22f), glm::vec3(0.f), 0.22f, 0.25f};
// A cut's section is matt: a highlight would wash out the tissue colours a
// teacher reads the walls by.
const DrawMaterial kSection{glm::vec3(1.f), glm::vec3(0.f), glm::vec3(0.f), 0.22f, 0.1f};

// A TriangleMesh (unshared corners) into a GlMesh: per-vertex colours when
// `colours`, else white for the per-draw colour; texture coordinates if any.
void upload(GlMesh& gl, const TriangleMesh& mesh, bool colours) {
  std::vector<Vertex> v(mesh.positions.size());
  std::vector<std::uint32_t> idx(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    v[i] = {mesh.positions[i], mesh.normals[i], colours ? mesh.colours[i] : glm::vec3(1.f)};
    idx[i] = std::uint32_t(i);
  }
  gl.upload(v, idx);
  if (mesh.texCoords.size() == v.size()) gl.uploadTexCoords(mesh.texCoords);
}

}  // namespace

SceneDrawer::SceneDrawer(SceneView scene) : scene_(std::move(scene)), view_(scene_.view) {
  program_ = std::make_unique<ShadedProgram>();
  std::vector<Vertex> v;
  std::vector<std::uint32_t> idx;
  sphere_ = std::make_unique<GlMesh>(false);
  cylinder_ = std::make_unique<GlMesh>(false);
  box_ = std::make_unique<GlMesh>(false);
  unitSphere(v, idx);
  sphere_->upload(v, idx);
  unitCylinder(v, idx);
  cylinder_->upload(v, idx);
  unitBox(v, idx);
  box_->upload(v, idx);
  for (const DrawVolume& dv : scene_.volumes) {
    meshes_.push_back(std::make_unique<VolumeMesh>(*dv.voxels, float(dv.iso), dv.tissues));
  }
}

SceneDrawer::~SceneDrawer() {
  for (auto& [file, t] : textures_)
    if (t.id) glDeleteTextures(1, &t.id);
}

std::size_t SceneDrawer::addVolume(const VoxelVolume& voxels, const glm::dmat4& localToWorld, double iso) {
  scene_.volumes.push_back({&voxels, localToWorld, iso, {}, {}});
  meshes_.push_back(std::make_unique<VolumeMesh>(voxels, float(iso)));
  return meshes_.size() - 1;
}

std::size_t SceneDrawer::volumeCount() const { return meshes_.size(); }

void SceneDrawer::volumeChanged(std::size_t index, const std::vector<BlockOrigin>& blocks) {
  if (blocks.empty()) return;
  mesh(index).update(blocks);
  for (auto& [key, cap] : caps_)
    if (key.first == index) cap->update(blocks);
}

void SceneDrawer::rebuildVolume(std::size_t index) {
  mesh(index).build();
  for (auto& [key, cap] : caps_)
    if (key.first == index) cap->invalidate();
}

VolumeMesh& SceneDrawer::mesh(std::size_t index) {
  if (index >= meshes_.size())
    throw std::out_of_range("volume index " + std::to_string(index) + " is out of range (the renderer has " +
                            std::to_string(meshes_.size()) + " volumes)");
  return *meshes_[index];
}

bool SceneDrawer::adoptCuts(const SceneView& fresh) {
  if (fresh.volumes.size() != scene_.volumes.size() || fresh.shapes.size() != scene_.shapes.size()) return false;
  std::vector<CutPlane> user;
  for (const CutPlane& c : scene_.cutPlanes)
    if (c.user) user.push_back(c);
  scene_.cutPlanes = fresh.cutPlanes;
  for (std::size_t i = 0; i < fresh.volumes.size(); ++i) {
    scene_.volumes[i].clipPlanes = fresh.volumes[i].clipPlanes;
    scene_.volumes[i].cuts = fresh.volumes[i].cuts;
  }
  for (std::size_t i = 0; i < fresh.shapes.size(); ++i) {
    scene_.shapes[i].clipPlanes = fresh.shapes[i].clipPlanes;
    scene_.shapes[i].cuts = fresh.shapes[i].cuts;
  }
  for (const CutPlane& c : user) {
    scene_.cutPlanes.push_back(c);
    for (DrawVolume& v : scene_.volumes) v.cuts.push_back(int(scene_.cutPlanes.size() - 1));
  }
  // A cap kept under an index that now names another plane samples that plane at its next draw.
  std::erase_if(caps_, [&](const auto& entry) { return entry.first.second >= int(scene_.cutPlanes.size()); });
  return true;
}

bool SceneDrawer::adoptView(const SceneView& fresh) {
  if (fresh.volumes.size() != scene_.volumes.size()) return false;
  scene_.shapes = fresh.shapes;  // first, so that adoptCuts sees the same shapes
  scene_.background = fresh.background;
  scene_.headlight = fresh.headlight;
  scene_.lights = fresh.lights;
  for (std::size_t i = 0; i < fresh.volumes.size(); ++i) scene_.volumes[i].lights = fresh.volumes[i].lights;
  return adoptCuts(fresh);
}

ClipPlanes SceneDrawer::planesFor(const std::vector<int>& cutIndices, bool volume) const {
  ClipPlanes out;
  for (int i : cutIndices) {
    const CutPlane& c = scene_.cutPlanes[std::size_t(i)];
    if (c.enabled && (volume || !c.user)) out.push_back(c.plane);
  }
  return out;
}

void SceneDrawer::draw(int width, int height, const std::vector<ToolView>& tools) {
  aim(width, height, tools);
  glViewport(0, 0, width, height);
  glClearColor(scene_.background.r, scene_.background.g, scene_.background.b, 1.f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // open iso-surfaces and cut-planes show their insides
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  for (int i = 0; i < kMaxClipPlanes; ++i) glEnable(GLenum(GL_CLIP_DISTANCE0 + i));

  // Headlight from the eye; fill light from the camera's upper left.
  const glm::dmat3 cameraAxes = glm::mat3_cast(view_.orientation);
  const glm::vec3 head(glm::normalize(cameraAxes * glm::dvec3(0.0, 0.0, 1.0)));
  const glm::vec3 fill(glm::normalize(cameraAxes * glm::dvec3(-0.6, 0.8, 0.4)));
  program_->use(camera_, head, fill, scene_.headlight, scene_.lights);

  for (std::size_t i = 0; i < meshes_.size(); ++i) {
    program_->setObject(scene_.volumes[i].localToWorld, kTissue, nullptr, true, planesFor(scene_.volumes[i].cuts, true));
    program_->setLights(scene_.volumes[i].lights);
    const int level = levelOfDetail(i, height);
    meshes_[i]->prepare(level);
    meshes_[i]->draw(level);
    if (drawnLevels_.size() < meshes_.size()) drawnLevels_.resize(meshes_.size(), 0);
    drawnLevels_[i] = level;
  }
  capsDrawn_ = 0;
  if (capCuts_)
    for (std::size_t i = 0; i < meshes_.size(); ++i) drawCaps(i);
  std::vector<const DrawShape*> seeThrough;
  for (const DrawShape& s : scene_.shapes)
    if (s.material.transparency > 0.f || s.kind == DrawShape::Kind::Text) seeThrough.push_back(&s);  // glyph edges blend
    else drawShape(s);
  for (const ToolView& t : tools) drawTool(t);
  // See-through shapes last, farthest first, blended over what is behind them
  // and not hiding each other in the depth buffer (enough for a few convex
  // region shapes; no per-triangle sorting). Region overlays ignore depth:
  // they show through the tooth that holds them.
  if (!seeThrough.empty()) {
    const glm::dvec3 eye = camera_.eye();
    auto distance = [&](const DrawShape* s) { return glm::length(glm::dvec3(s->model[3]) - eye); };
    std::stable_sort(seeThrough.begin(), seeThrough.end(),
                     [&](const DrawShape* a, const DrawShape* b) { return distance(a) > distance(b); });
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    for (const DrawShape* s : seeThrough) {
      if (s->overlay) glDisable(GL_DEPTH_TEST);
      drawShape(*s);
      glEnable(GL_DEPTH_TEST);
    }
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }
  for (int i = 0; i < kMaxClipPlanes; ++i) glDisable(GLenum(GL_CLIP_DISTANCE0 + i));
  glBindVertexArray(0);
  dropUnused();
}

void SceneDrawer::drawCaps(std::size_t i) {
  const DrawVolume& dv = scene_.volumes[i];
  for (int c : dv.cuts) {
    const CutPlane& cut = scene_.cutPlanes[std::size_t(c)];
    if (!cut.enabled) continue;
    std::unique_ptr<CutCap>& cap = caps_[{i, c}];
    if (!cap) cap = std::make_unique<CutCap>(*dv.voxels, float(dv.iso), dv.tissues);
    if (!cap->aim(cut.plane, dv.localToWorld)) continue;
    ClipPlanes others;
    for (int o : dv.cuts)
      if (o != c && scene_.cutPlanes[std::size_t(o)].enabled) others.push_back(scene_.cutPlanes[std::size_t(o)].plane);
    program_->setObject(glm::dmat4(1.0), kSection, nullptr, false, others);
    program_->setLights(dv.lights);
    program_->setTexture(ShadedProgram::TextureMode::Section);
    cap->draw();
    ++capsDrawn_;
  }
}

int SceneDrawer::levelOfDetail(std::size_t i, int height) const {
  // How many pixels one voxel covers at the volume's centre: below about 1.5
  // its triangles (about two per surface voxel) are smaller than a pixel.
  if (!levelOfDetail_) return 0;
  const glm::dmat4& m = scene_.volumes[i].localToWorld;
  const glm::dvec3 centre(m[3]);
  const double distance = glm::length(centre - camera_.eye());
  const double scale = glm::length(glm::dvec3(m[0]));
  const double pixelsPerMetre = 0.5 * double(height) * camera_.projection[1][1] / std::max(distance, 1e-9);
  const double pixels = meshes_[i]->voxelSize() * scale * pixelsPerMetre;
  int level = 0;
  while (level + 1 < meshes_[i]->levels() && pixels * double(1 << level) < kCoarseBelowPixels) ++level;
  return level;
}

void SceneDrawer::drawShape(const DrawShape& s) {
  const ClipPlanes planes = planesFor(s.cuts, false);
  switch (s.kind) {
    case DrawShape::Kind::Sphere:
    case DrawShape::Kind::Cylinder:
    case DrawShape::Kind::Box:
      program_->setObject(s.model, s.material, &s.material.diffuse, false, planes);
      program_->setLights(s.lights);
      (s.kind == DrawShape::Kind::Sphere ? *sphere_ : s.kind == DrawShape::Kind::Cylinder ? *cylinder_ : *box_).draw();
      return;
    case DrawShape::Kind::Mesh: {
      GlMesh& gl = meshFor(s.mesh);
      program_->setObject(s.model, s.material, s.mesh->colours.empty() ? &s.material.diffuse : nullptr, false, planes);
      program_->setLights(s.lights);
      bool grey = false;
      if (!s.texture.file.empty() && bindTexture(s.texture, grey))
        program_->setTexture(grey ? ShadedProgram::TextureMode::Modulate : ShadedProgram::TextureMode::Replace);
      gl.draw();
      return;
    }
    case DrawShape::Kind::Text: {
      FontAtlas* font = nullptr;
      GlMesh* gl = textFor(*s.text, font);
      if (!gl) return;
      program_->setObject(s.model, s.material, &s.material.diffuse, false, planes);
      program_->setLights(s.lights);
      font->bind();
      program_->setTexture(ShadedProgram::TextureMode::Coverage);
      gl->draw();
      return;
    }
  }
}

GlMesh& SceneDrawer::meshFor(const std::shared_ptr<const TriangleMesh>& mesh) {
  CachedMesh& c = shapeMeshes_[mesh.get()];
  if (!c.gl) {
    c.source = mesh;
    const bool colours = mesh->colours.size() == mesh->positions.size();
    c.gl = std::make_unique<GlMesh>(colours);
    upload(*c.gl, *mesh, colours);
  }
  return *c.gl;
}

GlMesh* SceneDrawer::textFor(const DrawText& text, FontAtlas*& font) {
  for (CachedText& c : texts_)
    if (c.text == text) return font = c.font, c.gl.get();
  // The first family fontconfig resolves (it always finds one: its substitutes).
  const std::string family = text.family.empty() ? "SERIF" : text.family.front();
  auto [slot, fresh] = fonts_.try_emplace({family, text.style});
  auto& atlas = slot->second;
  if (fresh) {
    try {
      atlas = std::make_unique<FontAtlas>(family, text.style);
    } catch (const GraphicsError& e) {
      std::cerr << "millsim: warning: Text is not drawn: " << e.what() << "\n";  // once: the empty slot stays
    }
  }
  if (!atlas) return nullptr;
  const TriangleMesh mesh = layoutText(text, *atlas);
  CachedText c{text, atlas.get(), std::make_unique<GlMesh>(false)};
  upload(*c.gl, mesh, false);
  texts_.push_back(std::move(c));
  return font = texts_.back().font, texts_.back().gl.get();
}

bool SceneDrawer::bindTexture(const DrawTexture& texture, bool& grey) {
  auto [it, fresh] = textures_.try_emplace(texture.file);
  CachedTexture& t = it->second;
  if (fresh) {
    try {
      const TextureImage img = readTextureImage(texture.file);
      glGenTextures(1, &t.id);
      glBindTexture(GL_TEXTURE_2D, t.id);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, img.width, img.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
      glGenerateMipmap(GL_TEXTURE_2D);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      t.grey = img.grey;
    } catch (const GraphicsError& e) {
      std::cerr << "millsim: warning: ImageTexture is not drawn: " << e.what() << "\n";
    }
  }
  if (!t.id) return false;
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, t.id);
  // Per draw: two shapes may share an image with different wrapping.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, texture.repeatS ? GL_REPEAT : GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, texture.repeatT ? GL_REPEAT : GL_CLAMP_TO_EDGE);
  grey = t.grey;
  return true;
}

void SceneDrawer::dropUnused() {
  if (shapeMeshes_.size() + texts_.size() <= scene_.shapes.size()) return;
  for (auto it = shapeMeshes_.begin(); it != shapeMeshes_.end();) {
    const bool used = std::any_of(scene_.shapes.begin(), scene_.shapes.end(),
                                  [&](const DrawShape& s) { return s.mesh.get() == it->first; });
    it = used ? std::next(it) : shapeMeshes_.erase(it);
  }
  std::erase_if(texts_, [&](const CachedText& c) {
    return std::none_of(scene_.shapes.begin(), scene_.shapes.end(),
                        [&](const DrawShape& s) { return s.text && *s.text == c.text; });
  });
}

Image SceneDrawer::readPixels(int width, int height) {
  Image img;
  img.width = width;
  img.height = height;
  img.rgba.resize(std::size_t(width) * std::size_t(height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.rgba.data());
  flipRows(img.rgba.data(), std::size_t(width) * 4, height);
  return img;
}

std::vector<float> SceneDrawer::readDepth(int width, int height) {
  std::vector<float> depth(std::size_t(width) * std::size_t(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  flipRows(reinterpret_cast<std::uint8_t*>(depth.data()), std::size_t(width) * sizeof(float), height);
  return depth;
}

DrawStats SceneDrawer::stats() const {
  DrawStats s;
  for (std::size_t i = 0; i < meshes_.size(); ++i) {
    const auto& m = meshes_[i];
    const int level = i < drawnLevels_.size() ? drawnLevels_[i] : 0;
    s.triangles += m->triangles(level);
    s.level = std::max(s.level, level);
    s.chunks += m->chunks();
    s.chunkUploads += m->uploads();
  }
  s.caps = capsDrawn_;
  for (const auto& [key, cap] : caps_) s.capTexels += cap->section().texelsSampled();
  return s;
}

// Near and far planes hug what there is to see (scene bounds and tools), so
// that a 24-bit depth buffer resolves a tooth seen from a few centimetres.
void SceneDrawer::aim(int width, int height, const std::vector<ToolView>& tools) {
  glm::dvec3 lo = scene_.boundsMin, hi = scene_.boundsMax;
  bool any = !scene_.volumes.empty() || !scene_.shapes.empty();
  for (const ToolView& t : tools) {
    const double reach = t.geometry.shaftLength + t.geometry.head().boundingRadius();
    const glm::dvec3 a = t.pose.position - reach, b = t.pose.position + reach;
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
  camera_ = makeCamera(view_, width, height, nearDistance, farDistance);
}

void SceneDrawer::drawTool(const ToolView& t) {
  const ClipPlanes none;
  const glm::dmat4 pose =
      glm::translate(glm::dmat4(1.0), t.pose.position) * glm::mat4_cast(glm::normalize(t.pose.orientation));
  // The ghost in wire and over everything: it shows where the hand is even
  // inside the tooth, and never hides the renderer's tool.
  if (t.ghost) {
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDisable(GL_DEPTH_TEST);
  }
  if (t.geometry.round()) {
    program_->setObject(glm::scale(pose, glm::dvec3(t.geometry.tipRadius)), t.ghost ? kGhost : kBurr,
                        t.ghost ? &kGhost.diffuse : &kBurr.diffuse, false, none);
    sphere_->draw();
  } else {
    const BurrHead head = t.geometry.head();
    const glm::vec2 radii(float(head.cuttingEndRadius() / head.radius), float(head.shankEndRadius() / head.radius));
    if (!head_ || radii != headRadii_) {
      std::vector<Vertex> v;
      std::vector<std::uint32_t> idx;
      unitFrustum(v, idx, radii.x, radii.y);
      if (!head_) head_ = std::make_unique<GlMesh>(false);
      head_->upload(v, idx);
      headRadii_ = radii;
    }
    program_->setObject(glm::scale(pose, glm::dvec3(head.radius, head.length, head.radius)), t.ghost ? kGhost : kBurr,
                        t.ghost ? &kGhost.diffuse : &kBurr.diffuse, false, none);
    head_->draw();
  }
  const glm::dmat4 shaft = glm::scale(glm::translate(pose, glm::dvec3(0.0, t.geometry.shaftLength / 2, 0.0)),
                                      glm::dvec3(t.geometry.shaftRadius, t.geometry.shaftLength,
                                                 t.geometry.shaftRadius));
  program_->setObject(shaft, t.ghost ? kGhost : kShaft, t.ghost ? &kGhost.diffuse : &kShaft.diffuse, false, none);
  cylinder_->draw();
  if (t.ghost) {
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glEnable(GL_DEPTH_TEST);
  }
  if (t.hasIntersection && !t.ghost) {
    // As thick as the shaft and drawn over everything: the point is where
    // the shaft enters the tooth, so the tooth would hide it (paper, Fig. 14).
    const double r = std::max(t.geometry.shaftRadius, 0.5 * t.geometry.tipRadius);
    program_->setObject(glm::scale(glm::translate(glm::dmat4(1.0), t.intersection), glm::dvec3(r)), kMarker,
                        &kMarker.diffuse, false, none);
    glDisable(GL_DEPTH_TEST);
    sphere_->draw();
    glEnable(GL_DEPTH_TEST);
  }
}

}  // namespace millsim
