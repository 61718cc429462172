#include "millsim/volume/PlacedVolumes.h"

#include "millsim/std/SceneWalk.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim {

std::vector<PlacedVolume> placedVolumes(const Scene& scene) {
  std::vector<PlacedVolume> out;
  walkScene(scene, [&](Node& n, const WalkFrame& at) {
    if (auto* vo = dynamic_cast<VolumeObject*>(&n); vo && vo->volume())
      out.push_back({vo, at.localToWorld, *at.clipPlanes});
  });
  return out;
}

}  // namespace millsim
