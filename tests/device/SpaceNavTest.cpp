// The 3D mouse through the real libspnav against MillSim's fake spacenavd
// (tests/emulators/spacenav), run by tests/scripts/with_fake_spacenavd.sh with
// data/devices/spacenav/twist.csv: H3DAPI's SpaceWareSensor turns the puck's
// push, twist and buttons into X3D events at the event clock's ticks, and a
// route carries them into the scene.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "SceneText.h"
#include "millsim/devices/SpaceWareSensor.h"
#include "millsim/std/EventClock.h"
#include "millsim/std/Transform.h"

using namespace millsim;
using namespace millsim::test;

TEST(SpaceWareSensor, SendsThePucksPushTwistAndButtonsThroughARoute) {
  LoadResult r = load(x3dScene(R"(
    <SpaceWareSensor DEF="Puck" translationScale="0.02" accumulateTimeDependent="true"/>
    <Transform DEF="Moved"><Shape><Sphere radius="0.01"/></Shape></Transform>
    <ROUTE fromNode="Puck" fromField="accumulatedTranslation" toNode="Moved" toField="set_translation"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  SpaceWareSensor& puck = onlyNode<SpaceWareSensor>(r);
  Transform& moved = onlyNode<Transform>(r);
  EventClock clock(*r.scene);
  int pressesSeen = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int tick = 0; tick < 40; ++tick) {  // 0.8 s of 20 ms ticks, in real time: the daemon plays its script
    clock.tick(tick * kEventTickSeconds);
    if (puck.latestButtonPress.get() == 1 && puck.buttons.get() == 2) ++pressesSeen;
    std::this_thread::sleep_until(start + std::chrono::milliseconds(20 * (tick + 1)));
  }
  EXPECT_TRUE(puck.isActive.get()) << "connected to the (fake) spacenavd";
  EXPECT_FLOAT_EQ(puck.rawTranslation.get().x, 0.5f) << "175 of 350: half a push to the right";
  EXPECT_FLOAT_EQ(puck.instantTranslation.get().x, 0.01f) << "times translationScale";
  EXPECT_NEAR(puck.rawRotation.get().angle, 1.0f, 1e-6f) << "a full twist";
  EXPECT_NEAR(puck.rawRotation.get().axis.y, 1.0f, 1e-6f) << "about y (spacenavd's y is X3D's)";
  EXPECT_GT(pressesSeen, 0) << "button 1 went down (bit 1 of buttons)";
  EXPECT_EQ(puck.latestButtonRelease.get(), 1) << "and came up";
  EXPECT_EQ(puck.buttons.get(), 0);
  // Held for about 0.75 s at 0.01 m/s: some 7 mm to the right, through the route.
  EXPECT_GT(moved.translation.get().x, 0.004f);
  EXPECT_LT(moved.translation.get().x, 0.010f);
  EXPECT_GT(puck.accumulatedRotation.get().angle, 0.4f) << "the twist accumulates too";
}

// Run with no daemon listening (ctest spacenav:sensor-without-daemon).
TEST(SpaceWareSensor, IsInactiveWithoutTheDaemon) {
  LoadResult r = load(x3dScene(R"(<SpaceWareSensor DEF="Puck"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  EventClock clock(*r.scene);
  clock.tick(0.0);
  clock.tick(0.02);
  EXPECT_FALSE(onlyNode<SpaceWareSensor>(r).isActive.get()) << "no daemon: inactive, and no error";
}
