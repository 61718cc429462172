#pragma once
// The voxel side of VolumeObject, in libmillsim. libmillsim_scene (the node
// graph, the loader, every node's table) does not link it or OpenVDB: a
// VolumeObject opens it on its first initialize() through loadVolumeModule(),
// so that `millsim --version` and `millsim nodes` never map OpenVDB (27 MB
// resident). In any process that runs a scene libmillsim is already loaded,
// and opening it again costs a lookup.
// Internal to millsim/volume (listed in cmake/private-headers.txt).
#include <memory>
#include <string>

namespace millsim {

class DiagnosticSink;
class Scene;
class VolumeContents;
class VolumeObject;

// Bumped whenever this table, or a type it passes, changes incompatibly (3:
// DiagnosticSink carries the load's progress listener; 4: VolumeObject.millingBudget).
inline constexpr int kVolumeAbiVersion = 4;

struct VolumeModule {
  int abiVersion;
  // Loads the node's url (the first that loads), checks that it holds
  // material and classifies its tissues; reports to `sink` and sets the
  // node's output fields. Null when no url loaded.
  std::unique_ptr<VolumeContents> (*load)(VolumeObject& node, DiagnosticSink& sink);
  // The whole-scene checks of a lesson that read voxels (a tissue never
  // felt, a target with no material): checkLessonVolumes.
  void (*checkLesson)(const Scene& scene, DiagnosticSink& sink);
};

// Opens libmillsim once per process (MILLSIM_VOLUME_LIBRARY overrides its
// path; by default it is looked for next to libmillsim_scene). Null, with
// `error` saying why, when it cannot.
const VolumeModule* loadVolumeModule(std::string& error);

// The loader itself, defined in libmillsim.
std::unique_ptr<VolumeContents> loadVolumeContents(VolumeObject& node, DiagnosticSink& sink);
// Defined in libmillsim's lesson room (millsim/lesson/LessonVolumeChecks.cpp).
void checkLessonVolumes(const Scene& scene, DiagnosticSink& sink);

}  // namespace millsim
