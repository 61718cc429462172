// H3DAPI's device conventions (issue 17, part 5): AnyDevice opens what there
// is — an ARES, else the window's mouse, else a clear error — and a 4x4
// positionCalibration matrix is read when it translates and scales uniformly,
// refused with what it does otherwise.
#include <gtest/gtest.h>

#include "SceneText.h"
#include "millsim/devices/AnyDevice.h"
#include "millsim/devices/HandDevice.h"

using namespace millsim;
using namespace millsim::test;

namespace {

std::string scene(const std::string& units, const std::string& body) {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<X3D profile=\"Immersive\" version=\"4.0\">\n<head>" + units +
         "</head>\n<Scene>\n" + body + "\n</Scene>\n</X3D>\n";
}

TEST(PositionCalibration, AnH3dTranslationMatrixIsTheOffset) {
  LoadResult r = load(scene("", R"(<HandDevice positionCalibration="1 0 0 0.01  0 1 0 0.02  0 0 1 -0.03  0 0 0 1"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  EXPECT_EQ(onlyNode<HandDevice>(r).positionCalibration.get(), glm::vec3(0.01f, 0.02f, -0.03f));
  LoadResult mm = load(scene(R"(<unit category="length" name="mm" conversionFactor="0.001"/>)",
                             R"(<HandDevice positionCalibration="1 0 0 10  0 1 0 0  0 0 1 0  0 0 0 1"/>)"));
  ASSERT_TRUE(mm.ok()) << mm.report();
  EXPECT_EQ(onlyNode<HandDevice>(mm).positionCalibration.get(), glm::vec3(0.01f, 0.f, 0.f)) << "the translation is a length";
  LoadResult plain = load(scene("", R"(<HandDevice positionCalibration="0.1 0 0"/>)"));
  ASSERT_TRUE(plain.ok()) << plain.report();
  EXPECT_EQ(onlyNode<HandDevice>(plain).positionCalibration.get(), glm::vec3(0.1f, 0.f, 0.f)) << "MillSim's own form";
}

TEST(PositionCalibration, AUniformScaleInTheMatrixIsThePositionScale) {
  LoadResult r = load(scene("", R"(<HandDevice positionCalibration="2 0 0 0.01  0 2 0 0  0 0 2 0  0 0 0 1"/>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  const HandDevice& d = onlyNode<HandDevice>(r);
  EXPECT_EQ(d.positionCalibration.get(), glm::vec3(0.01f, 0.f, 0.f));
  EXPECT_EQ(d.positionScale.get(), 2.f);
  Pose raw;
  raw.position = glm::dvec3(0.001, 0.0, -0.002);
  EXPECT_NEAR(d.calibrate(raw).position.x, 0.012, 1e-9) << "scene = scale * raw + offset";
  EXPECT_NEAR(d.calibrate(raw).position.z, -0.004, 1e-9);
  LoadResult own = load(scene("", R"(<HandDevice positionScale="0.1" positionCalibration="1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1"/>)"));
  ASSERT_TRUE(own.ok()) << own.report();
  EXPECT_FLOAT_EQ(onlyNode<HandDevice>(own).positionScale.get(), 0.1f) << "a matrix that only translates keeps it";
}

TEST(PositionCalibration, AMatrixThatTurnsOrScalesUnevenlyIsRefusedSayingSo) {
  // A quarter turn about y.
  LoadResult r = load(scene("", R"(<HandDevice positionCalibration="0 0 1 0.01  0 1 0 0  -1 0 0 0  0 0 0 1"/>)"));
  ASSERT_FALSE(r.ok());
  const std::string e = firstError(r).str();
  EXPECT_NE(e.find("test.x3d:5:13: error: bad value"), std::string::npos) << e;
  EXPECT_NE(e.find("3x3 part is '0 0 1 0 1 0 -1 0 0'"), std::string::npos) << e;
  EXPECT_NE(e.find("positionScale='s' and positionCalibration='0.01 0 0'"), std::string::npos)
      << "what to write instead: " << e;
  LoadResult uneven = load(scene("", R"(<HandDevice positionCalibration="2 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1"/>)"));
  ASSERT_FALSE(uneven.ok());
  EXPECT_NE(firstError(uneven).message.find("read as a translation and a uniform scale"), std::string::npos) << uneven.report();
  LoadResult p = load(scene("", R"(<HandDevice positionCalibration="1 0 0 0  0 1 0 0  0 0 1 0  0 0 1 1"/>)"));
  ASSERT_FALSE(p.ok());
  EXPECT_NE(firstError(p).message.find("is a projection"), std::string::npos) << p.report();
  LoadResult n = load(scene("", R"(<HandDevice positionCalibration="1 0 0 0 0 1"/>)"));
  ASSERT_FALSE(n.ok()) << "neither 3 nor 16 numbers";
}

TEST(AnyDevice, FollowsTheMouseWhenThereIsNoAres) {
  LoadResult r = load(scene("", R"(<AnyDevice position="0 0.01 0" forceLimit="5"><MillTool/><SurfacePointRenderer/></AnyDevice>)"));
  ASSERT_TRUE(r.ok()) << r.report();
  const AnyDevice& any = onlyNode<AnyDevice>(r);
  EXPECT_EQ(any.startPose().position, glm::dvec3(0.0, 0.01f, 0.0)) << "the mouse starts where the scene says";
  Pose hand;
  hand.position = glm::dvec3(0.001, 0.002, 0.003);
  PointerInput pointer(hand);
  DriverOptions withWindow;
  withWindow.pointer = &pointer;
  // No ARES is attached here (the device tests mock one under umockdev).
  auto driver = any.openDriver(withWindow);
  ASSERT_TRUE(driver);
  EXPECT_TRUE(any.followsPointer());
  EXPECT_EQ(driver->read(0.0, 0.001).pose.position, hand.position) << "it reads the window's pointer";
  try {
    (void)any.openDriver(DriverOptions{});
    FAIL() << "no ARES and no window: an error";
  } catch (const DeviceError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("AnyDevice found no device to open: no ARES ("), std::string::npos) << what;
    EXPECT_NE(what.find("no window for the mouse"), std::string::npos) << what;
  }
}

}  // namespace
