#include "millsim/lesson/RegionChecks.h"

#include <set>
#include <string>

#include "millsim/core/Diagnostics.h"
#include "millsim/core/Scene.h"
#include "millsim/lesson/AssessmentRegion.h"
#include "millsim/volume/Tissue.h"
#include "millsim/volume/VolumeModule.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim {

void checkRegions(const Scene& scene, DiagnosticSink& sink) {
  std::set<std::string> tissues;
  for (const VolumeObject* v : scene.nodesOfType<VolumeObject>())
    for (const auto& t : v->tissues.get()) tissues.insert(t->name.get());
  for (const AssessmentRegion* r : scene.nodesOfType<AssessmentRegion>())
    for (const std::string& name : r->tissues.get())
      if (!tissues.count(name)) {
        std::string known;
        for (const std::string& t : tissues) known += (known.empty() ? "" : ", ") + ("'" + t + "'");
        sink.error(r->location(), r->typeName() + " '" + r->name.get() + "' names tissue '" + name +
                                      "', which no VolumeObject has (its tissues: " +
                                      (known.empty() ? std::string("none") : known) + ")");
      }
  // What needs the voxels (libmillsim), once a volume has loaded them.
  bool loaded = false;
  for (const VolumeObject* v : scene.nodesOfType<VolumeObject>()) loaded |= v->volume() != nullptr;
  std::string error;
  if (const VolumeModule* module = loaded ? loadVolumeModule(error) : nullptr) module->checkLesson(scene, sink);
}

}  // namespace millsim
