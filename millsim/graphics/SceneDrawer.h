#pragma once
// SceneDrawer: the one OpenGL drawing of a MillSim scene, into whatever 3.3
// core context is current — OSMesa's offscreen buffer (GlSceneRenderer) or the
// window's (millsim/window). Both link the same object code, so the test
// harness's screenshots and the window show the same frame.
//
// It draws each volume's iso-surface (re-meshed incrementally as it is
// milled), the standard Shapes, the tool at its drawn pose, optionally the
// device's own pose as a ghost, and Algorithm #1's intersection point, seen
// through a ViewSpec, cut by the cut planes (the scene's ClipPlanes and a
// user plane), which cut the drawing only. Where a plane cuts a volume the
// cut is capped by the section (CutSection): each tissue in its colour, soft
// tissue (the pulp) too, so the walls' thickness can be read off it.
//
// Threads: create, call and destroy it on the thread whose context is current.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/vec2.hpp>

#include "millsim/graphics/Image.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/haptics/MillTool.h"
#include "millsim/math/Pose.h"
#include "millsim/volume/DirtyBlocks.h"

namespace millsim {

class CutCap;
class FontAtlas;
class GlMesh;
class ShadedProgram;
class VolumeMesh;
class VoxelVolume;

// What to draw of the tool: burr head (a sphere, or the shape's head centred
// on pose.position: millsim/haptics/BurrHead.h) at pose.position, shaft along the
// pose's +Y, and the red intersection marker if there is one (drawn over
// everything, since it lies where the shaft enters the tooth).
struct ToolView {
  ToolGeometry geometry;
  Pose pose;
  bool hasIntersection = false;
  glm::dvec3 intersection{0.0};
  // Drawn translucent and without the marker: the device's pose next to the
  // renderer's (a MouseDevice has no force output, so the hand sees the gap).
  bool ghost = false;
};

struct DrawStats {
  std::size_t triangles = 0;     // of all volume meshes, at the level each was last drawn (none before a draw)
  int level = 0;                 // the coarsest level of detail a volume was last drawn at
  std::size_t chunks = 0;        // chunk meshes on the GPU, every level made
  std::size_t chunkUploads = 0;  // since construction (an incremental update adds only the chunks it touched)
  std::size_t caps = 0;          // cut caps drawn in the latest draw()
  std::uint64_t capTexels = 0;   // section texels sampled since construction (a moved plane samples its whole section)
};

class SceneDrawer {
public:
  // Takes every volume of `scene`; a volume is meshed at the level of detail it is first drawn at.
  explicit SceneDrawer(SceneView scene);
  ~SceneDrawer();
  SceneDrawer(const SceneDrawer&) = delete;
  SceneDrawer& operator=(const SceneDrawer&) = delete;

  const SceneView& scene() const { return scene_; }

  std::size_t addVolume(const VoxelVolume& voxels, const glm::dmat4& localToWorld, double iso);
  std::size_t volumeCount() const;
  void volumeChanged(std::size_t index, const std::vector<BlockOrigin>& blocks);
  void rebuildVolume(std::size_t index);

  void setView(const ViewSpec& view) { view_ = view; }
  const ViewSpec& view() const { return view_; }
  // The camera of the latest draw() or aim() (near and far follow the scene and tools).
  const Camera& camera() const { return camera_; }
  // Sets camera() for an image of width × height without drawing.
  void aim(int width, int height, const std::vector<ToolView>& tools = {});

  // The cut planes, scene ClipPlanes first (SceneView::cutPlanes), may be
  // moved, turned and switched off; they cut the drawing only.
  std::vector<CutPlane>& cutPlanes() { return scene_.cutPlanes; }
  // The scene's ClipPlanes changed while running (a route set a plane or
  // enabled): takes `fresh`'s cut planes and which objects each cuts, keeping
  // the user's own plane. False (and nothing changed) if `fresh` has other
  // volumes or shapes than this drawer.
  bool adoptCuts(const SceneView& fresh);
  // The scene changed while running (an event moved a Transform, chose
  // another Switch child, changed a Material, a light or a ClipPlane): takes
  // `fresh`'s shapes, background, lights and cut planes (as adoptCuts). Volumes stay where they
  // were meshed (placement is fixed for a run). False (and nothing changed)
  // if `fresh` has another number of volumes.
  bool adoptView(const SceneView& fresh);
  // False: volumes are always drawn from their every-voxel mesh.
  void setLevelOfDetail(bool on) { levelOfDetail_ = on; }
  // False: a cut shows the volume's inside surface, uncapped (X3D's plain ClipPlane).
  void setCapCuts(bool on) { capCuts_ = on; }
  bool capCuts() const { return capCuts_; }
  // SceneView::addUserCut: the user's own plane, facing `towards`.
  int addUserCut(const glm::dvec3& towards) { return scene_.addUserCut(towards); }

  // Draws one frame into the current framebuffer of width × height pixels.
  void draw(int width, int height, const std::vector<ToolView>& tools);
  // The current framebuffer: colour (rows from the top) and depth in [0, 1].
  static Image readPixels(int width, int height);
  static std::vector<float> readDepth(int width, int height);

  DrawStats stats() const;

private:
  VolumeMesh& mesh(std::size_t index);
  void drawTool(const ToolView& t);
  void drawShape(const DrawShape& s);
  // VolumeMesh's level of detail for volume i in an image `height` pixels high:
  // the finest whose voxel covers kCoarseBelowPixels.
  int levelOfDetail(std::size_t i, int height) const;
  // Where a voxel covers fewer pixels than this, a coarser level is drawn.
  static constexpr double kCoarseBelowPixels = 1.5;
  // The GPU copy of a mesh shape or a Text's glyph quads, made on first use.
  GlMesh& meshFor(const std::shared_ptr<const TriangleMesh>& mesh);
  GlMesh* textFor(const DrawText& text, FontAtlas*& font);
  // The texture of an image file bound to unit 0; false if it could not be read (said once on stderr).
  bool bindTexture(const DrawTexture& texture, bool& grey);
  // Forgets GPU meshes of shapes and texts no longer in the scene.
  void dropUnused();
  ClipPlanes planesFor(const std::vector<int>& cutIndices, bool volume) const;
  // Caps volume i where each of its enabled planes cuts it, clipped by its other planes.
  void drawCaps(std::size_t i);

  SceneView scene_;
  ViewSpec view_;
  Camera camera_;
  std::unique_ptr<ShadedProgram> program_;
  std::unique_ptr<GlMesh> sphere_, cylinder_, box_;
  // A non-round burr head as a unit frustum (radii relative to tipRadius),
  // uploaded again only when the head's proportions change.
  std::unique_ptr<GlMesh> head_;
  glm::vec2 headRadii_{-1.f};
  std::vector<std::unique_ptr<VolumeMesh>> meshes_;
  std::vector<int> drawnLevels_;  // the level of detail each mesh was last drawn at
  bool levelOfDetail_ = true;
  bool capCuts_ = true;
  // (volume, cut plane index) → its cap, made on first draw and kept while the plane is there.
  std::map<std::pair<std::size_t, int>, std::unique_ptr<CutCap>> caps_;
  std::size_t capsDrawn_ = 0;
  struct CachedMesh {
    std::shared_ptr<const TriangleMesh> source;  // keeps the key alive
    std::unique_ptr<GlMesh> gl;
  };
  std::unordered_map<const TriangleMesh*, CachedMesh> shapeMeshes_;
  struct CachedText {
    DrawText text;
    FontAtlas* font = nullptr;
    std::unique_ptr<GlMesh> gl;
  };
  std::vector<CachedText> texts_;
  // (family, style) → its atlas; null when no font was found (said once).
  std::map<std::pair<std::string, std::string>, std::unique_ptr<FontAtlas>> fonts_;
  struct CachedTexture {
    unsigned id = 0;  // 0: the file could not be read
    bool grey = false;
  };
  std::map<std::string, CachedTexture> textures_;
};

}  // namespace millsim
