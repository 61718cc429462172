#pragma once
// SceneView: what graphics draws from a Scene, read once on the scene thread
// and free of OpenGL — the bound Viewpoint, the Background colour, every
// Shape (Sphere, Cylinder, Box with its Material) and every VolumeObject with
// its accumulated transform and the ClipPlanes that apply to it. Also the
// camera maths (view, projection, projecting a world point to a pixel), which
// the scene tests use to know where things must appear.
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace millsim {

class Node;
class Scene;
class VoxelVolume;

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
};

// World-space planes (a, b, c, d), unit normal: a point p stays when dot(plane, (p, 1)) >= 0.
using ClipPlanes = std::vector<glm::dvec4>;

struct DrawShape {
  enum class Kind { Sphere, Cylinder, Box } kind;
  glm::dmat4 model;  // unit primitive (radius 1 / height 1 / edge 1, centred) to world
  DrawMaterial material;
  ClipPlanes clipPlanes;
};

struct DrawVolume {
  const VoxelVolume* voxels;
  glm::dmat4 localToWorld;
  double iso;
  ClipPlanes clipPlanes;
};

struct SceneView {
  ViewSpec view;                        // the first Viewpoint, or X3D's default
  glm::vec3 background{0.f};            // the first Background's first skyColor
  std::vector<DrawShape> shapes;
  std::vector<DrawVolume> volumes;      // loaded VolumeObjects, in placedVolumes() order (as VoxelScene)
  glm::dvec3 boundsMin{0.0}, boundsMax{0.0};  // of shapes and volumes (world); equal if none
};

// `viewpoint`: the Viewpoint to look through; null takes the first in the file.
SceneView readSceneView(const Scene& scene, const Node* viewpoint = nullptr);

// Clip planes beyond this many per object are ignored (GL guarantees 8 clip distances).
inline constexpr int kMaxClipPlanes = 6;

}  // namespace millsim
