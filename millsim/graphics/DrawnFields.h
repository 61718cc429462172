#pragma once
// DrawnFields: has a field that graphics draws from changed since the last
// SceneView was read? The scene thread of `millsim run` asks after each event
// tick and publishes a new view only then. Watched: every field of the
// Transforms and MatrixTransforms, Switches, Materials, ClipPlanes, Backgrounds, NavigationInfos,
// lights, Texts and FontStyles, and of mesh vertex data (Coordinate, Normal,
// Color, TextureCoordinate), set by a route, an event or a key. Primitive
// sizes are initializeOnly; volumes are placed once per run.
#include <cstdint>
#include <vector>

namespace millsim {

class Field;
class Scene;

class DrawnFields {
public:
  // The scene's nodes are fixed for a run: they are listed once. Starts marked.
  explicit DrawnFields(const Scene& scene);
  bool changed() const;
  // After reading a view: brings every watched field up to date and remembers its newest event.
  void mark();
  bool empty() const { return fields_.empty(); }

private:
  std::vector<Field*> fields_;
  std::uint64_t newest_ = 0;
};

}  // namespace millsim
