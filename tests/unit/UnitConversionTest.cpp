// X3D 4.0 <unit> statements (issue 17, part 6): values of a length, angle,
// mass or force quantity (and of quantities made of them, such as N/m) are
// converted to SI when a file is read, each file in its own units; every
// field declares its quantity, and the unit its documentation names agrees.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <regex>

#include "SceneText.h"
#include "TestFiles.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/devices/HandDevice.h"
#include "millsim/haptics/MillTool.h"
#include "millsim/renderers/LineProxyRenderer.h"
#include "millsim/std/Box.h"
#include "millsim/std/ClipPlane.h"
#include "millsim/std/Group.h"
#include "millsim/std/Inline.h"
#include "millsim/std/Shape.h"
#include "millsim/std/Sphere.h"
#include "millsim/std/Transform.h"
#include "millsim/std/Viewpoint.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;
using millsim::test::firstError;
using millsim::test::load;
using millsim::test::ScratchDir;

namespace {

template <class T> T& as(const std::shared_ptr<Node>& n) {
  auto* t = dynamic_cast<T*>(n.get());
  if (!t) throw std::runtime_error("expected another node type, found " + (n ? n->typeName() : std::string("null")));
  return *t;
}

std::string scene(const std::string& units, const std::string& body) {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<X3D profile=\"Immersive\" version=\"4.0\">\n<head>\n" + units +
         "\n</head>\n<Scene>\n" + body + "\n</Scene>\n</X3D>\n";
}

const char* kMillimetres = R"(<unit category="length" name="millimetre" conversionFactor="0.001"/>)";
const char* kDegrees = R"(<unit category="angle" name="degree" conversionFactor="0.017453292519943295"/>)";
const char* kGrams = R"(<unit category="mass" name="gram" conversionFactor="0.001"/>)";

bool sameDimension(const Quantity& a, const Quantity& b) {
  return a.length == b.length && a.angle == b.angle && a.mass == b.mass && a.force == b.force && a.time == b.time;
}

}  // namespace

// The unit a field's one line of documentation names is the quantity it is
// converted as: a field whose doc says "(N/m)" but declares no quantity would
// be read unconverted from a millimetre scene, silently 1000 times too soft.
TEST(Units, EveryFieldsQuantityMatchesTheUnitItsDocumentationNames) {
  const std::map<std::string, Quantity> units = {
      {"m", quantity::length},          {"m/s", quantity::velocity},
      {"metres", quantity::length},     {"N", quantity::force},
      {"N·m", quantity::torque},        {"N/m", quantity::linearStiffness},
      {"N·s/m", quantity::linearDamping}, {"N·m/rad", quantity::angularStiffness},
      {"N·m·s/rad", quantity::angularDamping}, {"kg", quantity::mass},
      {"kg·m²", quantity::inertia},     {"radians", quantity::angle},
      {"rad/s", quantity::angularVelocity}};  // per second converts as the angle (X3D has no time unit)
  // "(N/m)", "(m, world)", "d is in metres".
  const std::regex named(R"(\((m|m/s|N|N·m|N/m|N·s/m|N·m/rad|N·m·s/rad|kg|kg·m²|radians|rad/s)[,)]|in (metres))");
  NodeRegistry r = builtinRegistry();
  int tagged = 0;
  for (const NodeType* t : r.all()) {
    auto node = t->create();
    for (Field* f : node->fields()) {
      if (f->isNodeField() || !settableInFile(f->access())) continue;  // output-only values are never read from text
      const std::string doc(f->doc());
      std::smatch m;
      Quantity expected{};
      if (std::regex_search(doc, m, named)) expected = units.at(m[1].matched ? m[1].str() : m[2].str());
      const Quantity declared = f->range() ? f->range()->quantity : Quantity{};
      EXPECT_TRUE(sameDimension(declared, expected))
          << t->name << "." << f->name() << ": the doc names "
          << (m.empty() ? std::string("no unit") : m.str()) << " but the field declares another quantity (Range::in)";
      if (!declared.dimensionless()) ++tagged;
    }
  }
  EXPECT_GT(tagged, 40);  // the check above must have had something to compare
  // And the unit `check` prints after each value is the one the doc names.
  for (const auto& [name, q] : units) {
    if (name != "metres" && name != "radians") {
      EXPECT_EQ(siUnit(q), name);
    }
  }
  EXPECT_EQ(siUnit(quantity::length), "m");
  EXPECT_EQ(siUnit(Quantity{}), "");
}

TEST(Units, AScenesValuesAreReadInItsUnitsAndStoredInSI) {
  auto r = load(scene(std::string(kMillimetres) + kDegrees + kGrams, R"(
    <Transform DEF="T" translation="1 2 3" rotation="0 1 0 90" center="0 -5 0" bboxSize="-1 -1 -1">
      <ClipPlane DEF="Cut" plane="0 1 0 -2"/>
      <Shape><Box DEF="B" size="2 4 6"/></Shape>
    </Transform>
    <Viewpoint DEF="V" position="0 0 60" fieldOfView="45" nearDistance="-1"/>
    <HandDevice DEF="D" forceLimit="8" torqueLimit="200" positionCalibration="0 10 0"
                handMass="550" handStiffness="0.5" handInertia="300" handAngularStiffness="2000">
      <MillTool DEF="Tool" tipRadius="0.5" shaftLength="15"/>
      <LineProxyRenderer DEF="R" springConstant="0.5" feedResistance="20"/>
    </HandDevice>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& s = *r.scene;
  auto& t = as<Transform>(s.def("T"));
  EXPECT_FLOAT_EQ(t.translation.get().y, 0.002f);
  EXPECT_FLOAT_EQ(t.center.get().y, -0.005f);
  EXPECT_FLOAT_EQ(t.rotation.get().angle, float(std::numbers::pi / 2));
  EXPECT_EQ(t.bboxSize.get(), glm::vec3(-1.f));  // "none" stays none
  EXPECT_EQ(as<ClipPlane>(s.def("Cut")).plane.get(), glm::vec4(0.f, 1.f, 0.f, -0.002f));  // only d is a length
  EXPECT_FLOAT_EQ(as<Box>(s.def("B")).size.get().z, 0.006f);
  auto& v = as<Viewpoint>(s.def("V"));
  EXPECT_FLOAT_EQ(v.position.get().z, 0.06f);
  EXPECT_FLOAT_EQ(v.fieldOfView.get(), float(std::numbers::pi / 4));
  EXPECT_FLOAT_EQ(v.nearDistance.get(), -1.f);
  auto& d = as<HandDevice>(s.def("D"));
  EXPECT_FLOAT_EQ(d.forceLimit.get(), 8.f);            // newtons: no force unit given
  EXPECT_FLOAT_EQ(d.torqueLimit.get(), 0.2f);          // N·mm
  EXPECT_FLOAT_EQ(d.positionCalibration.get().y, 0.01f);
  EXPECT_FLOAT_EQ(d.handMass.get(), 0.55f);            // grams
  EXPECT_FLOAT_EQ(d.handStiffness.get(), 500.f);       // N/mm
  EXPECT_FLOAT_EQ(d.handInertia.get(), 3e-7f);         // g·mm²
  EXPECT_NEAR(d.handAngularStiffness.get(), 2000 * 1e-3 / (std::numbers::pi / 180), 1e-3);  // N·mm/degree
  auto& tool = as<MillTool>(s.def("Tool"));
  EXPECT_FLOAT_EQ(tool.tipRadius.get(), 0.0005f);
  EXPECT_FLOAT_EQ(tool.shaftLength.get(), 0.015f);
  auto& renderer = as<LineProxyRenderer>(s.def("R"));
  EXPECT_FLOAT_EQ(renderer.springConstant.get(), 500.f);
  EXPECT_FLOAT_EQ(renderer.feedResistance.get(), 20000.f);  // N·s/mm
}

TEST(Units, ASceneWithoutUnitStatementsIsReadAsWritten) {
  auto r = load(scene("", R"(<Transform DEF="T" translation="1 2 3" rotation="0 1 0 1.5"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& t = as<Transform>(r.scene->def("T"));
  EXPECT_EQ(t.translation.get(), glm::vec3(1.f, 2.f, 3.f));
  EXPECT_FLOAT_EQ(t.rotation.get().angle, 1.5f);
}

// The range is checked in SI, and the message says the value was converted.
TEST(Units, AValueOutOfRangeAfterConversionSaysSo) {
  auto r = load(scene(kMillimetres, R"(<HandDevice><MillTool tipRadius="50"/></HandDevice>)"));
  ASSERT_FALSE(r.ok());
  const Diagnostic& e = firstError(r);
  EXPECT_EQ(e.where.line, 7);
  EXPECT_NE(e.message.find("value 0.05 is outside the expected range (0, 0.01]"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("after converting from the file's <unit> statements"), std::string::npos) << e.message;
}

TEST(Units, ASecondStatementForOneCategoryIsAnError) {
  auto r = load(scene(std::string(kMillimetres) + "\n<unit category=\"length\" name=\"centimetre\" conversionFactor=\"0.01\"/>",
                      "<Group/>"));
  ASSERT_FALSE(r.ok());
  const Diagnostic& e = firstError(r);
  EXPECT_EQ(e.where.line, 5);
  EXPECT_NE(e.message.find("a second <unit> statement for category 'length'"), std::string::npos) << e.message;
}

// An Inline'd file is read in its own units, whatever the including file's are.
TEST(Units, AnInlineKeepsItsOwnUnits) {
  ScratchDir dir;
  dir.write("si.x3d", scene("", R"(<Shape><Box DEF="Inner" size="0.002 0.002 0.002"/></Shape>)"));
  dir.write("mm.x3d", scene(kMillimetres, R"(<Shape><Box DEF="Inner" size="3 3 3"/></Shape>)"));
  auto main = dir.write("main.x3d", scene(kMillimetres, R"(
    <Shape><Box DEF="Outer" size="2 2 2"/></Shape>
    <Inline DEF="A" url='"si.x3d"'/>)"));
  auto r = loadSceneFile(main, builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  EXPECT_FLOAT_EQ(as<Box>(r.scene->def("Outer")).size.get().x, 0.002f);
  const auto& inlined = as<Inline>(r.scene->def("A")).loaded.get();
  ASSERT_EQ(inlined.size(), 1u);
  EXPECT_FLOAT_EQ(as<Box>(as<Shape>(inlined[0]).geometry.get()).size.get().x, 0.002f);

  auto siMain = dir.write("si-main.x3d", scene("", R"(<Inline DEF="A" url='"mm.x3d"'/>)"));
  auto r2 = loadSceneFile(siMain, builtinRegistry());
  ASSERT_TRUE(r2.ok()) << r2.report();
  const auto& inlined2 = as<Inline>(r2.scene->def("A")).loaded.get();
  ASSERT_EQ(inlined2.size(), 1u);
  EXPECT_FLOAT_EQ(as<Box>(as<Shape>(inlined2[0]).geometry.get()).size.get().x, 0.003f);
}

// A prototype's default is in the units of the file that declares it; a
// fieldValue in the units of the file that writes it.
TEST(Units, ProtoValuesAreConvertedInTheUnitsOfTheFileThatWroteThem) {
  ScratchDir dir;
  dir.write("ball.x3d", scene("", R"(
    <ProtoDeclare name="Ball">
      <ProtoInterface><field name="r" type="SFFloat" accessType="initializeOnly" value="0.003"/></ProtoInterface>
      <ProtoBody><Shape><Sphere><IS><connect nodeField="radius" protoField="r"/></IS></Sphere></Shape></ProtoBody>
    </ProtoDeclare>)"));
  auto main = dir.write("main.x3d", scene(kMillimetres, R"(
    <ExternProtoDeclare name="Ball" url='"ball.x3d#Ball"'>
      <field name="r" type="SFFloat" accessType="initializeOnly"/>
    </ExternProtoDeclare>
    <ProtoDeclare name="Bead">
      <ProtoInterface><field name="r" type="SFFloat" accessType="initializeOnly" value="1"/></ProtoInterface>
      <ProtoBody><Shape><Sphere><IS><connect nodeField="radius" protoField="r"/></IS></Sphere></Shape></ProtoBody>
    </ProtoDeclare>
    <ProtoInstance name="Ball" DEF="BallDefault"/>
    <ProtoInstance name="Ball" DEF="BallGiven"><fieldValue name="r" value="4"/></ProtoInstance>
    <ProtoInstance name="Bead" DEF="BeadDefault"/>
    <ProtoInstance name="Bead" DEF="BeadGiven"><fieldValue name="r" value="2"/></ProtoInstance>)"));
  auto r = loadSceneFile(main, builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  auto radius = [&](const char* def) { return as<Sphere>(as<Shape>(r.scene->def(def)).geometry.get()).radius.get(); };
  EXPECT_FLOAT_EQ(radius("BallDefault"), 0.003f);  // ball.x3d is in metres
  EXPECT_FLOAT_EQ(radius("BallGiven"), 0.004f);    // main.x3d is in millimetres
  EXPECT_FLOAT_EQ(radius("BeadDefault"), 0.001f);
  EXPECT_FLOAT_EQ(radius("BeadGiven"), 0.002f);
}
