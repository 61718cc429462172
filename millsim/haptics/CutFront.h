#pragma once
// CutFront: where the burr cuts, for renderers that do not keep the burr on
// the surface — #2 draws it at the device, deep in material; #3's coupled
// tool rests a penalty depth inside, and cutting there would let the surface
// recede by that depth every frame, whatever the force. Out of contact the
// cut centre is the burr; in contact, while milling, it advances from where
// it was towards a target (the device) at the feed speed
// |F| / (feedResistance · hardness), with the hardness of the tissue at its
// leading point. So material gives way at the rate the hand's force and the
// tissue set, in every renderer (docs/algorithms.md, "Tissue hardness").
#include <glm/vec3.hpp>

namespace millsim {

class HapticScene;

struct FeedLaw {
  double feedResistance = 200.0;  // N·s/m: the feed speed at hardness 1 is |F| / feedResistance
  double tipRadius = 1e-3;        // m: the leading point is this far ahead of the cut centre
};

class CutFront {
public:
  void reset(const glm::dvec3& at) { centre_ = at, touching_ = false; }
  const glm::dvec3& centre() const { return centre_; }
  // The hardness the last step met (1 when it did not cut).
  double hardness() const { return hardness_; }

  // One frame: `burr` is where the burr is (drawn), `target` where the hand
  // wants it; `force` the magnitude felt (N).
  const glm::dvec3& step(const HapticScene& scene, const FeedLaw& law, const glm::dvec3& burr, const glm::dvec3& target,
                         bool touching, bool milling, double force, double dt);

private:
  glm::dvec3 centre_{0.0};
  double hardness_ = 1.0;
  bool touching_ = false;  // the last step's
};

}  // namespace millsim
