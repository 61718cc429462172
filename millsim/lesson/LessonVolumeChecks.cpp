// checkLessonVolumes (VolumeModule.h): the checks of a lesson that read its
// voxels, so live in libmillsim with OpenVDB; RegionChecks calls them through
// the volume module once a VolumeObject has loaded.
#include <algorithm>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>

#include "millsim/core/Diagnostics.h"
#include "millsim/core/FieldValues.h"
#include "millsim/core/Progress.h"
#include "millsim/core/Scene.h"
#include "millsim/lesson/ForbiddenRegion.h"
#include "millsim/lesson/MillingTarget.h"
#include "millsim/lesson/RegionAccounting.h"
#include "millsim/volume/Tissue.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VolumeModule.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim {

namespace {

// Three decimals: a report's precision, not a double's.
std::string mm3(double m3) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f mm³", m3 * 1e9);
  return text;
}

// A tissue (mostly) below its volume's isoValue is never felt or cut: fine for
// the pulp a ForbiddenRegion watches or a tissue marked soft, almost always a
// wrong isoValue, range or label otherwise.
void checkSoftTissues(const Scene& scene, DiagnosticSink& sink) {
  std::set<std::string> forbidden;
  for (const ForbiddenRegion* r : scene.nodesOfType<ForbiddenRegion>())
    for (const std::string& name : r->tissues.get()) forbidden.insert(name);
  for (const VolumeObject* v : scene.nodesOfType<VolumeObject>()) {
    const TissueMap* map = v->tissueMap();
    if (!map) continue;
    const auto& tissues = v->tissues.get();
    for (std::size_t i = 0; i < tissues.size() && i + 1 < map->voxelCounts().size(); ++i) {
      const Tissue& t = *tissues[i];
      const std::uint64_t all = map->voxelCounts()[i + 1], below = map->belowSurfaceCounts()[i + 1];
      if (all == 0 || 2 * below <= all || t.soft.get() || forbidden.count(t.name.get())) continue;
      sink.warning(t.location(), "Tissue '" + t.name.get() + "' lies below the VolumeObject's isoValue " +
                                     formatNumber(v->isoValue.get()) + " (" + std::to_string(below) + " of its " +
                                     std::to_string(all) + " voxels): the burr will never feel it, and its hardness does "
                                     "nothing. If it is a soft tissue (pulp, a canal), say soft='true' or name it "
                                     "in a ForbiddenRegion; else lower isoValue or choose its voxels again");
    }
  }
}

// Each target's material at the start: a target with none can only score 0
// (placed in metres in a millimetre file, or outside the tooth).
void checkTargets(const Scene& scene, DiagnosticSink& sink) {
  std::vector<RegionResult> start;
  try {
    const ProgressStep step(sink.progress(), "lesson regions: measuring their material at the start");
    start = RegionAccounting::atStart(scene);
  } catch (const std::exception&) {  // an unknown tissue: said above
    return;
  }
  const std::vector<MillingTarget*> targets = scene.nodesOfType<MillingTarget>();
  for (const RegionResult& r : start) {
    if (r.forbidden) continue;
    const auto at = std::find_if(targets.begin(), targets.end(), [&](const MillingTarget* t) { return t->name.get() == r.name; });
    if (at == targets.end()) continue;
    const MillingTarget& node = **at;
    if (r.initial <= 0.0) {
      sink.warning(node.location(), "MillingTarget '" + r.name +
                                        "' holds no material at the start (0 mm³): its shapes lie where no "
                                        "VolumeObject has material, so it can only score 0. Lengths are metres "
                                        "unless a <unit> statement says otherwise (1.4 mm is 0.0014)");
      continue;
    }
    sink.note(node.location(), "MillingTarget '" + r.name + "' holds " + mm3(r.initial) + " of material at the start");
    if (r.initialForbidden > 0.0)
      sink.warning(node.location(), "MillingTarget '" + r.name + "' overlaps a forbidden region: " +
                                        mm3(r.initialForbidden) + " of its " + mm3(r.initial) +
                                        " is forbidden, so completing it violates the lesson");
  }
}

}  // namespace

void checkLessonVolumes(const Scene& scene, DiagnosticSink& sink) {
  checkSoftTissues(scene, sink);
  checkTargets(scene, sink);
}

}  // namespace millsim
