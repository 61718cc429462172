// Cut planes capped by the section (CutSection, CutCap): each tissue where
// the label volume puts it, soft tissue (the pulp) included; milling
// re-samples only what it reached and ends where a fresh section would; and
// the drawn cap shows the exposed pulp in its colour.
#include <gtest/gtest.h>

#include <map>

#include "../unit/TestFiles.h"
#include "SceneProbe.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/graphics/CutSection.h"
#include "millsim/graphics/GlContext.h"
#include "millsim/graphics/SceneDrawer.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/volume/VoxelVolume.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;
using namespace millsim::test;

namespace {

// The default lesson's tissues on the phantom at 0.2 mm, cut through its
// middle (keeps z <= 0), seen from the side the cut removed.
const char* kCutTooth = R"(
  <Viewpoint position="0 0.004 0.045"/>
  <ClipPlane plane="0 0 -1 0"/>
  <VolumeObject url='"phantom:tooth?size=128,128,88"' labelUrl='"phantom:tooth-labels?size=128,128,88"' isoValue="700">
    <Tissue name="enamel" label="1" color="0.95 0.95 0.92"/>
    <Tissue name="dentin" label="2" color="0.93 0.82 0.55"/>
    <Tissue name="pulp" label="3" color="0.8 0.3 0.3"/>
    <Tissue name="cementum" label="4" color="0.85 0.75 0.5"/>
  </VolumeObject>)";

const glm::dvec4 kMiddle(0.0, 0.0, -1.0, 0.0);

struct Loaded {
  ScratchDir dir;
  LoadResult result;
  SceneView view;
};

std::unique_ptr<Loaded> load(const char* body) {
  auto l = std::make_unique<Loaded>();
  l->result = loadSceneFile(l->dir.write("cut.x3d", x3d(body)), builtinRegistry());
  if (l->result.ok()) l->view = readSceneView(*l->result.scene);
  return l;
}

// The world point at texel (a, b)'s centre.
glm::dvec3 texelCentre(const CutSection& s, int a, int b) {
  const glm::dvec3 u = (s.corner(1) - s.corner(0)) / double(s.width()), v = (s.corner(3) - s.corner(0)) / double(s.height());
  return s.corner(0) + (a + 0.5) * u + (b + 0.5) * v;
}

const std::uint8_t* texel(const CutSection& s, int a, int b) {
  return &s.rgba()[(std::size_t(b) * std::size_t(s.width()) + std::size_t(a)) * 4];
}

// The label every voxel within one voxel of `index` has, or -1 if they differ.
int labelAround(const TissueMap& tissues, const glm::ivec3& index) {
  const int label = tissues.labelAt(index.x, index.y, index.z);
  for (int k = -1; k <= 1; ++k)
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i)
        if (tissues.labelAt(index.x + i, index.y + j, index.z + k) != label) return -1;
  return label;
}

// The same tooth turned 30° about Y and 20° about X and stretched 1.5 times
// along its local X, cut by the same world plane: the section is the world's.
const char* kTurnedTooth = R"(
  <ClipPlane plane="0 0 -1 0"/>
  <Transform rotation="0.85 0.5 0 0.6" scale="1.5 1 1">
    <VolumeObject url='"phantom:tooth?size=128,128,88"' labelUrl='"phantom:tooth-labels?size=128,128,88"' isoValue="700">
      <Tissue name="enamel" label="1" color="0.95 0.95 0.92"/>
      <Tissue name="dentin" label="2" color="0.93 0.82 0.55"/>
      <Tissue name="pulp" label="3" color="0.8 0.3 0.3"/>
      <Tissue name="cementum" label="4" color="0.85 0.75 0.5"/>
    </VolumeObject>
  </Transform>)";

class TissueSection : public ::testing::TestWithParam<const char*> {};

TEST_P(TissueSection, ShowsEachTissueWhereItsLabelsAreAndThePulpToo) {
  auto l = load(GetParam());
  ASSERT_TRUE(l->result.ok()) << l->result.report();
  const DrawVolume& dv = l->view.volumes.at(0);
  ASSERT_NE(dv.tissues, nullptr);
  CutSection section(*dv.voxels, float(dv.iso), dv.tissues);
  ASSERT_TRUE(section.aim(kMiddle, dv.localToWorld));
  EXPECT_NEAR(section.texelSize(), 0.2e-3, 1e-9) << "a texel the smallest voxel edge wide";

  // Every texel whose voxel and its neighbours hold one tissue shows that
  // tissue's colour and counts as material; every texel amid air, none.
  const glm::dmat4 worldToLocal = glm::inverse(dv.localToWorld);
  std::map<int, int> checked;
  for (int b = 0; b < section.height(); ++b)
    for (int a = 0; a < section.width(); ++a) {
      const glm::dvec3 local(worldToLocal * glm::dvec4(texelCentre(section, a, b), 1.0));
      const glm::ivec3 index(glm::round(dv.voxels->localToIndex(local)));
      const int label = labelAround(*dv.tissues, index);
      if (label < 0) continue;
      const std::uint8_t* t = texel(section, a, b);
      ++checked[label];
      if (label == 0) {
        EXPECT_LT(t[3], 128) << "air at texel " << a << "," << b;
        continue;
      }
      const glm::vec3 colour = dv.tissues->entries()[std::size_t(label)].colour;
      ASSERT_GE(t[3], 128) << dv.tissues->entries()[std::size_t(label)].name << " missing at texel " << a << "," << b;
      for (int k = 0; k < 3; ++k)
        ASSERT_NEAR(t[k], 255.0 * colour[k], 1.0) << dv.tissues->entries()[std::size_t(label)].name << " at texel " << a << "," << b;
    }
  for (int label : {0, 1, 2, 3}) EXPECT_GT(checked[label], 30) << "too few texels deep in label " << label;
  EXPECT_TRUE(dv.tissues->soft(3)) << "the phantom's pulp lies below the isoValue";
}

INSTANTIATE_TEST_SUITE_P(CutSection, TissueSection, ::testing::Values(kCutTooth, kTurnedTooth),
                         [](const auto& p) { return p.index == 0 ? "Upright" : "TurnedAndStretched"; });

TEST(CutSection, IsEmptyWhereThePlaneMissesTheVolume) {
  auto l = load(kCutTooth);
  ASSERT_TRUE(l->result.ok()) << l->result.report();
  const DrawVolume& dv = l->view.volumes.at(0);
  CutSection section(*dv.voxels, float(dv.iso), dv.tissues);
  EXPECT_FALSE(section.aim(glm::dvec4(0.0, 0.0, 1.0, -0.1), dv.localToWorld)) << "10 cm beyond the tooth";
  EXPECT_FALSE(section.hasSection());
  EXPECT_TRUE(section.aim(kMiddle, dv.localToWorld));
}

// Milling where the plane cuts re-samples the texels its blocks reach, no
// more, and leaves what a fresh section of the milled volume shows.
TEST(CutSection, FollowsMillingWhereItsBlocksMeetThePlane) {
  auto l = load(kCutTooth);
  ASSERT_TRUE(l->result.ok()) << l->result.report();
  const DrawVolume& dv = l->view.volumes.at(0);
  CutSection section(*dv.voxels, float(dv.iso), dv.tissues);
  ASSERT_TRUE(section.aim(kMiddle, dv.localToWorld));
  const std::uint64_t whole = section.texelsSampled();

  // A burr of 0.6 mm sunk into the crown's top, centred on the plane.
  VoxelScene hs(*l->result.scene);
  glm::dvec3 p(0.0, hs.volume(0).voxels->halfSize().y, 0.0);
  while (!hs.inside(p) && p.y > 0.0) p.y -= 1e-4;
  p.y -= 0.3e-3;
  ASSERT_GT(hs.mill(p, 0.6e-3), 0.0);
  const TexelRect r = section.update(hs.volume(0).changed.origins());
  ASSERT_FALSE(r.empty());
  EXPECT_LT(section.texelsSampled() - whole, whole / 10) << "a stamp re-samples a small part of the section";

  CutSection fresh(*dv.voxels, float(dv.iso), dv.tissues);
  ASSERT_TRUE(fresh.aim(kMiddle, dv.localToWorld));
  ASSERT_EQ(section.rgba().size(), fresh.rgba().size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < fresh.rgba().size(); ++i) differing += section.rgba()[i] != fresh.rgba()[i];
  EXPECT_EQ(differing, 0u) << "bytes of the updated section that differ from the milled volume's section";

  // And the stamp's centre, on the plane, is empty now.
  const glm::dvec3 u = (section.corner(1) - section.corner(0)) / double(section.width());
  const glm::dvec3 v = (section.corner(3) - section.corner(0)) / double(section.height());
  const glm::dvec3 world = glm::dvec3(dv.localToWorld * glm::dvec4(p, 1.0)) - section.corner(0);
  const int a = int(glm::dot(world, u) / glm::dot(u, u)), b = int(glm::dot(world, v) / glm::dot(v, v));
  EXPECT_LT(texel(section, a, b)[3], 128) << "the burr's centre is cut away";
  EXPECT_GE(r.x1, a);
  EXPECT_LE(r.x0, a);
}

// Drawn: at the pulp chamber's centre the picture shows the pulp's colour
// (red well over green and blue) on the plane itself; without caps the
// chamber's far wall, 2 mm behind, is what is there.
TEST(SceneDrawer, CapsACutWithThePulpInItsColour) {
  auto l = load(kCutTooth);
  ASSERT_TRUE(l->result.ok()) << l->result.report();
  constexpr int kSide = 256;
  GlContext context(kSide, kSide);
  SceneDrawer drawer(l->view);
  const glm::dmat4& toWorld = l->view.volumes[0].localToWorld;
  const glm::dvec3 pulpCentre(toWorld * glm::dvec4(0.0, 3.6e-3, 0.0, 1.0));
  const glm::dvec3 dentinAbove(toWorld * glm::dvec4(0.0, 5.8e-3, 0.0, 1.0));  // between the pulp horns and the enamel
  ASSERT_TRUE(l->view.volumes[0].tissues->soft(3));
  struct Seen {
    glm::u8vec4 colour;
    double distance;  // along the view axis
  };
  auto seen = [&](const glm::dvec3& world) {
    drawer.draw(kSide, kSide, {});
    const Image img = SceneDrawer::readPixels(kSide, kSide);
    const std::vector<float> depth = SceneDrawer::readDepth(kSide, kSide);
    const glm::dvec3 s = drawer.camera().project(world);
    const int x = int(s.x), y = int(s.y);
    return Seen{img.at(x, y), viewDistance(drawer.camera(), depth[std::size_t(y) * kSide + std::size_t(x)])};
  };
  const Seen pulp = seen(pulpCentre);
  EXPECT_EQ(drawer.stats().caps, 1u);
  EXPECT_GT(int(pulp.colour.r), int(pulp.colour.g) + 60) << "pulp pixel " << int(pulp.colour.r) << "," << int(pulp.colour.g) << "," << int(pulp.colour.b);
  EXPECT_GT(int(pulp.colour.r), int(pulp.colour.b) + 60);
  EXPECT_NEAR(pulp.distance, viewDistanceOf(drawer.camera(), pulpCentre), 0.1e-3) << "drawn on the plane";
  const Seen dentin = seen(dentinAbove);
  EXPECT_GT(int(dentin.colour.g), int(dentin.colour.b) + 40)
      << "dentin pixel " << int(dentin.colour.r) << "," << int(dentin.colour.g) << "," << int(dentin.colour.b);
  EXPECT_NEAR(dentin.distance, viewDistanceOf(drawer.camera(), dentinAbove), 0.1e-3);

  drawer.setCapCuts(false);
  const Seen open = seen(pulpCentre);
  EXPECT_EQ(drawer.stats().caps, 0u);
  EXPECT_GT(open.distance, viewDistanceOf(drawer.camera(), pulpCentre) + 1e-3) << "uncapped: the chamber's far wall";
}

}  // namespace
