#pragma once
// The fields graphics draws from, watched (FieldWatch) by the scene thread of
// a run, which reads a new SceneView only when one of them had an event:
// every field of the Transforms and MatrixTransforms, Switches, Materials,
// ClipPlanes, Backgrounds, NavigationInfos, lights, Texts and FontStyles, and
// of mesh vertex data (Coordinate, Normal, Color, TextureCoordinate), set by
// a route, an event or a key. Primitive sizes are initializeOnly; volumes are
// placed once per run.
#include "millsim/core/FieldWatch.h"

namespace millsim {

class Scene;

// The scene's nodes are fixed for a run: they are listed once. Starts marked.
FieldWatch drawnFields(const Scene& scene);

}  // namespace millsim
