// X3D prototypes (issue 17, part 4): ProtoDeclare, ExternProtoDeclare,
// ProtoInstance, fieldValue and IS, expanded at load; routes through a
// proto instance's interface; and the errors that name the proto and field.
#include <gtest/gtest.h>

#include "SceneText.h"
#include "TestFiles.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/std/Appearance.h"
#include "millsim/std/Group.h"
#include "millsim/std/Material.h"
#include "millsim/std/Shape.h"
#include "millsim/std/Sphere.h"
#include "millsim/std/Transform.h"
#include "millsim/std/Viewpoint.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;
using millsim::test::ScratchDir;
using millsim::test::x3d;
using millsim::test::firstError;
using millsim::test::load;

namespace {


template <class T>
T& as(const std::shared_ptr<Node>& n) {
  auto* t = dynamic_cast<T*>(n.get());
  if (!t) throw std::runtime_error("expected another node type, found " + (n ? n->typeName() : std::string("null")));
  return *t;
}

// A Marker: a Transform holding a sphere and a Viewpoint, with one interface
// field of each access type and an SFNode field with a default node.
const char* kMarkerLibrary = R"(
<ProtoDeclare name="Marker">
  <ProtoInterface>
    <field name="size" type="SFFloat" accessType="initializeOnly" value="0.5"/>
    <field name="position" type="SFVec3f" accessType="inputOutput" value="0 0 0"/>
    <field name="bind" type="SFBool" accessType="inputOnly"/>
    <field name="bound" type="SFBool" accessType="outputOnly"/>
    <field name="look" type="SFNode" accessType="initializeOnly">
      <Appearance><Material diffuseColor="1 0 0"/></Appearance>
    </field>
  </ProtoInterface>
  <ProtoBody>
    <Transform>
      <IS><connect nodeField="translation" protoField="position"/></IS>
      <Shape>
        <IS><connect nodeField="appearance" protoField="look"/></IS>
        <Sphere><IS><connect nodeField="radius" protoField="size"/></IS></Sphere>
      </Shape>
      <Viewpoint><IS><connect nodeField="set_bind" protoField="bind"/><connect nodeField="isBound" protoField="bound"/></IS></Viewpoint>
    </Transform>
  </ProtoBody>
</ProtoDeclare>)";

const char* kMainScene = R"(
<ExternProtoDeclare name="Marker" url='"missing.x3d#Marker" "protos/markers.x3d#Marker"'>
  <field name="size" type="SFFloat" accessType="initializeOnly"/>
  <field name="position" type="SFVec3f" accessType="inputOutput"/>
  <field name="bind" type="SFBool" accessType="inputOnly"/>
  <field name="bound" type="SFBool" accessType="outputOnly"/>
  <field name="look" type="SFNode" accessType="initializeOnly"/>
</ExternProtoDeclare>
<ProtoDeclare name="Pair">
  <ProtoInterface>
    <field name="gap" type="SFVec3f" accessType="inputOutput" value="0.1 0 0"/>
    <field name="tipSize" type="SFFloat" accessType="initializeOnly" value="0.25"/>
    <field name="bindTip" type="SFBool" accessType="inputOnly"/>
    <field name="tipBound" type="SFBool" accessType="outputOnly"/>
  </ProtoInterface>
  <ProtoBody>
    <Group>
      <ProtoInstance name="Marker" DEF="Base"/>
      <ProtoInstance name="Marker" DEF="Tip">
        <IS>
          <connect nodeField="position" protoField="gap"/>
          <connect nodeField="size" protoField="tipSize"/>
          <connect nodeField="bind" protoField="bindTip"/>
          <connect nodeField="bound" protoField="tipBound"/>
        </IS>
      </ProtoInstance>
    </Group>
  </ProtoBody>
</ProtoDeclare>
<ProtoInstance name="Pair" DEF="P1"><fieldValue name="gap" value="0 0.2 0"/></ProtoInstance>
<ProtoInstance name="Pair" DEF="P2"><fieldValue name="tipSize" value="0.125"/></ProtoInstance>
<ProtoInstance name="Marker" DEF="M">
  <fieldValue name="look"><Appearance><Material diffuseColor="0 0 1"/></Appearance></fieldValue>
</ProtoInstance>
<ProtoInstance name="Pair" DEF="P3"/>
<Transform DEF="Mover" translation="0 0 0.3"/>
<Viewpoint DEF="Watcher"/>
<ROUTE fromNode="Mover" fromField="translation_changed" toNode="P3" toField="set_gap"/>
<ROUTE fromNode="Watcher" fromField="isBound" toNode="P3" toField="bindTip"/>
<ROUTE fromNode="P3" fromField="tipBound" toNode="Watcher" toField="set_bind"/>)";

// The parts of one expanded Marker.
struct MarkerParts {
  Transform* transform;
  Sphere* sphere;
  Material* material;
  Viewpoint* viewpoint;
};
MarkerParts partsOf(const std::shared_ptr<Node>& marker) {
  auto& t = as<Transform>(marker);
  EXPECT_EQ(t.children.get().size(), 2u);
  auto& shape = as<Shape>(t.children.get().at(0));
  auto& appearance = as<Appearance>(shape.appearance.get());
  return {&t, &as<Sphere>(shape.geometry.get()), &as<Material>(appearance.material.get()),
          &as<Viewpoint>(t.children.get().at(1))};
}

}  // namespace

// The must-hold test of issue 17: nested protos, IS on every access type and
// an ExternProtoDeclare to a sibling file.
TEST(Proto, NestedProtosIsOnEveryAccessTypeAndExternProtoToASiblingFile) {
  ScratchDir dir;
  dir.write("protos/markers.x3d", x3d(kMarkerLibrary));
  auto main = dir.write("main.x3d", x3d(kMainScene));
  auto r = loadSceneFile(main, builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  const auto& top = r.scene->root->children.get();
  ASSERT_EQ(top.size(), 6u);

  // A Pair is its body's first node, a Group holding two Markers.
  auto& p1 = as<Group>(r.scene->def("P1"));
  auto& p2 = as<Group>(r.scene->def("P2"));
  ASSERT_EQ(p1.children.get().size(), 2u);
  ASSERT_EQ(p2.children.get().size(), 2u);
  MarkerParts base1 = partsOf(p1.children.get()[0]), tip1 = partsOf(p1.children.get()[1]);
  MarkerParts tip2 = partsOf(p2.children.get()[1]);
  // initializeOnly: defaults, a nested IS, and a fieldValue through it.
  EXPECT_FLOAT_EQ(base1.sphere->radius.get(), 0.5f);
  EXPECT_FLOAT_EQ(tip1.sphere->radius.get(), 0.25f);
  EXPECT_FLOAT_EQ(tip2.sphere->radius.get(), 0.125f);
  // inputOutput: the fieldValue of the outer instance reaches the inner Transform.
  EXPECT_EQ(base1.transform->translation.get(), glm::vec3(0.f));
  EXPECT_EQ(tip1.transform->translation.get(), glm::vec3(0.f, 0.2f, 0.f));
  EXPECT_EQ(tip2.transform->translation.get(), glm::vec3(0.1f, 0.f, 0.f));
  // SFNode: the default node, one copy per instance; and a fieldValue of nodes.
  EXPECT_EQ(base1.material->diffuseColor.get().rgb, glm::vec3(1.f, 0.f, 0.f));
  EXPECT_NE(base1.material, tip1.material);
  auto m = partsOf(r.scene->def("M"));
  EXPECT_EQ(m.material->diffuseColor.get().rgb, glm::vec3(0.f, 0.f, 1.f));
  // Every instance is a fresh copy.
  EXPECT_NE(tip1.transform, tip2.transform);

  // Routes to and from the interface fields are routes to and from the inner fields.
  auto& p3 = as<Group>(r.scene->def("P3"));
  MarkerParts base3 = partsOf(p3.children.get()[0]), tip3 = partsOf(p3.children.get()[1]);
  auto& mover = as<Transform>(r.scene->def("Mover"));
  auto& watcher = as<Viewpoint>(r.scene->def("Watcher"));
  EXPECT_EQ(tip3.transform->translation.get(), glm::vec3(0.f, 0.f, 0.3f));  // a new route delivers the value
  mover.translation.set(glm::vec3(0.f, 0.f, 0.4f));
  EXPECT_EQ(tip3.transform->translation.get(), glm::vec3(0.f, 0.f, 0.4f));  // inputOutput, via set_gap
  EXPECT_EQ(base3.transform->translation.get(), glm::vec3(0.f));
  EXPECT_EQ(tip2.transform->translation.get(), glm::vec3(0.1f, 0.f, 0.f));  // other instances are untouched
  watcher.isBound.set(true);
  EXPECT_TRUE(tip3.viewpoint->set_bind.get());  // inputOnly
  EXPECT_FALSE(base3.viewpoint->set_bind.get());
  EXPECT_FALSE(watcher.set_bind.get());
  tip3.viewpoint->isBound.set(true);
  EXPECT_TRUE(watcher.set_bind.get());  // outputOnly
  EXPECT_EQ(r.scene->routes.size(), 3u);
}

TEST(Proto, BodyNodesAfterTheFirstAreKeptButNotInTheTree) {
  auto r = load(x3d(R"(
<ProtoDeclare name="Lit"><ProtoBody>
  <Transform DEF="T"/>
  <Viewpoint DEF="V" description="inside"/>
  <ROUTE fromNode="T" fromField="translation" toNode="V" toField="position"/>
</ProtoBody></ProtoDeclare>
<ProtoInstance name="Lit"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  ASSERT_EQ(r.scene->root->children.get().size(), 1u);
  EXPECT_EQ(r.scene->unattached.size(), 1u);
  EXPECT_EQ(r.scene->nodesOfType<Viewpoint>().size(), 1u);
  EXPECT_TRUE(r.scene->defs.empty());  // a body's DEF names are private to the instance
  auto& t = as<Transform>(r.scene->root->children.get()[0]);
  t.translation.set(glm::vec3(1.f, 2.f, 3.f));
  EXPECT_EQ(r.scene->nodesOfType<Viewpoint>()[0]->position.get(), glm::vec3(1.f, 2.f, 3.f));
}

TEST(Proto, FieldValueOfAnUndeclaredFieldNamesProtoAndField) {
  auto r = load(x3d(R"(
<ProtoDeclare name="Ball">
  <ProtoInterface><field name="radius" type="SFFloat" accessType="initializeOnly" value="1"/></ProtoInterface>
  <ProtoBody><Shape><Sphere><IS><connect nodeField="radius" protoField="radius"/></IS></Sphere></Shape></ProtoBody>
</ProtoDeclare>
<ProtoInstance name="Ball"><fieldValue name="radious" value="2"/></ProtoInstance>)"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(firstError(r).str(),
            "test.x3d:9:40: error: fieldValue: proto 'Ball' has no field 'radious' (its fields are 'radius'); "
            "did you mean 'radius'?")
      << r.report();
}

TEST(Proto, WrongTypedValueGivesTheValueAndTheExpectedType) {
  auto r = load(x3d(R"(
<ProtoDeclare name="Ball">
  <ProtoInterface><field name="radius" type="SFFloat" accessType="initializeOnly" value="1"/></ProtoInterface>
  <ProtoBody><Shape><Sphere><IS><connect nodeField="radius" protoField="radius"/></IS></Sphere></Shape></ProtoBody>
</ProtoDeclare>
<ProtoInstance name="Ball"><fieldValue name="radius" value="big"/></ProtoInstance>)"));
  ASSERT_FALSE(r.ok());
  const std::string e = firstError(r).str();
  EXPECT_NE(e.find("test.x3d:9:54: error: fieldValue: bad value 'big' for field 'radius' of proto 'Ball', which "
                   "expects SFFloat"),
            std::string::npos)
      << r.report();
  // A value of the right type that the inner field refuses names the proto, the field and the inner field.
  auto range = load(x3d(R"(
<ProtoDeclare name="Ball">
  <ProtoInterface><field name="radius" type="SFFloat" accessType="initializeOnly" value="1"/></ProtoInterface>
  <ProtoBody><Shape><Sphere><IS><connect nodeField="radius" protoField="radius"/></IS></Sphere></Shape></ProtoBody>
</ProtoDeclare>
<ProtoInstance name="Ball"><fieldValue name="radius" value="-1"/></ProtoInstance>)"));
  ASSERT_FALSE(range.ok());
  EXPECT_NE(firstError(range).str().find("test.x3d:9:54: error: bad value '-1' for field 'radius' of proto 'Ball' "
                                         "(IS Sphere.radius): value -1 is outside"),
            std::string::npos)
      << range.report();
}

TEST(Proto, ISConnectsAreCheckedForTypeAndAccess) {
  auto r = load(x3d(R"(
<ProtoDeclare name="Bad">
  <ProtoInterface>
    <field name="where" type="SFVec3f" accessType="inputOutput" value="0 0 0"/>
    <field name="size" type="SFVec3f" accessType="inputOutput" value="1 1 1"/>
  </ProtoInterface>
  <ProtoBody><Shape><Sphere><IS><connect nodeField="radius" protoField="where"/></IS></Sphere></Shape></ProtoBody>
</ProtoDeclare>
<ProtoInstance name="Bad"/>)"));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.report().find("IS connect: Sphere.radius is SFFloat but field 'where' of proto 'Bad' is SFVec3f"),
            std::string::npos)
      << r.report();
  auto access = load(x3d(R"(
<ProtoDeclare name="Bad">
  <ProtoInterface><field name="r" type="SFFloat" accessType="inputOutput" value="1"/></ProtoInterface>
  <ProtoBody><Shape><Sphere><IS><connect nodeField="radius" protoField="r"/></IS></Sphere></Shape></ProtoBody>
</ProtoDeclare>
<ProtoInstance name="Bad"/>)"));
  ASSERT_FALSE(access.ok());
  EXPECT_NE(access.report().find("IS connect: Sphere.radius is initializeOnly and cannot be connected to "
                                 "inputOutput SFFloat field 'r' of proto 'Bad'"),
            std::string::npos)
      << access.report();
  auto outside = load(x3d(R"(<Transform><IS><connect nodeField="translation" protoField="p"/></IS></Transform>)"));
  ASSERT_FALSE(outside.ok());
  EXPECT_NE(outside.report().find("<IS> belongs inside a <ProtoBody>"), std::string::npos) << outside.report();
}

TEST(Proto, RecursionIsAnErrorNotAHang) {
  auto self = load(x3d(R"(
<ProtoDeclare name="Forever"><ProtoBody><Group><ProtoInstance name="Forever"/></Group></ProtoBody></ProtoDeclare>
<ProtoInstance name="Forever"/>)"));
  ASSERT_FALSE(self.ok());
  EXPECT_NE(
      firstError(self).message.find("ProtoInstance of 'Forever' inside its own expansion ('Forever' -> 'Forever')"),
      std::string::npos)
      << self.report();
  auto mutual = load(x3d(R"(
<ProtoDeclare name="A"><ProtoBody><Group><ProtoInstance name="B"/></Group></ProtoBody></ProtoDeclare>
<ProtoDeclare name="B"><ProtoBody><Group><ProtoInstance name="A"/></Group></ProtoBody></ProtoDeclare>
<ProtoInstance name="A"/>)"));
  ASSERT_FALSE(mutual.ok());
  EXPECT_NE(firstError(mutual).message.find("('A' -> 'B' -> 'A')"), std::string::npos) << mutual.report();
}

TEST(Proto, ProtosThatMultiplyStopAtALimit) {
  // Six levels of ten: 222 222 body elements, past a limit of 20 000.
  std::string text;
  text += R"(<ProtoDeclare name="P0"><ProtoBody><Group/></ProtoBody></ProtoDeclare>)";
  for (int level = 1; level <= 5; ++level) {
    text += "<ProtoDeclare name=\"P" + std::to_string(level) + "\"><ProtoBody><Group>";
    for (int i = 0; i < 10; ++i) text += "<ProtoInstance name=\"P" + std::to_string(level - 1) + "\"/>";
    text += "</Group></ProtoBody></ProtoDeclare>\n";
  }
  text += R"(<ProtoInstance name="P5"/><ProtoInstance name="P5"/>)";
  LoadOptions options;
  options.maxProtoElements = 20000;
  auto r = loadSceneString(x3d(text), "test.x3d", builtinRegistry(), options);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.report().find("expanding the protos of this scene would make more than 20000 elements"),
            std::string::npos)
      << r.report().substr(0, 2000);
}

TEST(Proto, ExternProtoCyclesAreAnError) {
  ScratchDir dir;
  dir.write("a.x3d", x3d(R"(<ExternProtoDeclare name="Q" url='"b.x3d#Q"'/><ProtoInstance name="Q"/>)"));
  dir.write("b.x3d", x3d(R"(<ExternProtoDeclare name="Q" url='"c.x3d"'/>)"));
  dir.write("c.x3d", x3d(R"(<ExternProtoDeclare name="R" url='"b.x3d#Q"'/>)"));
  auto r = loadSceneFile(dir.path() / "a.x3d", builtinRegistry());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.report().find("is already being loaded (a cycle: b.x3d -> c.x3d -> b.x3d)"), std::string::npos)
      << r.report();
}

TEST(Proto, ExternProtoFieldsMustMatchTheDeclaration) {
  ScratchDir dir;
  dir.write("lib.x3d", x3d(R"(<ProtoDeclare name="Ball">
  <ProtoInterface><field name="radius" type="SFFloat" accessType="initializeOnly" value="1"/></ProtoInterface>
  <ProtoBody><Shape><Sphere><IS><connect nodeField="radius" protoField="radius"/></IS></Sphere></Shape></ProtoBody>
</ProtoDeclare>)"));
  auto main = dir.write("main.x3d", x3d(R"(<ExternProtoDeclare name="Ball" url='"lib.x3d"'>
  <field name="radius" type="SFDouble" accessType="initializeOnly"/>
</ExternProtoDeclare>)"));
  auto r = loadSceneFile(main, builtinRegistry());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.report().find("ExternProtoDeclare 'Ball' lists field 'radius' as initializeOnly SFDouble, but proto "
                            "'Ball' at "),
            std::string::npos)
      << r.report();
}

TEST(Proto, ProtoInstanceCanBeUsedAndIsPlacedByItsFirstNode) {
  auto r = load(x3d(R"(
<ProtoDeclare name="Ball"><ProtoBody><Sphere radius="0.25"/></ProtoBody></ProtoDeclare>
<Shape><ProtoInstance name="Ball" DEF="B"/></Shape>
<Shape><ProtoInstance name="Ball" USE="B"/></Shape>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  auto shapes = r.scene->nodesOfType<Shape>();
  ASSERT_EQ(shapes.size(), 2u);
  EXPECT_EQ(shapes[0]->geometry.get(), shapes[1]->geometry.get());
  EXPECT_FLOAT_EQ(as<Sphere>(shapes[0]->geometry.get()).radius.get(), 0.25f);
}

TEST(Proto, RoutesToAFieldAProtoCannotTakeAreRefused) {
  auto r = load(x3d(R"(
<ProtoDeclare name="Ball">
  <ProtoInterface><field name="radius" type="SFFloat" accessType="initializeOnly" value="1"/></ProtoInterface>
  <ProtoBody><Shape><Sphere><IS><connect nodeField="radius" protoField="radius"/></IS></Sphere></Shape></ProtoBody>
</ProtoDeclare>
<ProtoInstance name="Ball" DEF="B"/>
<Transform DEF="T"/>
<ROUTE fromNode="T" fromField="scale" toNode="B" toField="radius"/>)"));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(firstError(r).message.find("ROUTE to field 'radius' of proto 'Ball': it is initializeOnly and cannot be a "
                                       "route destination"),
            std::string::npos)
      << r.report();
}
