#pragma once
// SpaceWareSensor: H3DAPI's sensor for a 3Dconnexion 3D mouse, here through
// spacenavd and libspnav (millsim/driver/SpaceNav.h): the puck's deflection
// and buttons as X3D events, at each tick of the scene's event clock, for a
// scene to route where it likes (a Transform, a Viewpoint). Fields as
// H3DAPI names them: raw* are the deflection as a fraction of full scale in
// X3D's frame (H3DAPI gives the driver's own units), instant* are raw times
// the scale, accumulated* their sum (per second when
// accumulateTimeDependent). H3DAPI's separate yaw/pitch/roll fields and its
// reset fields are not provided. The sensor connects when the scene first
// ticks (isActive says whether it is), and tries again each second while
// spacenavd cannot be reached; it is live input, not part of a replay.
#include <chrono>
#include <cstdint>
#include <memory>

#include "millsim/std/EventNode.h"

namespace millsim {

class SpaceNav;

class SpaceWareSensor : public EventNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  SFBool enabled{this, "enabled", Access::InputOutput, true, "Whether the sensor reads the 3D mouse."};
  SFBool isActive{this, "isActive", Access::OutputOnly, false, "TRUE while connected to spacenavd."};
  SFVec3f rawTranslation{this, "rawTranslation", Access::OutputOnly, glm::vec3(0.f),
                         "The puck's push, each axis a fraction of full deflection in [-1, 1] (X3D's frame)."};
  SFRotation rawRotation{this, "rawRotation", Access::OutputOnly, Rotation{},
                         "The puck's twist: its axis, and as angle its size as a fraction of full twist."};
  SFFloat translationScale{this, "translationScale", Access::InputOutput, 1.f,
                           "instantTranslation = rawTranslation × this.", Range::closed(-1e6, 1e6)};
  SFFloat rotationScale{this, "rotationScale", Access::InputOutput, 1.f,
                        "instantRotation's angle = rawRotation's × this (radians).",
                        Range::closed(-1e3, 1e3).in(quantity::angle)};
  SFVec3f instantTranslation{this, "instantTranslation", Access::OutputOnly, glm::vec3(0.f),
                             "rawTranslation × translationScale."};
  SFRotation instantRotation{this, "instantRotation", Access::OutputOnly, Rotation{},
                             "rawRotation with its angle × rotationScale."};
  SFBool accumulateTimeDependent{this, "accumulateTimeDependent", Access::InputOutput, true,
                                 "TRUE: the accumulated fields add instant values per second of the scene's "
                                 "clock; FALSE: per tick."};
  SFVec3f accumulatedTranslation{this, "accumulatedTranslation", Access::OutputOnly, glm::vec3(0.f),
                                 "The sum of instantTranslation since the sensor connected."};
  SFRotation accumulatedRotation{this, "accumulatedRotation", Access::OutputOnly, Rotation{},
                                 "instantRotation composed since the sensor connected."};
  SFInt32 buttons{this, "buttons", Access::OutputOnly, 0, "The buttons down, as bits (bit 0: button 0)."};
  SFInt32 latestButtonPress{this, "latestButtonPress", Access::OutputOnly, 0, "The button last pressed."};
  SFInt32 latestButtonRelease{this, "latestButtonRelease", Access::OutputOnly, 0, "The button last released."};

  bool processEvents() override;
  bool hasPendingEvent() const override;
  void dropPending() override {}

private:
  using Clock = std::chrono::steady_clock;
  std::shared_ptr<SpaceNav> nav_;
  Clock::time_point nextTry_{}, lastUpdate_{};
  std::uint64_t seenEvents_ = 0;
  int seenPress_ = -1, seenRelease_ = -1;
  glm::quat accumulated_{1.f, 0.f, 0.f, 0.f};
};

}  // namespace millsim
