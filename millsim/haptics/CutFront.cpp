#include "millsim/haptics/CutFront.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "millsim/haptics/HapticScene.h"

namespace millsim {

const glm::dvec3& CutFront::step(const HapticScene& scene, const FeedLaw& law, const glm::dvec3& burr,
                                 const glm::dvec3& target, bool touching, bool milling, double force, double dt) {
  hardness_ = 1.0;
  // Out of contact for a frame or more the centre is the burr. Not in the
  // first frame: #3's coupled tool lost all its contacts for one frame after
  // a stamp in the §8.2 replay, stepped a penalty depth further in, and the
  // centre jumping there cut 0.035 mm³ at once (a quarter of a second's
  // milling) and dropped the force 0.18 N.
  const bool wasTouching = touching_;
  touching_ = touching;
  if (!touching && !wasTouching) {
    centre_ = burr;
    return centre_;
  }
  if (!touching || !milling) return centre_;
  const glm::dvec3 toTarget = target - centre_;
  const double gap = glm::length(toTarget);
  if (!(gap > 0.0)) return centre_;
  const glm::dvec3 dir = toTarget / gap;
  // The tissue just ahead of the burr's leading point is what gives way.
  const double hardness = scene.hardness(centre_ + dir * (law.tipRadius + 0.5 * scene.voxelSize()));
  hardness_ = hardness;
  if (!(hardness > 0.0)) return centre_;
  const double feed = force / (law.feedResistance * hardness) * dt;
  centre_ += dir * std::min(feed, gap);
  return centre_;
}

}  // namespace millsim
