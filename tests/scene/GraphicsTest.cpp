// The graphics building blocks: context and PNG errors, incremental remeshing
// against a full rebuild, ClipPlane scoping.
#include <gtest/gtest.h>

#include <iostream>

#include <numbers>

#include "../unit/TestFiles.h"
#include "ImageCompare.h"
#include "millsim/core/NodeRegistry.h"
#include "millsim/graphics/Examine.h"
#include "millsim/graphics/GlContext.h"
#include "millsim/graphics/PointerTool.h"
#include "millsim/graphics/SceneDrawer.h"
#include "millsim/std/ClipPlane.h"
#include "millsim/std/EventClock.h"
#include "millsim/std/Switch.h"
#include "millsim/graphics/GraphicsError.h"
#include "millsim/graphics/SceneRenderer.h"
#include "millsim/volume/VoxelScene.h"
#include "millsim/x3d/X3DLoader.h"

using namespace millsim;
using namespace millsim::test;

namespace {

RendererOptions sized(int side) {
  RendererOptions o;
  o.width = o.height = side;
  return o;
}

std::string errorOf(int w, int h) {
  try {
    GlContext c(w, h);
  } catch (const GraphicsError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GlContext, RefusesBadSizesNamingThem) {
  EXPECT_NE(errorOf(0, 512).find("0x512"), std::string::npos) << errorOf(0, 512);
  EXPECT_NE(errorOf(512, -3).find("512x-3"), std::string::npos);
  EXPECT_NE(errorOf(9000, 16).find("9000x16"), std::string::npos);
}

TEST(GlContext, IsCoreProfileOnOSMesa) {
  GlContext c(16, 16);
  EXPECT_NE(c.description().find("Core"), std::string::npos) << c.description();
}

TEST(WritePng, UnwritablePathIsAClearError) {
  Image img{2, 2, std::vector<std::uint8_t>(16, 255)};
  try {
    writePng(img, "/nonexistent-folder/shot.png");
    FAIL() << "no error";
  } catch (const GraphicsError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/shot.png"), std::string::npos) << e.what();
  }
}

TEST(WritePng, RoundTrips) {
  ScratchDir dir;
  Image img{3, 2, {}};
  for (int i = 0; i < 24; ++i) img.rgba.push_back(std::uint8_t(i * 10));
  writePng(img, dir.path() / "x.png");
  const Image back = readPng(dir.path() / "x.png");
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.rgba, img.rgba);
}

// A small phantom seen from above, so that a stamp on its crown is in view.
const char* kSmallTooth = R"(
  <Viewpoint position="0 0.03 0" orientation="1 0 0 -1.5707963" fieldOfView="0.5"/>
  <VolumeObject url='"phantom:tooth?size=128,128,88"' isoValue="700"/>)";

// At 128 pixels a voxel of the small tooth covers more than 1.5 pixels and
// the every-voxel mesh is drawn; at 80 and 48 less, and an averaged one is
// (VolumeMesh's levels 1 and 2), which milling must keep as current.
class IncrementalUpdate : public ::testing::TestWithParam<int> {};

TEST_P(IncrementalUpdate, DrawsWhatAFullRebuildDraws) {
  ScratchDir dir;
  LoadResult r = loadSceneFile(dir.write("t.x3d", x3d(kSmallTooth)), builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  auto incremental = createSceneRenderer(*r.scene, sized(GetParam()));
  auto full = createSceneRenderer(*r.scene, sized(GetParam()));
  // A level is meshed when first drawn (VolumeMesh), and milling keeps the drawn one current.
  incremental->render(std::nullopt);
  full->render(std::nullopt);
  const RendererStats start = incremental->stats();
  EXPECT_EQ(start.level, GetParam() == 128 ? 0 : GetParam() == 80 ? 1 : 2) << "the level of detail drawn";
  ASSERT_GT(start.triangles, 1000u);

  VoxelScene hs(*r.scene);
  // Down from the top onto the crown until the burr bites.
  glm::dvec3 p(0.0, hs.volume(0).voxels->halfSize().y, 0.0);
  while (!hs.inside(p) && p.y > 0.0) p.y -= 1e-4;
  ASSERT_GT(hs.mill(p, 0.6e-3), 0.0);
  const std::vector<BlockOrigin> blocks = hs.volume(0).changed.origins();
  incremental->volumeChanged(0, blocks);
  full->rebuildVolume(0);

  const RendererStats after = incremental->stats();
  EXPECT_GT(after.chunkUploads, start.chunkUploads);
  // A coarse level has a few chunks, most of which a stamp touches.
  EXPECT_LT(after.chunkUploads - start.chunkUploads, GetParam() == 128 ? start.chunks / 2 : start.chunks)
      << "an update re-uploads only touched chunks";
  EXPECT_EQ(after.triangles, full->stats().triangles);
  incremental->render(std::nullopt);
  full->render(std::nullopt);
  EXPECT_EQ(incremental->readPixels().rgba, full->readPixels().rgba);
}

INSTANTIATE_TEST_SUITE_P(SceneRenderer, IncrementalUpdate, ::testing::Values(128, 80, 48));

TEST(SceneRenderer, ClipPlaneCutsItsSiblingsOnly) {
  // Two boxes side by side; the ClipPlane inside the left Transform keeps y <= 0
  // of the left box only. Seen from +Z.
  ScratchDir dir;
  LoadResult r = loadSceneFile(dir.write("c.x3d", x3d(R"(
    <Viewpoint position="0 0 5" fieldOfView="0.8"/>
    <Background skyColor="0 0 0"/>
    <Transform translation="-0.6 0 0">
      <ClipPlane plane="0 -1 0 0"/>
      <Shape><Appearance><Material diffuseColor="1 0 0"/></Appearance><Box size="1 1 1"/></Shape>
    </Transform>
    <Transform translation="0.6 0 0">
      <Shape><Appearance><Material diffuseColor="0 1 0"/></Appearance><Box size="1 1 1"/></Shape>
    </Transform>)")),
                               builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  auto renderer = createSceneRenderer(*r.scene, sized(128));
  renderer->render(std::nullopt);
  const Image img = renderer->readPixels();
  const Camera cam = renderer->camera();
  auto px = [&](double x, double y) {
    const glm::dvec3 p = cam.project({x, y, 0.5});
    return img.at(int(p.x), int(p.y));
  };
  EXPECT_GT(px(-0.6, -0.3).r, 100) << "left box below the plane stays";
  EXPECT_EQ(px(-0.6, 0.3).r, 0) << "left box above the plane is cut away";
  EXPECT_GT(px(0.6, 0.3).g, 100) << "the plane does not reach the right box";
}

TEST(SceneRenderer, UnknownViewpointNameIsAClearError) {
  ScratchDir dir;
  LoadResult r = loadSceneFile(dir.write("v.x3d", x3d(R"(<Viewpoint DEF="Side"/>)")), builtinRegistry());
  ASSERT_TRUE(r.ok());
  RendererOptions o;
  o.viewpoint = "Top";
  try {
    createSceneRenderer(*r.scene, o);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'Top'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Side"), std::string::npos) << e.what();
  }
}

}  // namespace

// The haptic scene and the graphics view take their volumes from one walk:
// the same volumes, in the same order, at the same place, under Transforms,
// a USE and an Inline-free nesting; and a ClipPlane reaches only its siblings.
TEST(SceneWalk, HapticsAndGraphicsSeeTheSameVolumesInTheSameOrder) {
  ScratchDir dir;
  LoadResult r = loadSceneFile(dir.write("w.x3d", x3d(R"(
    <Transform translation="0.01 0 0" scale="2 2 2">
      <ClipPlane plane="0 -1 0 0"/>
      <VolumeObject DEF="A" url='"phantom:tooth?size=16,16,12"'/>
    </Transform>
    <Group>
      <Transform rotation="0 1 0 1.5707963" translation="0 0.02 0">
        <VolumeObject DEF="B" url='"phantom:tooth?size=12,12,8"'/>
      </Transform>
    </Group>
    <Transform translation="-0.03 0 0"><VolumeObject USE="A"/></Transform>)")),
                               builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  VoxelScene haptic(*r.scene);
  const SceneView view = readSceneView(*r.scene);
  ASSERT_EQ(haptic.volumeCount(), 3u);
  ASSERT_EQ(view.volumes.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(view.volumes[i].voxels, haptic.volume(i).voxels) << "volume " << i;
    EXPECT_EQ(view.volumes[i].localToWorld, haptic.placement(i).localToWorld) << "volume " << i;
  }
  EXPECT_EQ(haptic.volume(0).voxels, haptic.volume(2).voxels) << "USE shares the node's voxels";
  EXPECT_NE(haptic.volume(0).voxels, haptic.volume(1).voxels);
  EXPECT_NEAR(haptic.placement(0).worldPerLocal, 2.0, 1e-12);
  EXPECT_EQ(view.volumes[0].clipPlanes.size(), 1u) << "the ClipPlane clips its sibling";
  EXPECT_TRUE(view.volumes[1].clipPlanes.empty()) << "and nothing outside its Transform";
  EXPECT_TRUE(view.volumes[2].clipPlanes.empty());
}

// X3D's default viewpoint sits 10 m away: a millimetre tooth would be a dot
// (or nothing). Without a Viewpoint the scene is framed, and the tooth fills
// a good part of the picture.
TEST(SceneView, SceneWithoutViewpointIsFramedNotBlack) {
  ScratchDir dir;
  LoadResult r = loadSceneFile(dir.write("novp.x3d", x3d(R"(
    <Background skyColor="0 0 0"/>
    <VolumeObject url='"phantom:tooth?size=48,48,32"'/>)")),
                               builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  const SceneView view = readSceneView(*r.scene);
  EXPECT_TRUE(view.framed);
  EXPECT_TRUE(view.viewpoints.empty());
  auto renderer = createSceneRenderer(*r.scene, sized(128));
  renderer->render(std::nullopt);
  const Image img = renderer->readPixels();
  int lit = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) lit += img.at(x, y).r + img.at(x, y).g > 40 ? 1 : 0;
  EXPECT_GT(lit, img.width * img.height / 20) << "the framed tooth covers over 5 % of the image";
  EXPECT_LT(lit, img.width * img.height * 9 / 10) << "and fits inside it";
}

TEST(SceneView, ViewpointsAreListedByDescriptionOrDefName) {
  ScratchDir dir;
  LoadResult r = loadSceneFile(dir.write("vps.x3d", x3d(R"(
    <Viewpoint DEF="A" description="From the side" position="0 0 0.05"/>
    <Transform translation="0 0.01 0"><Viewpoint DEF="B" position="0 0 0.05" centerOfRotation="0 0.001 0"/></Transform>
    <Viewpoint position="0 0 1"/>)")),
                               builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  const SceneView view = readSceneView(*r.scene);
  ASSERT_EQ(view.viewpoints.size(), 3u);
  EXPECT_EQ(view.viewpoints[0].name, "From the side");
  EXPECT_EQ(view.viewpoints[1].name, "B");
  EXPECT_EQ(view.viewpoints[2].name, "Viewpoint 3");
  EXPECT_NEAR(view.viewpoints[1].view.position.y, 0.01, 1e-9) << "in world coordinates";
  EXPECT_TRUE(view.viewpoints[1].hasCenterOfRotation);
  EXPECT_NEAR(view.viewpoints[1].centerOfRotation.y, 0.011, 1e-9);
  EXPECT_FALSE(view.framed);
}

// EXAMINE navigation: the camera orbits and dollies about a centre and pans with it.
TEST(ExamineNavigator, TurnsZoomsAndPansAboutTheCentre) {
  ViewSpec start;
  start.position = glm::dvec3(0.0, 0.0, 0.06);
  ExamineNavigator nav;
  nav.reset(start, glm::dvec3(0.0, 0.001, 0.0));
  EXPECT_NEAR(nav.distance(), 0.06, 1e-12);
  EXPECT_NEAR(nav.centre().y, 0.0, 1e-12) << "the centre is put on the line of sight: no jump";
  nav.rotate(100.0, 0.0, 200);  // half the height: a quarter turn about +Y
  const ViewSpec turned = nav.view();
  EXPECT_NEAR(glm::length(turned.position - nav.centre()), 0.06, 1e-9);
  EXPECT_NEAR(turned.position.x, -0.06, 1e-9) << "dragging right brings the scene's right side to the front";
  EXPECT_NEAR(glm::dot(glm::mat3_cast(turned.orientation) * glm::dvec3(0, 1, 0), glm::dvec3(0, 1, 0)), 1.0, 1e-9)
      << "a horizontal drag keeps the horizon level";
  nav.zoom(1.0);
  EXPECT_NEAR(nav.distance(), 0.054, 1e-9);
  const glm::dvec3 before = nav.centre();
  nav.pan(0.0, 50.0, 200);  // dragging down moves the scene down: the camera goes up
  EXPECT_GT(nav.centre().y, before.y);
  EXPECT_NEAR(glm::length(nav.view().position - nav.centre()), 0.054, 1e-9);
}

// The mouse as a device: the burr goes under the cursor at its own depth.
TEST(PointerTool, BurrFollowsTheCursorOnItsPlaneAndPushesInDepth) {
  ViewSpec v;
  v.position = glm::dvec3(0.0, 0.0, 0.06);
  const Camera cam = makeCamera(v, 400, 300, 0.01, 1.0);
  Pose start;
  start.position = glm::dvec3(0.002, 0.003, 0.0);
  PointerTool tool(start, 1e-3);
  const glm::dvec3 px = cam.project(start.position);
  tool.follow(cam, px.x, px.y);
  EXPECT_NEAR(glm::length(tool.pose().position - start.position), 0.0, 1e-9) << "no motion, no change";
  tool.follow(cam, 200.0, 150.0);  // the image centre
  EXPECT_NEAR(tool.pose().position.x, 0.0, 1e-9);
  EXPECT_NEAR(tool.pose().position.y, 0.0, 1e-9);
  EXPECT_NEAR(tool.pose().position.z, 0.0, 1e-9) << "the burr stays on the plane through it facing the camera";
  tool.push(cam, 2.0);
  EXPECT_NEAR(tool.pose().position.z, -0.002, 1e-9) << "two notches away from the viewer";
  tool.turn(cam, 0.0, 150.0);  // half the height: a quarter turn about the screen's right axis
  EXPECT_NEAR(std::abs(tool.pose().shaftDirection().z), 1.0, 1e-9);
}

// A ClipPlane switched off while running (by a route) reaches the drawing:
// the drawer takes the fresh cut layout and keeps the user's own plane.
TEST(SceneDrawer, AdoptsChangedClipPlanesKeepingTheUserCut) {
  ScratchDir dir;
  LoadResult r = loadSceneFile(dir.write("cut.x3d", x3d(R"(
    <Group>
      <ClipPlane DEF="Cut" plane="0 -1 0 0"/>
      <VolumeObject url='"phantom:tooth?size=16,16,12"'/>
    </Group>)")),
                               builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  GlContext context(32, 32);
  SceneDrawer drawer(readSceneView(*r.scene));
  ASSERT_EQ(drawer.cutPlanes().size(), 1u);
  const int user = drawer.addUserCut(glm::dvec3(0, 0, 1));
  drawer.cutPlanes()[std::size_t(user)].enabled = true;
  ASSERT_EQ(drawer.scene().volumes[0].cuts.size(), 2u);

  dynamic_cast<ClipPlane&>(*r.scene->def("Cut")).enabled.set(false);
  ASSERT_TRUE(drawer.adoptCuts(readSceneView(*r.scene)));
  ASSERT_EQ(drawer.cutPlanes().size(), 1u) << "the scene's plane is gone, the user's stays";
  EXPECT_TRUE(drawer.cutPlanes()[0].user);
  EXPECT_TRUE(drawer.cutPlanes()[0].enabled);
  EXPECT_EQ(drawer.scene().volumes[0].cuts, std::vector<int>{0});

  dynamic_cast<ClipPlane&>(*r.scene->def("Cut")).enabled.set(true);
  ASSERT_TRUE(drawer.adoptCuts(readSceneView(*r.scene)));
  EXPECT_EQ(drawer.cutPlanes().size(), 2u);
  EXPECT_EQ(drawer.scene().volumes[0].cuts, (std::vector<int>{0, 1}));
  drawer.draw(32, 32, {});
  GlContext::check("drawing after adopting cuts");
}

// The drawn burr head follows MillTool.shape: a taper is narrower at its
// cutting end (below, the shaft pointing up) than at its shank end, an
// inverted cone wider, a cylinder the same.
TEST(SceneDrawer, DrawsTheBurrHeadsShape) {
  ScratchDir dir;
  LoadResult r = loadSceneFile(dir.write("tool.x3d", x3d(R"(
    <Background skyColor="0 0 0"/>
    <Viewpoint position="0 0 0.03" fieldOfView="0.4"/>)")),
                               builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  auto renderer = createSceneRenderer(*r.scene, sized(256));
  for (BurrShape shape : {BurrShape::Cylinder, BurrShape::Taper, BurrShape::InvertedCone}) {
    ToolView tool;
    tool.geometry = ToolGeometry{2e-3, 0.2e-3, 6e-3};
    tool.geometry.shape = shape;
    tool.geometry.tipLength = 4e-3;
    tool.geometry.tipEndRadius = 0.8e-3;
    tool.pose = Pose{{0, 0, 0}, glm::dquat(1, 0, 0, 0)};
    renderer->render(tool);
    const Image img = renderer->readPixels();
    // Lit width of each row (image rows run top to bottom); head rows are
    // wider than the shaft's.
    std::vector<int> widths;
    for (int y = 0; y < img.height; ++y) {
      int lo = img.width, hi = -1;
      for (int x = 0; x < img.width; ++x)
        if (img.at(x, y).r + img.at(x, y).g + img.at(x, y).b > 60) lo = std::min(lo, x), hi = std::max(hi, x);
      if (hi >= lo && hi - lo + 1 > 12) widths.push_back(hi - lo + 1);
    }
    ASSERT_GT(widths.size(), 20u) << burrShapeName(shape);
    const int top = widths[widths.size() / 8], bottom = widths[widths.size() * 7 / 8];  // shank end, cutting end
    std::printf("%s head drawn: %d px wide near the shank end, %d px near the cutting end\n",
                std::string(burrShapeName(shape)).c_str(), top, bottom);
    if (shape == BurrShape::Cylinder) {
      EXPECT_NEAR(top, bottom, 2);
    } else if (shape == BurrShape::Taper) {
      EXPECT_GT(top, bottom + 10);
    } else if (shape == BurrShape::InvertedCone) {
      EXPECT_GT(bottom, top + 10);
    }
  }
}

// A visible assessment region is drawn see-through over what is behind it
// (issue 18, part 3); a Material's transparency blends any shape the same way.
TEST(SceneRenderer, VisibleRegionsAreSeeThrough) {
  auto centreOf = [](const std::string& front) {
    ScratchDir dir;
    LoadResult r = loadSceneFile(dir.write("t.x3d", x3d(R"(
      <Viewpoint position="0 0 5" fieldOfView="0.8"/>
      <Background skyColor="0 0 0"/>
      <Shape><Appearance><Material diffuseColor="0 1 0"/></Appearance><Box size="1 1 1"/></Shape>)" + front)),
                                 builtinRegistry());
    EXPECT_TRUE(r.ok()) << r.report();
    auto renderer = createSceneRenderer(*r.scene, sized(64));
    renderer->render(std::nullopt);
    const Image img = renderer->readPixels();
    return img.at(32, 32);
  };
  const std::string redBox =
      R"(<Transform translation="0 0 1"><Shape><Appearance><Material diffuseColor="1 0 0"/></Appearance>)"
      R"(<Box size="0.5 0.5 0.5"/></Shape></Transform>)";
  const auto hidden = centreOf("<ForbiddenRegion name='r'>" + redBox + "</ForbiddenRegion>");
  EXPECT_EQ(hidden.r, 0) << "a region is not drawn by default";
  EXPECT_GT(hidden.g, 100);
  const auto shown = centreOf("<ForbiddenRegion name='r' visible='true'>" + redBox + "</ForbiddenRegion>");
  EXPECT_GT(shown.r, 40) << "the region's red is drawn";
  EXPECT_GT(shown.g, 40) << "and the green box shows through it";
  const std::string behind = std::string(R"(<ForbiddenRegion name='r' visible='true'><Transform translation="0 0 -1">)") +
                             R"(<Shape><Appearance><Material diffuseColor="1 0 0"/></Appearance>)" +
                             R"(<Box size="0.5 0.5 0.5"/></Shape></Transform></ForbiddenRegion>)";
  const auto hiddenInside = centreOf(behind);
  EXPECT_GT(hiddenInside.r, 40) << "a region behind (or inside) an opaque shape still shows through it";
  const auto opaque = centreOf(redBox);
  EXPECT_GT(opaque.r, 100);
  EXPECT_EQ(opaque.g, 0) << "an opaque shape hides what is behind";
  std::string halfRed = redBox;
  halfRed.replace(halfRed.find("diffuseColor=\"1 0 0\""), 20, "diffuseColor=\"1 0 0\" transparency=\"0.5\"");
  const auto blended = centreOf(halfRed);
  EXPECT_GT(blended.r, 40);
  EXPECT_GT(blended.g, 40) << "Material.transparency is drawn";
}

// What is drawn follows the event cascade: a TimeSensor moves a red ball
// from left to right through a PositionInterpolator, the renderer adopts the
// new view (as the graphics thread of a run does), and a Switch set to -1
// hides it.
TEST(SceneRenderer, DrawingFollowsAnAnimatedTransformAndASwitch) {
  ScratchDir dir;
  LoadResult r = loadSceneFile(dir.write("anim.x3d", x3d(R"(
    <Viewpoint position="0 0 1" fieldOfView="0.8"/>
    <Background skyColor="0 0 0"/>
    <Switch DEF="Show" whichChoice="0">
      <Transform DEF="Mover" translation="0 0.3 0">
        <Shape><Appearance><Material diffuseColor="1 0 0" emissiveColor="1 0 0"/></Appearance><Sphere radius="0.05"/></Shape>
      </Transform>
    </Switch>
    <TimeSensor DEF="Clock" cycleInterval="1"/>
    <PositionInterpolator DEF="Path" key="0 1" keyValue="-0.2 0 0, 0.2 0 0"/>
    <ROUTE fromNode="Clock" fromField="fraction_changed" toNode="Path" toField="set_fraction"/>
    <ROUTE fromNode="Path" fromField="value_changed" toNode="Mover" toField="set_translation"/>)")),
                               builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  // Mean x of the red pixels, and how many there are.
  auto red = [](const Image& img) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        if (const auto p = img.at(x, y); p.r > 150 && p.g < 80 && p.b < 80) sum += x + 0.5, ++n;
    return std::pair{n ? sum / n : -1.0, n};
  };
  EventClock events(*r.scene);
  events.tick(0.0);
  auto renderer = createSceneRenderer(*r.scene, sized(96));
  renderer->render(std::nullopt);
  const auto [left, leftCount] = red(renderer->readPixels());
  ASSERT_GT(leftCount, 20);
  EXPECT_NEAR(left, renderer->camera().project({-0.2, 0.0, 0.0}).x, 2.0) << "at t = 0 the ball is on the left";

  events.advanceTo(1.0);
  ASSERT_TRUE(renderer->sceneChanged(readSceneView(*r.scene)));
  renderer->render(std::nullopt);
  const auto [right, rightCount] = red(renderer->readPixels());
  ASSERT_GT(rightCount, 20);
  EXPECT_NEAR(right, renderer->camera().project({0.2, 0.0, 0.0}).x, 2.0) << "at t = 1 s it is on the right";

  dynamic_cast<Switch&>(*r.scene->def("Show")).whichChoice.set(-1);
  ASSERT_TRUE(renderer->sceneChanged(readSceneView(*r.scene)));
  renderer->render(std::nullopt);
  EXPECT_EQ(red(renderer->readPixels()).second, 0) << "the Switch chooses nothing";
}

// Issue 17's drawn standard nodes: mesh geometry, Cone, Text, lights and
// ImageTexture appear where the scene puts them.
namespace {

Image drawScene(ScratchDir& dir, const std::string& body, int side = 96) {
  LoadResult r = loadSceneFile(dir.write("s.x3d", x3d(body)), builtinRegistry());
  EXPECT_TRUE(r.ok()) << r.report();
  if (!r.ok()) return {};
  auto renderer = createSceneRenderer(*r.scene, sized(side));
  renderer->render(std::nullopt);
  return renderer->readPixels();
}

// Pixels in [x0, x1) × [y0, y1) that pass `match`.
template <class Match> int countIn(const Image& img, int x0, int y0, int x1, int y1, Match match) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) n += match(img.at(x, y)) ? 1 : 0;
  return n;
}

bool isRed(glm::u8vec4 p) { return p.r > 150 && p.g < 60 && p.b < 60; }
bool isGreen(glm::u8vec4 p) { return p.g > 100 && p.r < 60 && p.b < 60; }
bool isWhite(glm::u8vec4 p) { return p.r > 150 && p.g > 150 && p.b > 150; }

const char* kCamera = R"(<Viewpoint position="0 0 3" fieldOfView="0.8"/><Background skyColor="0 0 0"/>)";

}  // namespace

TEST(SceneRenderer, DrawsFaceSetsConesAndText) {
  ScratchDir dir;
  const std::string shapes = std::string(kCamera) + R"(
    <Transform translation="-0.6 0.4 0"><Shape><Appearance><Material emissiveColor="1 0 0" diffuseColor="0 0 0"/></Appearance>
      <IndexedFaceSet coordIndex="0 1 2 3 -1"><Coordinate point="-0.2 -0.2 0, 0.2 -0.2 0, 0.2 0.2 0, -0.2 0.2 0"/></IndexedFaceSet>
    </Shape></Transform>
    <Transform translation="0.6 0.4 0"><Shape><Appearance><Material emissiveColor="0 0.8 0" diffuseColor="0 0 0"/></Appearance>
      <Cone bottomRadius="0.2" height="0.4"/></Shape></Transform>)";
  const std::string label = R"(
    <Transform translation="0 -0.5 0"><Shape><Appearance><Material emissiveColor="1 1 1" diffuseColor="0 0 0"/></Appearance>
      <Text string='"MillSim"'><FontStyle family='"SANS"' size="0.3" justify='"MIDDLE" "MIDDLE"'/></Text></Shape></Transform>)";
  const Image img = drawScene(dir, shapes + label);
  ASSERT_EQ(img.width, 96);
  // The face set fills the upper left, the cone the upper right, the text the bottom middle.
  EXPECT_GT(countIn(img, 0, 0, 48, 48, isRed), 150) << "IndexedFaceSet";
  EXPECT_EQ(countIn(img, 48, 0, 96, 96, isRed), 0);
  const int cone = countIn(img, 48, 0, 96, 48, isGreen);
  EXPECT_GT(cone, 60) << "Cone";
  // A cone is narrower at its apex: fewer green pixels in its top row half than its bottom.
  EXPECT_LT(countIn(img, 48, 0, 96, 22, isGreen), countIn(img, 48, 22, 96, 48, isGreen));
  const int text = countIn(img, 0, 60, 96, 96, isWhite);
  EXPECT_GT(text, 40) << "Text draws glyphs";
  EXPECT_LT(text, 1000) << "glyphs, not a filled box";
  const Image none = drawScene(dir, shapes);
  EXPECT_EQ(countIn(none, 0, 60, 96, 96, isWhite), 0);
  // Two strings draw differently, centred either way (justify MIDDLE): mean x near the middle.
  double sum = 0;
  int n = 0;
  for (int y = 60; y < 96; ++y)
    for (int x = 0; x < 96; ++x)
      if (isWhite(img.at(x, y))) sum += x + 0.5, ++n;
  EXPECT_NEAR(sum / n, 48.0, 6.0) << "justify MIDDLE centres the line";
}

TEST(SceneRenderer, SceneLightsReplaceTheHeadlight) {
  ScratchDir dir;
  const std::string box = std::string(kCamera) + R"(<NavigationInfo headlight="false"/>
    <Shape><Appearance><Material diffuseColor="1 1 1" ambientIntensity="0"/></Appearance><Box size="1 1 1"/></Shape>)";
  auto centre = [&](const std::string& extra) { return drawScene(dir, box + extra, 32).at(16, 16); };
  EXPECT_LT(centre("").r, 10) << "headlight FALSE and no light: dark";
  const auto lit = centre(R"(<DirectionalLight direction="0 0 -1" color="1 0.5 0"/>)");
  EXPECT_GT(lit.r, 200) << "a DirectionalLight shining at the face";
  EXPECT_NEAR(lit.g, lit.r / 2, 20) << "in its colour";
  EXPECT_LT(centre(R"(<DirectionalLight direction="0 0 1"/>)").r, 10) << "shining from behind";
  EXPECT_LT(centre(R"(<DirectionalLight direction="0 0 -1" on="false"/>)").r, 10) << "off";
  EXPECT_GT(centre(R"(<PointLight location="0 0 2"/>)").r, 150) << "a PointLight in front";
  EXPECT_LT(centre(R"(<PointLight location="0 0 2" radius="1"/>)").r, 10) << "beyond its radius";
  EXPECT_GT(centre(R"(<SpotLight location="0 0 2" direction="0 0 -1" cutOffAngle="0.3"/>)").r, 150) << "a spot at the face";
  EXPECT_LT(centre(R"(<SpotLight location="0 0 2" direction="1 0 0" cutOffAngle="0.3"/>)").r, 10) << "a spot turned away";
}

TEST(SceneRenderer, ImageTextureWrapsTheImageOnAShape) {
  ScratchDir dir;
  // 2 × 2: red, green on the top row; blue, white below (PNG rows run from the top).
  Image checker{2, 2, {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255}};
  writePng(checker, dir.path() / "checker.png");
  const Image img = drawScene(dir, std::string(kCamera) + R"(
    <Shape><Appearance><Material emissiveColor="0 0 0"/><ImageTexture url='"checker.png"' repeatS="false" repeatT="false"/></Appearance>
      <Box size="1.6 1.6 0.01"/></Shape>)");
  ASSERT_EQ(img.width, 96);
  // The face spans about the middle two thirds; its quadrants show the image's pixels, upright.
  const auto topLeft = img.at(30, 30), topRight = img.at(66, 30), bottomLeft = img.at(30, 66), bottomRight = img.at(66, 66);
  EXPECT_TRUE(topLeft.r > 120 && topLeft.g < 60 && topLeft.b < 60) << int(topLeft.r) << " " << int(topLeft.g) << " " << int(topLeft.b);
  EXPECT_TRUE(topRight.g > 120 && topRight.r < 60 && topRight.b < 60);
  EXPECT_TRUE(bottomLeft.b > 120 && bottomLeft.r < 60 && bottomLeft.g < 60);
  EXPECT_TRUE(bottomRight.r > 120 && bottomRight.g > 120 && bottomRight.b > 120);
  // JPEG too (a grey one modulates the material's colour).
  const Image jpeg = drawScene(dir, std::string(kCamera) + R"(
    <Shape><Appearance><Material diffuseColor="1 0 0"/><ImageTexture url='"/nonexistent.jpg" ")" MILLSIM_SOURCE_DIR
                                                    R"(/tests/data/textures/grey-ramp.jpg"'/></Appearance>
      <Box size="1.6 1.6 0.01"/></Shape>)");
  const auto left = jpeg.at(26, 48), right = jpeg.at(70, 48);
  EXPECT_LT(left.r + 40, right.r) << "the ramp runs dark to light, left to right";
  EXPECT_LT(right.g, 40) << "grey modulates the red material";
}

TEST(ImageTexture, AMissingOrWrongFileIsAWarningAtTheNode) {
  ScratchDir dir;
  dir.write("not-an-image.png", "hello");
  LoadResult r = loadSceneFile(dir.write("s.x3d", x3d(R"(
<Shape><Appearance><ImageTexture url='"missing.png" "not-an-image.png" "https://example.org/a.png"'/></Appearance><Box/></Shape>)")),
                               builtinRegistry());
  ASSERT_TRUE(r.ok()) << r.report();
  const std::string report = r.report();
  EXPECT_NE(report.find("s.x3d:5:20: warning: ImageTexture has no usable image"), std::string::npos) << report;
  EXPECT_NE(report.find("'not-an-image.png': is neither a PNG nor a JPEG file"), std::string::npos) << report;
  EXPECT_NE(report.find("not fetched (MillSim reads local files only)"), std::string::npos) << report;
}

// Issue 15, part 7: the tooth's smooth surfaces are drawn smooth. The root
// of the default lesson, seen from the side, used to be shaded in terraces
// ("wood grain"): the phantom's density was quadratic across its one-voxel
// surface ramp where the dentin's ramp lay on the surface's, and the normals
// were plain central differences. Measured as the mean |second difference| of
// brightness down each column of the root: 16 before, 1.9 now, and 5.1 or
// 5.4 with either of the two changes alone.
// Mean |second difference| of brightness down each column of the default
// lesson's tooth between two points (metres, the lesson's frame), over the
// pixels that show the tooth: terraces ("wood grain") make it large.
double shadingRoughness(const glm::dvec3& topLeft, const glm::dvec3& bottomRight, int size, int* counted) {
  LoadResult r = loadSceneFile(std::filesystem::path(MILLSIM_SOURCE_DIR) / "x3d/default.x3d", builtinRegistry());
  EXPECT_TRUE(r.ok()) << r.report();
  auto renderer = createSceneRenderer(*r.scene, sized(size));
  renderer->render(std::nullopt);
  const Image img = renderer->readPixels();
  const Camera& cam = renderer->camera();
  const glm::dvec3 a = cam.project(topLeft), b = cam.project(bottomRight);
  const auto bg = img.at(2, 2);
  auto brightness = [&](int x, int y) { const auto p = img.at(x, y); return (p.r + p.g + p.b) / 3.0; };
  auto isTooth = [&](int x, int y) {
    const auto p = img.at(x, y);
    return std::abs(int(p.r) - int(bg.r)) + std::abs(int(p.g) - int(bg.g)) + std::abs(int(p.b) - int(bg.b)) > 30;
  };
  double sum = 0.0;
  int n = 0;
  for (int x = int(a.x); x <= int(b.x); x += 2)
    for (int y = int(a.y) + 1; y < int(b.y) - 1; ++y)
      if (isTooth(x, y - 1) && isTooth(x, y) && isTooth(x, y + 1))
        sum += std::abs(brightness(x, y + 1) - 2.0 * brightness(x, y) + brightness(x, y - 1)), ++n;
  *counted = n;
  return n > 0 ? sum / n : 0.0;
}

// Issue 15, part 7: the tooth's smooth surfaces are drawn smooth. The root
// of the default lesson, seen from the side, used to be shaded in terraces
// ("wood grain"): the phantom's density was quadratic across its one-voxel
// surface ramp where the dentin's ramp lay on the surface's, and the normals
// were plain central differences. Measured as the mean |second difference| of
// brightness down each column of the root: 16 before, 1.9 now, and 5.1 or
// 5.4 with either of the two changes alone.
TEST(SceneRenderer, TheRootIsShadedSmoothly) {
  int n = 0;
  // The root's middle, 2 to 8 mm below the tooth's centre, 2.5 mm either side of its axis.
  const double rough = shadingRoughness({-2.5e-3, -2e-3, 3e-3}, {2.5e-3, -8e-3, 3e-3}, 512, &n);
  ASSERT_GT(n, 500) << "the root is in the picture";
  EXPECT_LT(rough, 3.5) << "terraces on the root: mean |second difference| of brightness " << rough;
  std::cout << "root roughness " << rough << " over " << n << " pixels\n";
}

// The crown and the neck, drawn at 1024 pixels (the window's size), still
// showed one ring per voxel on their gentle slopes: the Sobel gradient of a
// one-voxel ramp leans with where the surface crosses the samples. The
// normals are now taken of the samples smoothed 1-2-1 along every axis
// (IsoSurface.cpp): 1.18 before, 0.71 after.
TEST(SceneRenderer, TheCrownIsShadedSmoothly) {
  int n = 0;
  const double crown = shadingRoughness({-3e-3, 6e-3, 4e-3}, {3e-3, 0.5e-3, 4e-3}, 1024, &n);
  ASSERT_GT(n, 2000) << "the crown is in the picture";
  EXPECT_LT(crown, 0.9) << "terraces on the crown: mean |second difference| of brightness " << crown;
}

// X3D's scoping: a DirectionalLight that is not global lights its siblings
// and their descendants only (wherever it stands among them); a global one
// lights everything.
TEST(SceneRenderer, ADirectionalLightLightsOnlyItsSiblings) {
  ScratchDir dir;
  auto shot = [&](const std::string& global) {
    return drawScene(dir, std::string(kCamera) + R"(<NavigationInfo headlight="false"/>
      <Transform translation="-0.6 0 0">
        <Shape><Appearance><Material diffuseColor="1 1 1" ambientIntensity="0"/></Appearance><Box size="0.8 0.8 0.8"/></Shape>
        <DirectionalLight direction="0 0 -1" global=")" + global + R"("/>
      </Transform>
      <Transform translation="0.6 0 0">
        <Shape><Appearance><Material diffuseColor="1 1 1" ambientIntensity="0"/></Appearance><Box size="0.8 0.8 0.8"/></Shape>
      </Transform>)",
                     64);
  };
  const Image scoped = shot("false");
  EXPECT_GT(scoped.at(20, 32).r, 150) << "its sibling (before it in the file) is lit";
  EXPECT_LT(scoped.at(44, 32).r, 10) << "the other Transform's box is not";
  const Image global = shot("true");
  EXPECT_GT(global.at(20, 32).r, 150);
  EXPECT_GT(global.at(44, 32).r, 150) << "global TRUE lights everything";
}
