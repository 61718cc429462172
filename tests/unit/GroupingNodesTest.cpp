// MatrixTransform and Collision as the loader reads them
// and as SceneWalk (and so haptics and graphics) sees them.
#include <gtest/gtest.h>

#include <map>

#include "SceneText.h"
#include "millsim/core/Scene.h"
#include "millsim/std/Collision.h"
#include "millsim/std/MatrixTransform.h"
#include "millsim/std/SceneWalk.h"
#include "millsim/std/Shape.h"

using namespace millsim;
using namespace millsim::test;

namespace {

std::string scene(const std::string& body, const std::string& head = "") {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Immersive" version="4.0">)" +
         (head.empty() ? std::string() : "<head>" + head + "</head>") + "<Scene>" + body + "</Scene></X3D>";
}

template <class T> T& def(const LoadResult& r, const char* name) {
  auto* n = dynamic_cast<T*>(r.scene->def(name).get());
  if (!n) throw std::runtime_error(std::string("no ") + name);
  return *n;
}

// Each DEF'd node's frame as the walk saw it.
std::map<std::string, WalkFrame> frames(const Scene& s) {
  std::map<std::string, WalkFrame> out;
  walkScene(s, [&](Node& n, const WalkFrame& at) {
    if (!n.defName().empty()) out[n.defName()] = WalkFrame{at.localToWorld, nullptr, at.shown, at.translucent};
  });
  return out;
}

TEST(MatrixTransform, PlacesItsChildrenWhereItsMatrixSays) {
  LoadResult r = load(scene(R"(
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
  LoadResult r = load(scene(R"(
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
  LoadResult r = load(scene(R"(
    <MatrixTransform DEF="M" matrix="2 0 0 10  0 1 0 -5  0 0 1 2.5  0 0 0 1"/>)",
                            R"(<unit category="length" name="millimetre" conversionFactor="0.001"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  const glm::mat4& m = def<MatrixTransform>(r, "M").matrix.get();
  EXPECT_FLOAT_EQ(m[3][0], 0.01f);
  EXPECT_FLOAT_EQ(m[3][1], -0.005f);
  EXPECT_FLOAT_EQ(m[3][2], 0.0025f);
  EXPECT_FLOAT_EQ(m[0][0], 2.f) << "a scale factor is not a length";
  EXPECT_FLOAT_EQ(m[1][1], 1.f);
  EXPECT_FLOAT_EQ(m[3][3], 1.f);
}

TEST(MatrixTransform, ASingularMatrixIsALoadErrorAtTheAttribute) {
  LoadResult r = load(scene("\n<MatrixTransform matrix='1 0 0 0  0 0 0 0  0 0 1 0  0 0 0 1'/>"));
  ASSERT_FALSE(r.ok());
  const Diagnostic& e = firstError(r);
  EXPECT_NE(e.message.find("singular"), std::string::npos) << r.report();
  EXPECT_EQ(e.where.line, 3);
  EXPECT_GT(e.where.column, 1) << r.report();
  EXPECT_NE(r.report().find("test.x3d:3:"), std::string::npos) << r.report();
}

TEST(Collision, ShowsItsChildrenButNotItsProxy) {
  LoadResult r = load(scene(R"(
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
  auto& c = def<Collision>(r, "C");
  EXPECT_FALSE(c.enabled.get());
  EXPECT_EQ(c.children.get().size(), 1u);
  ASSERT_TRUE(c.proxy.get());
}

}  // namespace
