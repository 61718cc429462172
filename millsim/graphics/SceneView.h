#pragma once
// SceneView: what graphics draws from a Scene, read once on the scene thread
// and free of OpenGL — the bound Viewpoint, the Background colour, the lights,
// every Shape (Sphere, Cylinder, Box, Cone, IndexedFaceSet,
// IndexedTriangleSet, Text, with its Material and ImageTexture) and every
// VolumeObject with its accumulated transform and the ClipPlanes that apply
// to it. Also the
// camera maths (view, projection, projecting a world point to a pixel), which
// the scene tests use to know where things must appear.
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace millsim {

class TissueMap;

class Node;
class Scene;
class VoxelVolume;
struct TriangleMesh;

// An X3D viewpoint in the world frame: the camera looks along its local −Z, +Y up.
struct ViewSpec {
  glm::dvec3 position{0.0, 0.0, 10.0};
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};
  double fieldOfView = 0.7853981633974483;  // the smaller of the horizontal and vertical angles (radians)
};

struct Camera {
  glm::dmat4 view{1.0}, projection{1.0};
  int width = 0, height = 0;
  // Pixel x from the left, y from the top (pixel centres at +0.5), and depth
  // in [0, 1] as the depth buffer stores it; z < 0 or > 1 means clipped.
  glm::dvec3 project(const glm::dvec3& world) const;
  glm::dvec3 eye() const;
};
// near/far: distances of the depth range (m).
Camera makeCamera(const ViewSpec& view, int width, int height, double nearDistance, double farDistance);

struct DrawMaterial {
  glm::vec3 diffuse{0.8f}, specular{0.f}, emissive{0.f};
  float ambient = 0.2f, shininess = 0.2f;  // X3D's [0, 1] shininess
  float transparency = 0.f;                 // X3D's: 0 opaque, 1 invisible
};

// How transparent a shape under a visible assessment region is drawn at least:
// the region shows where it is without hiding the tooth inside it.
inline constexpr float kRegionTransparency = 0.65f;

// World-space planes (a, b, c, d), unit normal: a point p stays when dot(plane, (p, 1)) >= 0.
using ClipPlanes = std::vector<glm::dvec4>;

// A plane that cuts the drawing (never the haptics): one per distinct world
// plane of the scene's ClipPlanes, plus the user's own (SceneView::addUserCut).
struct CutPlane {
  glm::dvec4 plane;      // as ClipPlanes: unit normal, keeps dot(plane, (p, 1)) >= 0
  bool enabled = true;
  std::string name;      // "ClipPlane 'DEF'" or "ClipPlane 1"; "user cut"
  bool user = false;     // the user's plane cuts every volume (not the Shapes)
};

// A Text's lines and how to set them (FontStyle's fields, defaults when it has none).
struct DrawText {
  std::vector<std::string> lines;
  std::vector<float> lengths;  // Text.length: a line's width when > 0 (local units)
  float maxExtent = 0.f;
  std::vector<std::string> family{"SERIF"};
  std::string style = "PLAIN";
  float size = 1.f, spacing = 1.f;
  std::string justifyMajor = "BEGIN", justifyMinor = "FIRST";
  bool topToBottom = true;
  bool operator==(const DrawText&) const = default;
};

// An ImageTexture: the file found at load (empty: none) and its wrapping.
struct DrawTexture {
  std::string file;
  bool repeatS = true, repeatT = true;
};

struct DrawShape {
  enum class Kind { Sphere, Cylinder, Box, Mesh, Text } kind = Kind::Sphere;
  // Sphere, Cylinder, Box: unit primitive (radius 1 / height 1 / edge 1,
  // centred) to world; Mesh (the mesh's own units), Text: local to world.
  glm::dmat4 model{1.0};
  DrawMaterial material;
  ClipPlanes clipPlanes;  // as authored (world)
  std::vector<int> cuts;  // the same planes as indices into SceneView::cutPlanes
  // An assessment region's shape: drawn see-through over everything, even
  // where the tooth hides it (a target inside the crown shows where to cut).
  bool overlay = false;
  std::shared_ptr<const TriangleMesh> mesh;  // Kind::Mesh (also a textured primitive)
  std::shared_ptr<const DrawText> text;      // Kind::Text
  DrawTexture texture;
  std::uint32_t lights = ~0u;  // bit i: SceneView::lights[i] lights it (X3D's light scoping)
};

// A light in the world frame (X3D's DirectionalLight, PointLight, SpotLight).
struct DrawLight {
  enum class Kind { Directional, Point, Spot } kind = Kind::Directional;
  glm::vec3 colour{1.f};          // color × intensity
  glm::vec3 ambient{0.f};         // color × ambientIntensity
  glm::dvec3 position{0.0};       // Point, Spot
  glm::dvec3 direction{0.0, 0.0, -1.0};  // where the light travels (unit), Directional, Spot
  glm::vec3 attenuation{1.f, 0.f, 0.f};
  double radius = 100.0;          // world units
  float beamWidth = 0.785398f, cutOffAngle = 1.570796f;
  // False for a light with global FALSE: it lights only the nodes whose
  // DrawShape/DrawVolume::lights has its bit (its siblings' subtrees).
  bool global = true;
};

struct DrawVolume {
  const VoxelVolume* voxels;
  glm::dmat4 localToWorld;
  double iso;
  ClipPlanes clipPlanes;
  std::vector<int> cuts;
  const TissueMap* tissues = nullptr;  // colours the surface by tissue when the volume has them
  std::uint32_t lights = ~0u;          // as DrawShape::lights
};

// A Viewpoint to cycle through (Page Up / Page Down in the window).
struct NamedView {
  std::string name;  // its description, else its DEF name, else "Viewpoint N"
  ViewSpec view;
  glm::dvec3 centerOfRotation{0.0};  // world; EXAMINE turns about it when it is set
  bool hasCenterOfRotation = false;  // the field is not (0, 0, 0)
};

struct SceneView {
  // The first Viewpoint (or the one asked for); without any, the whole scene
  // framed from +Z (frameBounds), since X3D's default viewpoint 10 m away
  // sees a millimetre tooth as a dot.
  ViewSpec view;
  bool framed = false;                  // true when `view` was framed, not read
  std::vector<NamedView> viewpoints;    // every Viewpoint, in file order
  std::string navigation = "EXAMINE";   // the first NavigationInfo's first type
  glm::vec3 background{0.f};            // the first Background's first skyColor
  bool headlight = true;                // the first NavigationInfo's headlight
  std::vector<DrawLight> lights;        // every light that is on, in file order
  std::vector<DrawShape> shapes;
  std::vector<DrawVolume> volumes;      // loaded VolumeObjects, in placedVolumes() order (as VoxelScene)
  std::vector<CutPlane> cutPlanes;
  glm::dvec3 boundsMin{0.0}, boundsMax{0.0};  // of shapes and volumes (world); equal if none

  bool hasBounds() const { return boundsMax != boundsMin; }
  glm::dvec3 centre() const { return 0.5 * (boundsMin + boundsMax); }
  // Adds (once) a plane through the scene's centre facing `towards` that
  // cuts every volume, disabled; returns its index in cutPlanes.
  int addUserCut(const glm::dvec3& towards);
};

// Meshes built from mesh geometry, kept between reads of the same scene so
// that an animation re-reading the view 50 times a second does not
// re-triangulate an unchanged jaw. Rebuilt when a field of the geometry or
// of its vertex data nodes has a newer event. Belongs to one Scene.
class ShapeMeshCache {
public:
  std::shared_ptr<const TriangleMesh> meshOf(const Node& geometry);

private:
  struct Entry {
    std::uint64_t version = 0;
    std::shared_ptr<const TriangleMesh> mesh;
  };
  std::unordered_map<const Node*, Entry> entries_;
};

// `viewpoint`: the Viewpoint to look through; null takes the first in the
// file. `meshes`: a cache for repeated reads (null: meshes are built anew).
SceneView readSceneView(const Scene& scene, const Node* viewpoint = nullptr, ShapeMeshCache* meshes = nullptr);

// A view along `orientation` (looking down its −Z) from far enough that the
// sphere around [lo, hi] fills the smaller image side with a small margin.
ViewSpec frameBounds(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dquat& orientation,
                     double fieldOfView = 0.7853981633974483);

// Clip planes beyond this many per object are ignored (GL guarantees 8 clip distances).
inline constexpr int kMaxClipPlanes = 6;
// Lights beyond this many are ignored (the shader's arrays).
inline constexpr int kMaxLights = 8;

}  // namespace millsim
