#pragma once
// The scene's loaded VolumeObjects where they sit, in walk order: the one list
// that both the haptic scene (VoxelScene) and graphics (readSceneView) take
// their volumes from, so volume i is the same volume on both sides.
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

namespace millsim {

class Scene;
class VolumeObject;

struct PlacedVolume {
  VolumeObject* node;
  glm::dmat4 localToWorld;
  std::vector<glm::dvec4> clipPlanes;  // world space, as WalkFrame gives them
};

// Only VolumeObjects whose volume loaded.
std::vector<PlacedVolume> placedVolumes(const Scene& scene);

}  // namespace millsim
