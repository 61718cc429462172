// The event cascade (millsim/std/EventClock.h): TimeSensors drive
// interpolators and, through routes, Transforms, in simulated time; a
// KeySensor toggles a Switch through a chain of type-correct routes; route
// cycles end with each node sending once per timestamp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/gtc/quaternion.hpp>

#include "SceneText.h"
#include "millsim/graphics/DrawnFields.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/std/ColorInterpolator.h"
#include "millsim/std/EventClock.h"
#include "millsim/std/KeySensor.h"
#include "millsim/std/Material.h"
#include "millsim/std/MatrixTransform.h"
#include "millsim/std/OrientationInterpolator.h"
#include "millsim/std/ScalarInterpolator.h"
#include "millsim/std/Switch.h"
#include "millsim/std/TimeSensor.h"
#include "millsim/std/Transform.h"

using namespace millsim;
using namespace millsim::test;

namespace {

std::string mover(bool loop) {
  return x3dScene(R"(
    <Transform DEF="Mover"><Shape><Sphere radius="0.01"/></Shape></Transform>
    <TimeSensor DEF="Clock" cycleInterval="2" loop=")" + std::string(loop ? "true" : "false") + R"("/>
    <PositionInterpolator DEF="Path" key="0 0.5 1" keyValue="0 0 0, 1 0 0, 1 2 0"/>
    <ROUTE fromNode="Clock" fromField="fraction_changed" toNode="Path" toField="set_fraction"/>
    <ROUTE fromNode="Path" fromField="value_changed" toNode="Mover" toField="set_translation"/>)");
}

void expectAt(const Transform& t, glm::vec3 v, const char* when) {
  const glm::vec3 p = t.translation.get();
  EXPECT_NEAR(p.x, v.x, 1e-5) << when;
  EXPECT_NEAR(p.y, v.y, 1e-5) << when;
  EXPECT_NEAR(p.z, v.z, 1e-5) << when;
}

TEST(EventCascade, TimeSensorMovesATransformOnceThroughItsPath) {
  LoadResult r = load(mover(false));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& t = defNode<Transform>(r, "Mover");
  auto& clock = defNode<TimeSensor>(r, "Clock");
  EventClock events(*r.scene);
  events.advanceTo(0.5);  // fraction 0.25: halfway to the second key
  expectAt(t, {0.5f, 0.f, 0.f}, "t = 0.5 s");
  EXPECT_TRUE(clock.isActive.get());
  events.advanceTo(1.5);  // fraction 0.75
  expectAt(t, {1.f, 1.f, 0.f}, "t = 1.5 s");
  events.advanceTo(3.0);  // one cycle only: it ended at 2 s on the last key
  expectAt(t, {1.f, 2.f, 0.f}, "t = 3 s");
  EXPECT_FLOAT_EQ(clock.fraction_changed.get(), 1.f);
  EXPECT_FALSE(clock.isActive.get());
  EXPECT_DOUBLE_EQ(clock.time.get().seconds, 2.0) << "the last tick of the cycle is at its end";
}

TEST(EventCascade, LoopingTimeSensorStartsTheCycleAgain) {
  LoadResult r = load(mover(true));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& t = defNode<Transform>(r, "Mover");
  auto& clock = defNode<TimeSensor>(r, "Clock");
  EventClock events(*r.scene);
  events.advanceTo(1.5);
  expectAt(t, {1.f, 1.f, 0.f}, "t = 1.5 s");
  events.advanceTo(2.5);  // second cycle, fraction 0.25
  expectAt(t, {0.5f, 0.f, 0.f}, "t = 2.5 s");
  EXPECT_DOUBLE_EQ(clock.cycleTime.get().seconds, 2.0);
  EXPECT_NEAR(clock.elapsedTime.get().seconds, 2.5, 1e-9);
  events.advanceTo(4.0);  // the end of a cycle is fraction 1, not 0
  expectAt(t, {1.f, 2.f, 0.f}, "t = 4 s");
  EXPECT_TRUE(clock.isActive.get());
}

TEST(EventCascade, PausedTimeDoesNotCountAndStopTimeEnds) {
  LoadResult r = load(x3dScene(R"(
    <TimeSensor DEF="Clock" cycleInterval="10" pauseTime="1" resumeTime="3" stopTime="6"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& clock = defNode<TimeSensor>(r, "Clock");
  EventClock events(*r.scene);
  events.advanceTo(2.0);
  EXPECT_TRUE(clock.isPaused.get());
  EXPECT_NEAR(clock.elapsedTime.get().seconds, 1.0, 0.021) << "the last tick before the pause";
  events.advanceTo(4.0);
  EXPECT_FALSE(clock.isPaused.get());
  EXPECT_NEAR(clock.elapsedTime.get().seconds, 2.0, 1e-9) << "4 s less the 2 s paused";
  events.advanceTo(7.0);
  EXPECT_FALSE(clock.isActive.get());
  EXPECT_NEAR(clock.fraction_changed.get(), 0.4f, 1e-6) << "stopped at 6 s: 4 s of 10";
}

TEST(EventCascade, OrientationInterpolatorTurnsATransformAlongTheShorterArc) {
  LoadResult r = load(x3dScene(R"(
    <Transform DEF="Turner"><Shape><Sphere radius="0.01"/></Shape></Transform>
    <TimeSensor DEF="Clock" cycleInterval="1"/>
    <OrientationInterpolator DEF="Half" key="0 1" keyValue="0 1 0 0, 0 1 0 3"/>
    <OrientationInterpolator DEF="Short" key="0 1" keyValue="0 1 0 0.1, 0 1 0 6.1"/>
    <ROUTE fromNode="Clock" fromField="fraction_changed" toNode="Half" toField="set_fraction"/>
    <ROUTE fromNode="Clock" fromField="fraction_changed" toNode="Short" toField="set_fraction"/>
    <ROUTE fromNode="Half" fromField="value_changed" toNode="Turner" toField="set_rotation"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& t = defNode<Transform>(r, "Turner");
  EventClock events(*r.scene);
  events.advanceTo(0.5);
  const glm::dquat q(t.rotation.get().quat());
  const glm::dquat want = glm::angleAxis(1.5, glm::dvec3(0, 1, 0));
  EXPECT_NEAR(std::abs(glm::dot(q, want)), 1.0, 1e-6) << "1.5 rad about +Y halfway";
  // 0.1 rad and 6.1 rad (= -0.183 rad) are 0.283 rad apart the short way: halfway is -0.0416 rad, not π.
  const auto& s = defNode<OrientationInterpolator>(r, "Short");
  const glm::dquat qs(s.value_changed.get().quat());
  const glm::dquat wantShort = glm::angleAxis((0.1 + (6.1 - 2 * std::numbers::pi)) / 2, glm::dvec3(0, 1, 0));
  EXPECT_NEAR(std::abs(glm::dot(qs, wantShort)), 1.0, 1e-6);
}

// Key down → BooleanFilter.inputTrue → BooleanToggle flips → a second
// BooleanFilter → IntegerTrigger 1 (on TRUE) or, through inputNegate,
// IntegerTrigger 0 (on FALSE) → Switch.whichChoice. Every route is
// type-correct (SFBool to SFBool, SFInt32 to SFInt32).
const char* kToggle = R"(
    <Switch DEF="Marker" whichChoice="0">
      <Shape><Box size="0.01 0.01 0.01"/></Shape>
      <Shape><Sphere radius="0.01"/></Shape>
    </Switch>
    <KeySensor DEF="Keys"/>
    <BooleanFilter DEF="Down"/>
    <BooleanToggle DEF="Flip"/>
    <BooleanFilter DEF="State"/>
    <IntegerTrigger DEF="One" integerKey="1"/>
    <IntegerTrigger DEF="Zero" integerKey="0"/>
    <ROUTE fromNode="Keys" fromField="isActive" toNode="Down" toField="set_boolean"/>
    <ROUTE fromNode="Down" fromField="inputTrue" toNode="Flip" toField="set_boolean"/>
    <ROUTE fromNode="Flip" fromField="toggle_changed" toNode="State" toField="set_boolean"/>
    <ROUTE fromNode="State" fromField="inputTrue" toNode="One" toField="set_boolean"/>
    <ROUTE fromNode="State" fromField="inputNegate" toNode="Zero" toField="set_boolean"/>
    <ROUTE fromNode="One" fromField="triggerValue" toNode="Marker" toField="whichChoice"/>
    <ROUTE fromNode="Zero" fromField="triggerValue" toNode="Marker" toField="whichChoice"/>)";

KeyEvent key(bool press, std::string c) { return KeyEvent{press, std::move(c), 0, KeyEvent::Modifier::None}; }

TEST(EventCascade, KeySensorTogglesASwitchThroughTypeCorrectRoutes) {
  LoadResult r = load(x3dScene(kToggle));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& sw = defNode<Switch>(r, "Marker");
  auto& keys = defNode<KeySensor>(r, "Keys");
  EventClock events(*r.scene);
  events.tick(0.0);
  EXPECT_EQ(sw.whichChoice.get(), 0) << "no key yet: as written";
  EXPECT_EQ(readSceneView(*r.scene).shapes.size(), 1u);

  events.key(key(true, "t"));
  events.tick(0.02);
  EXPECT_EQ(sw.whichChoice.get(), 1) << "first press";
  EXPECT_EQ(keys.keyPress.get(), "t");
  EXPECT_TRUE(keys.isActive.get());
  events.key(key(false, "t"));
  events.tick(0.04);
  EXPECT_EQ(sw.whichChoice.get(), 1) << "a release does not flip it";
  EXPECT_EQ(keys.keyRelease.get(), "t");
  events.key(key(true, "t"));
  events.key(key(false, "t"));  // press and release within one tick: each is its own timestamp
  events.tick(0.06);
  EXPECT_EQ(sw.whichChoice.get(), 0) << "second press";

  // The scene walk draws the chosen child only.
  const SceneView zero = readSceneView(*r.scene);
  ASSERT_EQ(zero.shapes.size(), 1u);
  EXPECT_EQ(zero.shapes[0].kind, DrawShape::Kind::Box);
  sw.whichChoice.set(1);
  EXPECT_EQ(readSceneView(*r.scene).shapes.at(0).kind, DrawShape::Kind::Sphere);
  sw.whichChoice.set(-1);
  EXPECT_TRUE(readSceneView(*r.scene).shapes.empty());
}

TEST(EventCascade, ActionAndModifierKeysAndDisabledSensors) {
  LoadResult r = load(x3dScene(R"(<KeySensor DEF="Keys"/><KeySensor DEF="Off" enabled="false"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& keys = defNode<KeySensor>(r, "Keys");
  auto& off = defNode<KeySensor>(r, "Off");
  EventClock events(*r.scene);
  events.key(KeyEvent{true, "", 17, KeyEvent::Modifier::None});  // Up
  events.key(KeyEvent{true, "", 0, KeyEvent::Modifier::Shift});
  EXPECT_GT(events.tick(0.0), 0u);
  EXPECT_EQ(keys.actionKeyPress.get(), 17);
  EXPECT_TRUE(keys.shiftKey.get());
  EXPECT_EQ(off.actionKeyPress.lastEvent(), 0u) << "a disabled KeySensor sends nothing";
  events.key(KeyEvent{false, "", 0, KeyEvent::Modifier::Shift});
  events.tick(0.02);
  EXPECT_FALSE(keys.shiftKey.get());
}

// Two interpolators feeding each other: A sends f, B sends 1 - f back to A,
// which has already sent at this timestamp, so the cascade ends and A keeps f.
TEST(EventCascade, ARouteCycleEndsWithEachNodeSendingOncePerTimestamp) {
  LoadResult r = load(x3dScene(R"(
    <TimeSensor DEF="Clock" cycleInterval="1" loop="true"/>
    <ScalarInterpolator DEF="A" key="0 1" keyValue="0 1"/>
    <ScalarInterpolator DEF="B" key="0 1" keyValue="1 0"/>
    <ROUTE fromNode="Clock" fromField="fraction_changed" toNode="A" toField="set_fraction"/>
    <ROUTE fromNode="A" fromField="value_changed" toNode="B" toField="set_fraction"/>
    <ROUTE fromNode="B" fromField="value_changed" toNode="A" toField="set_fraction"/>
    <Transform DEF="T1"/><Transform DEF="T2"/>
    <ROUTE fromNode="T1" fromField="translation_changed" toNode="T2" toField="set_translation"/>
    <ROUTE fromNode="T2" fromField="translation_changed" toNode="T1" toField="set_translation"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& a = defNode<ScalarInterpolator>(r, "A");
  auto& b = defNode<ScalarInterpolator>(r, "B");
  EventClock events(*r.scene);
  EXPECT_EQ(events.tick(0.25), 3u) << "the TimeSensor, A and B, once each";
  EXPECT_FLOAT_EQ(a.value_changed.get(), 0.25f);
  EXPECT_FLOAT_EQ(b.value_changed.get(), 0.75f);
  EXPECT_FALSE(a.hasPendingEvent()) << "B's event back into A is dropped, not kept for the next tick";
  EXPECT_EQ(events.tick(0.5), 3u);
  EXPECT_FLOAT_EQ(a.value_changed.get(), 0.5f);

  // Plain fields in a cycle: a set reaches the other side and stops there.
  auto& t1 = defNode<Transform>(r, "T1");
  auto& t2 = defNode<Transform>(r, "T2");
  t1.translation.set({1.f, 2.f, 3.f});
  EXPECT_EQ(t2.translation.get(), glm::vec3(1.f, 2.f, 3.f));
  EXPECT_EQ(t1.translation.get(), glm::vec3(1.f, 2.f, 3.f));
}

TEST(EventCascade, DrawnFieldsSeeWhatAnEventChanged) {
  LoadResult r = load(mover(false));
  ASSERT_TRUE(r.ok()) << r.report();
  EventClock events(*r.scene);
  FieldWatch drawn = drawnFields(*r.scene);
  EXPECT_FALSE(drawn.changed());
  events.tick(0.0);
  events.tick(0.5);
  EXPECT_TRUE(drawn.changed()) << "the interpolator moved the Transform";
  drawn.mark();
  EXPECT_FALSE(drawn.changed());
  events.advanceTo(5.0);  // the cycle ended at 2 s
  drawn.mark();
  events.tick(6.0);
  EXPECT_FALSE(drawn.changed()) << "an inactive sensor changes nothing";
}

void expectColor(const Color& c, glm::vec3 want, const char* when) {
  EXPECT_NEAR(c.rgb.r, want.r, 1e-5) << when;
  EXPECT_NEAR(c.rgb.g, want.g, 1e-5) << when;
  EXPECT_NEAR(c.rgb.b, want.b, 1e-5) << when;
}

// X3D 19.4.1: colours mix in HSV. Red (hue 0°) to blue (240°) goes the shorter
// way, through magenta (300°), not through green; black to green keeps green's
// hue and mixes saturation and value. The values below are worked by hand.
TEST(EventCascade, ColorInterpolatorMixesInHsvTheShorterWayRound) {
  LoadResult r = load(x3dScene(R"(
    <Shape><Appearance><Material DEF="Mat"/></Appearance><Sphere radius="0.01"/></Shape>
    <TimeSensor DEF="Clock" cycleInterval="4"/>
    <ColorInterpolator DEF="RedBlue" key="0 1" keyValue="1 0 0, 0 0 1"/>
    <ColorInterpolator DEF="BlackGreen" key="0 1" keyValue="0 0 0, 0 1 0"/>
    <ROUTE fromNode="Clock" fromField="fraction_changed" toNode="RedBlue" toField="set_fraction"/>
    <ROUTE fromNode="Clock" fromField="fraction_changed" toNode="BlackGreen" toField="set_fraction"/>
    <ROUTE fromNode="RedBlue" fromField="value_changed" toNode="Mat" toField="set_diffuseColor"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& mat = defNode<Material>(r, "Mat");
  const auto& blackGreen = defNode<ColorInterpolator>(r, "BlackGreen");
  EventClock events(*r.scene);
  events.advanceTo(1.0);  // fraction 0.25: hue 0° - 60° = 330°, s = v = 1
  expectColor(mat.diffuseColor.get(), {1.f, 0.f, 0.5f}, "t = 1 s");
  // hue 120°, s = v = 0.25: (v(1 - s), v, v(1 - s)); an RGB mix would give (0, 0.25, 0)
  expectColor(blackGreen.value_changed.get(), {0.1875f, 0.25f, 0.1875f}, "t = 1 s, black to green");
  events.advanceTo(2.0);  // fraction 0.5: hue 300°, magenta
  expectColor(mat.diffuseColor.get(), {1.f, 0.f, 1.f}, "t = 2 s");
  expectColor(blackGreen.value_changed.get(), {0.25f, 0.5f, 0.25f}, "t = 2 s, black to green");
  events.advanceTo(4.0);  // the end of the cycle: the last key
  expectColor(mat.diffuseColor.get(), {0.f, 0.f, 1.f}, "t = 4 s");
}

TEST(EventCascade, DrawnFieldsSeeAMatrixTransformsMatrix) {
  LoadResult r = load(x3dScene(R"(
    <MatrixTransform DEF="Source"/>
    <MatrixTransform DEF="Drawn"><Shape><Sphere radius="0.01"/></Shape></MatrixTransform>
    <ROUTE fromNode="Source" fromField="matrix_changed" toNode="Drawn" toField="set_matrix"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  FieldWatch drawn = drawnFields(*r.scene);
  EXPECT_FALSE(drawn.changed());
  defNode<MatrixTransform>(r, "Source").matrix.setFromString("1 0 0 0.01  0 1 0 0  0 0 1 0  0 0 0 1");
  EXPECT_TRUE(drawn.changed()) << "the routed matrix changed what is drawn";
  drawn.mark();
  EXPECT_FLOAT_EQ(defNode<MatrixTransform>(r, "Drawn").matrix.get()[3][0], 0.01f);
}

}  // namespace
