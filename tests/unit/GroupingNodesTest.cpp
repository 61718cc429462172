// MatrixTransform, Collision and the metadata nodes as the loader reads them
// and as SceneWalk (and so haptics and graphics) sees them.
#include <gtest/gtest.h>

#include <map>

#include "SceneText.h"
#include "millsim/core/Scene.h"
#include "millsim/std/Collision.h"
#include "millsim/std/Material.h"
#include "millsim/std/MatrixTransform.h"
#include "millsim/std/MetadataBoolean.h"
#include "millsim/std/MetadataDouble.h"
#include "millsim/std/MetadataFloat.h"
#include "millsim/std/MetadataInteger.h"
#include "millsim/std/MetadataSet.h"
#include "millsim/std/MetadataString.h"
#include "millsim/std/SceneWalk.h"
#include "millsim/std/Shape.h"

using namespace millsim;
using namespace millsim::test;

namespace {

// Each DEF'd node's frame as the walk saw it.
std::map<std::string, WalkFrame> frames(const Scene& s) {
  std::map<std::string, WalkFrame> out;
  walkScene(s, [&](Node& n, const WalkFrame& at) {
    if (!n.defName().empty()) out[n.defName()] = WalkFrame{at.localToWorld, nullptr, at.shown, at.translucent, nullptr};
  });
  return out;
}

TEST(MatrixTransform, PlacesItsChildrenWhereItsMatrixSays) {
  LoadResult r = load(x3dScene(R"(
    <MatrixTransform DEF="M" matrix="1 0 0 0.01  0 1 0 0  0 0 1 0  0 0 0 1">
      <Shape DEF="S"><Sphere radius="0.001"/></Shape>
    </MatrixTransform>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  const auto f = frames(*r.scene);
  ASSERT_TRUE(f.count("S"));
  const glm::dvec4 origin = f.at("S").localToWorld * glm::dvec4(0, 0, 0, 1);
  EXPECT_NEAR(origin.x, 0.01, 1e-9) << "10 mm along +x";
  EXPECT_NEAR(origin.y, 0.0, 1e-12);
  EXPECT_NEAR(origin.z, 0.0, 1e-12);
  EXPECT_TRUE(f.at("S").shown);
}

TEST(MatrixTransform, NestsWithTransformsInOrder) {
  LoadResult r = load(x3dScene(R"(
    <Transform rotation="0 0 1 1.5707963">
      <MatrixTransform matrix="2 0 0 0.01  0 2 0 0  0 0 2 0  0 0 0 1">
        <Shape DEF="S"><Sphere radius="0.001"/></Shape>
      </MatrixTransform>
    </Transform>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  const glm::dvec4 p = frames(*r.scene).at("S").localToWorld * glm::dvec4(0.001, 0, 0, 1);
  // Scaled by 2 and moved 10 mm along x inside, then turned a quarter about z: (0.012, 0) → (0, 0.012).
  EXPECT_NEAR(p.x, 0.0, 1e-7);
  EXPECT_NEAR(p.y, 0.012, 1e-7);
}

TEST(MatrixTransform, UnitStatementsConvertOnlyTheTranslation) {
  LoadResult r = load(x3dScene(R"(
    <MatrixTransform DEF="M" matrix="2 0 0 10  0 1 0 -5  0 0 1 2.5  0 0 0 1"/>)",
                            R"(<unit category="length" name="millimetre" conversionFactor="0.001"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  const glm::mat4& m = defNode<MatrixTransform>(r, "M").matrix.get();
  EXPECT_FLOAT_EQ(m[3][0], 0.01f);
  EXPECT_FLOAT_EQ(m[3][1], -0.005f);
  EXPECT_FLOAT_EQ(m[3][2], 0.0025f);
  EXPECT_FLOAT_EQ(m[0][0], 2.f) << "a scale factor is not a length";
  EXPECT_FLOAT_EQ(m[1][1], 1.f);
  EXPECT_FLOAT_EQ(m[3][3], 1.f);
}

TEST(MatrixTransform, ASingularMatrixIsALoadErrorAtTheAttribute) {
  LoadResult r = load(x3dScene("\n<MatrixTransform matrix='1 0 0 0  0 0 0 0  0 0 1 0  0 0 0 1'/>"));
  ASSERT_FALSE(r.ok());
  const Diagnostic& e = firstError(r);
  EXPECT_NE(e.message.find("singular"), std::string::npos) << r.report();
  EXPECT_EQ(e.where.line, 3);
  EXPECT_GT(e.where.column, 1) << r.report();
  EXPECT_NE(r.report().find("test.x3d:3:"), std::string::npos) << r.report();
}

TEST(Collision, ShowsItsChildrenButNotItsProxy) {
  LoadResult r = load(x3dScene(R"(
    <Collision DEF="C" enabled="false">
      <Transform translation="0.02 0 0"><Shape DEF="Child"><Box size="0.01 0.01 0.01"/></Shape></Transform>
      <Transform containerField="proxy"><Shape DEF="Proxy"><Sphere radius="0.05"/></Shape></Transform>
    </Collision>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  const auto f = frames(*r.scene);
  ASSERT_TRUE(f.count("Child") && f.count("Proxy"));
  EXPECT_TRUE(f.at("Child").shown);
  EXPECT_NEAR((f.at("Child").localToWorld * glm::dvec4(0, 0, 0, 1)).x, 0.02, 1e-9) << "placed as in a Group";
  EXPECT_FALSE(f.at("Proxy").shown) << "the proxy is for collision only";
  auto& c = defNode<Collision>(r, "C");
  EXPECT_FALSE(c.enabled.get());
  EXPECT_EQ(c.children.get().size(), 1u);
  ASSERT_TRUE(c.proxy.get());
}

TEST(Metadata, LoadsUnderAnyNodeAndInsideASet) {
  LoadResult r = load(x3dScene(R"(
    <Transform DEF="T">
      <MetadataString DEF="Author" name="author" value='"Blender" "4.1"' reference="https://blender.org"/>
      <Shape DEF="S">
        <MetadataSet DEF="Set" name="export">
          <MetadataInteger DEF="I" name="version" value="1 2 3"/>
          <MetadataFloat name="scale" value="0.5" containerField="value"/>
          <MetadataDouble name="precise" value="0.1"/>
          <MetadataBoolean name="flags" value="true false"/>
          <MetadataString containerField="metadata" name="about the set"/>
        </MetadataSet>
        <Appearance><Material DEF="Mat"><MetadataFloat DEF="F" name="ior" value="1.5"/></Material></Appearance>
        <Sphere radius="0.01"><MetadataBoolean name="generated" value="true"/></Sphere>
      </Shape>
    </Transform>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  EXPECT_TRUE(r.diagnostics.empty()) << r.report();
  auto& author = defNode<MetadataString>(r, "Author");
  EXPECT_EQ(author.value.get(), (std::vector<std::string>{"Blender", "4.1"}));
  EXPECT_EQ(author.reference.get(), "https://blender.org");
  EXPECT_EQ(defNode<Transform>(r, "T").metadata.get().get(), &author);
  auto& set = defNode<MetadataSet>(r, "Set");
  EXPECT_EQ(defNode<Shape>(r, "S").metadata.get().get(), &set);
  ASSERT_EQ(set.value.get().size(), 4u) << "metadata nodes inside a set are its values";
  EXPECT_EQ(set.value.get()[0].get(), &defNode<MetadataInteger>(r, "I"));
  EXPECT_EQ(defNode<MetadataInteger>(r, "I").value.get(), (std::vector<std::int32_t>{1, 2, 3}));
  ASSERT_TRUE(set.metadata.get());
  EXPECT_EQ(set.metadata.get()->typeName(), "MetadataString");
  EXPECT_EQ(defNode<Material>(r, "Mat").metadata.get().get(), &defNode<MetadataFloat>(r, "F"));
}

TEST(Metadata, OnlyMetadataNodesFitTheMetadataField) {
  LoadResult r = load(x3dScene(R"(
    <Group><Shape containerField="metadata"><Sphere/></Shape></Group>)"));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(firstError(r).message.find("X3DMetadataObject"), std::string::npos) << r.report();
  LoadResult two = load(x3dScene(R"(
    <Group><MetadataString name="a"/><MetadataString name="b"/></Group>)"));
  ASSERT_FALSE(two.ok());
  EXPECT_NE(firstError(two).message.find("already holds"), std::string::npos) << two.report();
}

}  // namespace
