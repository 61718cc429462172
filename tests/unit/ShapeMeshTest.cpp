// Mesh geometry as graphics draws it (millsim/graphics/ShapeMeshes.h): faces
// split into triangles, normals given or computed (flat, or smoothed within
// creaseAngle), colours per vertex or per face, winding; bad indices refused
// at load with file:line:column; NumberToText carries a number into a Text.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "SceneText.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/graphics/ShapeMeshes.h"
#include "millsim/std/Cone.h"
#include "millsim/std/EventClock.h"
#include "millsim/std/IndexedFaceSet.h"
#include "millsim/std/IndexedTriangleSet.h"
#include "millsim/std/Text.h"
#include "millsim/volume/VolumeObject.h"

using namespace millsim;
using namespace millsim::test;

namespace {

void expectVec(const glm::vec3& a, const glm::vec3& b, const char* what) {
  EXPECT_NEAR(a.x, b.x, 1e-5) << what;
  EXPECT_NEAR(a.y, b.y, 1e-5) << what;
  EXPECT_NEAR(a.z, b.z, 1e-5) << what;
}

// A unit square in z = 0 and a second square folded up 90° along x = 1: a roof edge.
const char* kFold = R"(<Coordinate point="0 0 0, 1 0 0, 1 1 0, 0 1 0, 1 0 -1, 1 1 -1"/>)";

TEST(ShapeMesh, AQuadIsTwoTrianglesFacingItsWinding) {
  LoadResult r = load(x3dScene(R"(<Shape><IndexedFaceSet DEF="F" coordIndex="0 1 2 3 -1">)" + std::string(kFold) +
                            "</IndexedFaceSet></Shape>"));
  ASSERT_TRUE(r.ok()) << r.report();
  const TriangleMesh m = meshOf(defNode<IndexedFaceSet>(r, "F"));
  ASSERT_EQ(m.triangles(), 2u);
  for (const glm::vec3& n : m.normals) expectVec(n, {0, 0, 1}, "counter-clockwise from +Z faces +Z");
  expectVec(m.boundsMin, {0, 0, 0}, "bounds");
  expectVec(m.boundsMax, {1, 1, 0}, "bounds");
  // X3D's default texture mapping: s along x, t along y, both over the longest side.
  EXPECT_NEAR(m.texCoords[1].x, 1.f, 1e-6);

  LoadResult cw = load(x3dScene(R"(<Shape><IndexedFaceSet DEF="F" ccw="false" coordIndex="0 1 2 3">)" + std::string(kFold) +
                             "</IndexedFaceSet></Shape>"));
  ASSERT_TRUE(cw.ok()) << cw.report();
  const TriangleMesh c = meshOf(defNode<IndexedFaceSet>(cw, "F"));
  ASSERT_EQ(c.triangles(), 2u) << "the last face needs no -1";
  for (const glm::vec3& n : c.normals) expectVec(n, {0, 0, -1}, "ccw FALSE: the front is the other side");
}

TEST(ShapeMesh, CreaseAngleSmoothsOnlyGentleEdges) {
  auto normalsAtSharedVertex = [](float crease) {
    LoadResult r = load(x3dScene(R"(<Shape><IndexedFaceSet DEF="F" creaseAngle=")" + std::to_string(crease) +
                              R"(" coordIndex="0 1 2 3 -1 1 4 5 2 -1">)" + std::string(kFold) + "</IndexedFaceSet></Shape>"));
    EXPECT_TRUE(r.ok()) << r.report();
    const TriangleMesh m = meshOf(defNode<IndexedFaceSet>(r, "F"));
    std::vector<glm::vec3> at;  // the normals drawn at vertex (1, 0, 0)
    for (std::size_t i = 0; i < m.positions.size(); ++i)
      if (glm::length(m.positions[i] - glm::vec3(1, 0, 0)) < 1e-6f) at.push_back(m.normals[i]);
    return at;
  };
  const auto flat = normalsAtSharedVertex(0.f);
  ASSERT_GE(flat.size(), 2u);
  bool differ = false;
  for (const glm::vec3& n : flat) differ |= glm::dot(n, flat.front()) < 0.5f;
  EXPECT_TRUE(differ) << "creaseAngle 0: each face keeps its own normal at the fold";
  const float half = 1.f / std::sqrt(2.f);
  for (const glm::vec3& n : normalsAtSharedVertex(1.6f)) expectVec(n, {half, 0, half}, "90° fold within 1.6 rad: averaged");
  for (const glm::vec3& n : normalsAtSharedVertex(1.5f)) EXPECT_GT(std::abs(n.x) + std::abs(n.z), 0.99f) << "1.5 rad: still sharp";
}

TEST(ShapeMesh, GivenNormalsAndPerFaceColoursAreUsed) {
  LoadResult r = load(x3dScene(R"(<Shape><IndexedFaceSet DEF="F" colorPerVertex="false" normalPerVertex="false"
      coordIndex="0 1 2 3 -1 1 4 5 2 -1" colorIndex="1 0">)" + std::string(kFold) +
                            R"(<Color color="1 0 0, 0 0 1"/><Normal vector="0 0 2, 3 0 0"/></IndexedFaceSet></Shape>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  const TriangleMesh m = meshOf(defNode<IndexedFaceSet>(r, "F"));
  ASSERT_EQ(m.triangles(), 4u);
  ASSERT_EQ(m.colours.size(), m.positions.size());
  expectVec(m.colours.front(), {0, 0, 1}, "face 0 takes colorIndex[0] = 1");
  expectVec(m.colours.back(), {1, 0, 0}, "face 1 takes colorIndex[1] = 0");
  expectVec(m.normals.front(), {0, 0, 1}, "face 0's normal, made unit length");
  expectVec(m.normals.back(), {1, 0, 0}, "face 1's normal");
}

TEST(ShapeMesh, TriangleSetAndConeHaveTheirShape) {
  LoadResult r = load(x3dScene(R"(<Shape><IndexedTriangleSet DEF="T" index="0 1 2 0 2 3">)" + std::string(kFold) +
                            R"(</IndexedTriangleSet></Shape><Shape><Cone DEF="C" bottomRadius="0.5" height="3"/></Shape>
      <Shape><Cone DEF="Base" side="false"/></Shape>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  const TriangleMesh t = meshOf(defNode<IndexedTriangleSet>(r, "T"));
  EXPECT_EQ(t.triangles(), 2u);
  const TriangleMesh c = meshOf(defNode<Cone>(r, "C"));
  EXPECT_NEAR(c.boundsMin.y, -1.5f, 1e-6);
  EXPECT_NEAR(c.boundsMax.y, 1.5f, 1e-6);
  EXPECT_NEAR(c.boundsMax.x, 0.5f, 1e-3);
  const TriangleMesh base = meshOf(defNode<Cone>(r, "Base"));
  EXPECT_GT(base.triangles(), 0u);
  EXPECT_NEAR(base.boundsMax.y, -1.f, 1e-6) << "side FALSE: only the base, at y = -height/2";
}

TEST(ShapeMesh, IndexOutOfRangeIsAnErrorAtTheNode) {
  LoadResult r = load(x3dScene(R"(
<Shape><IndexedFaceSet coordIndex="0 1 7 -1"><Coordinate point="0 0 0, 1 0 0, 1 1 0"/></IndexedFaceSet></Shape>)"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(firstError(r).str(),
            "test.x3d:3:8: error: IndexedFaceSet field 'coordIndex': index 7 at position 2 is out of range: the Coordinate "
            "has 3 entries (expected 0..2, or -1 to end a face)");
  LoadResult t = load(x3dScene(R"(<Shape><IndexedTriangleSet index="0 1 3"><Coordinate point="0 0 0, 1 0 0, 1 1 0"/></IndexedTriangleSet></Shape>)"));
  ASSERT_FALSE(t.ok());
  EXPECT_NE(firstError(t).message.find("index 3 at position 2 is out of range"), std::string::npos) << t.report();
}

TEST(SceneView, ReadsMeshesTextAndLights) {
  LoadResult r = load(x3dScene(R"(
    <NavigationInfo headlight="false"/>
    <DirectionalLight direction="0 -1 0" intensity="0.5" color="1 0 0"/>
    <Transform translation="0 0 2"><PointLight location="0 1 0" on="true"/></Transform>
    <SpotLight on="false"/>
    <Shape><IndexedFaceSet coordIndex="0 1 2 3">)" + std::string(kFold) + R"(</IndexedFaceSet></Shape>
    <Shape><Text string='"one" "two"'><FontStyle size="0.1" justify='"MIDDLE" "MIDDLE"'/></Text></Shape>
    <Shape><Text/></Shape>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  ShapeMeshCache cache;
  const SceneView v = readSceneView(*r.scene, nullptr, &cache);
  EXPECT_FALSE(v.headlight);
  ASSERT_EQ(v.lights.size(), 2u) << "a light that is off is not drawn";
  expectVec(v.lights[0].colour, {0.5f, 0, 0}, "colour × intensity");
  EXPECT_NEAR(v.lights[1].position.z, 2.0, 1e-9) << "a light's location follows its Transform";
  ASSERT_EQ(v.shapes.size(), 2u) << "an empty Text draws nothing";
  EXPECT_EQ(v.shapes[0].kind, DrawShape::Kind::Mesh);
  ASSERT_EQ(v.shapes[1].kind, DrawShape::Kind::Text);
  EXPECT_EQ(v.shapes[1].text->lines, (std::vector<std::string>{"one", "two"}));
  EXPECT_EQ(v.shapes[1].text->justifyMinor, "MIDDLE");
  EXPECT_EQ(readSceneView(*r.scene, nullptr, &cache).shapes[0].mesh, v.shapes[0].mesh)
      << "an unchanged mesh is not built again";
}

// The issue's must-hold: a route from removedVolume into a Text's string
// updates it (through NumberToText: X3D routes join fields of one type).
TEST(NumberToText, RemovedVolumeIsShownInAText) {
  LoadResult r = load(x3dScene(R"(
    <VolumeObject DEF="Tooth" url="phantom:tooth?size=24,24,16"/>
    <NumberToText DEF="Fmt" scale="1e9" decimals="2" prefix="removed " suffix=" mm³"/>
    <Shape><Text DEF="Label" string='"nothing yet"'/></Shape>
    <ROUTE fromNode="Tooth" fromField="removedVolume" toNode="Fmt" toField="set_value"/>
    <ROUTE fromNode="Fmt" fromField="string_changed" toNode="Label" toField="set_string"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  auto& label = defNode<Text>(r, "Label");
  EventClock events(*r.scene);
  events.tick(0.0);
  EXPECT_EQ(label.string.get(), std::vector<std::string>{"nothing yet"}) << "no event yet, the written string stays";
  defNode<VolumeObject>(r, "Tooth").removedVolume.set(2.5e-9f);
  events.tick(0.02);
  EXPECT_EQ(label.string.get(), std::vector<std::string>{"removed 2.50 mm³"});
  defNode<VolumeObject>(r, "Tooth").removedVolume.set(1.234e-8f);
  events.tick(0.04);
  EXPECT_EQ(readSceneView(*r.scene).shapes.at(0).text->lines, std::vector<std::string>{"removed 12.34 mm³"})
      << "what graphics draws follows";
}

}  // namespace
