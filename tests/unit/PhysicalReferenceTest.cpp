// The physical reference solver (measure/PhysicalReference.h) on cases whose
// answers are worked out by hand: a burr pressed into a half-space, a burr on a
// ball pushed obliquely, a tilted tool on a plane, a shaft resting on an edge,
// a tool in a drilled hole; and its convergence on every pose the suite uses.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "measure/PhysicalReference.h"
#include "measure/PhysicalScenes.h"

namespace {

using namespace millsim;
using namespace millsim::measure;

const ToolGeometry kTool{0.5e-3, 0.25e-3, 5e-3};
constexpr double kK = 2000.0, kKr = 0.1;  // BarbicRenderer's coupling defaults (N/m, N·m/rad)
constexpr double kPi = 3.14159265358979323846;

Material halfSpace() {
  return {{[](const glm::dvec3& p) { return p.y; }}};
}

double angleDeg(const glm::dquat& a, const glm::dquat& b) {
  return glm::length(rotationVector(a * glm::inverse(b))) * 180.0 / kPi;
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tol, const char* what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

// The burr's surface 0.2 mm into the surface (centre at r − d), shaft upright:
// pushed out along +Y by the penetration d, force k·d along +Y, no torque, orientation kept.
TEST(PhysicalReference, BurrPressedIntoHalfSpace) {
  const double d = 0.2e-3;
  const Pose device{{0.1e-3, kTool.tipRadius - d, 0.2e-3}, {1, 0, 0, 0}};
  for (double kr : {kKr, std::numeric_limits<double>::infinity()}) {
    const PhysicalPose p = constrainedPose(halfSpace(), kTool, device, {kK, kr});
    ASSERT_TRUE(p.converged) << "kr " << kr;
    EXPECT_LE(p.violation, 1e-10);
    expectNear(p.pose.position, device.position + glm::dvec3(0, d, 0), 1e-10, "constrained burr centre");
    expectNear(p.force, glm::dvec3(0, kK * d, 0), 1e-7, "force k·d along +n");
    EXPECT_LT(glm::length(p.torque), 1e-12);
    EXPECT_LT(angleDeg(p.pose.orientation, device.orientation), 1e-8);
    ASSERT_EQ(p.contacts.size(), 1u);
    expectNear(p.contacts[0].normal, {0, 1, 0}, 1e-7, "contact normal");
    expectNear(p.contacts[0].point, {0.1e-3, 0, 0.2e-3}, 1e-10, "contact point under the burr centre");
    EXPECT_NEAR(p.contacts[0].force, kK * d, 1e-7);
    EXPECT_LT(p.momentArm, 1e-9);  // the line of action passes through the burr centre
  }
}

// A burr on a plane with the shaft tilted 40° (shaft clear of the plane): the
// contact force passes through the burr centre, so the tool only translates.
TEST(PhysicalReference, TiltedToolOnPlaneOnlyTranslates) {
  const double d = 0.15e-3, tilt = 40.0 * kPi / 180.0;
  const Pose device{{0, kTool.tipRadius - d, 0}, glm::angleAxis(tilt, glm::dvec3(0, 0, 1))};
  const PhysicalPose p = constrainedPose(halfSpace(), kTool, device, {kK, kKr});
  ASSERT_TRUE(p.converged);
  expectNear(p.pose.position, {0, kTool.tipRadius, 0}, 1e-10, "burr resting on the plane");
  EXPECT_LT(angleDeg(p.pose.orientation, device.orientation), 1e-8);
  EXPECT_LT(glm::length(p.torque), 1e-12);
}

// A burr (sphere) pressed obliquely into a ball of radius R: the nearest
// non-penetrating centre is the device's projection onto the sphere of radius
// R + r, whatever the direction of approach.
TEST(PhysicalReference, SphereOnSphereProjectsRadially) {
  const double R = 2e-3;
  const Material ball{{[R](const glm::dvec3& p) { return glm::length(p) - R; }}};
  const glm::dvec3 xd = glm::normalize(glm::dvec3(0.3, 1.0, 0.2)) * (R + kTool.tipRadius - 0.25e-3) +
                        glm::dvec3(0.05e-3, 0, -0.04e-3);
  const Pose device{xd, {1, 0, 0, 0}};
  const PhysicalPose p = constrainedPose(ball, kTool, device, {kK, kKr});
  ASSERT_TRUE(p.converged);
  const glm::dvec3 expected = glm::normalize(xd) * (R + kTool.tipRadius);
  expectNear(p.pose.position, expected, 1e-10, "radial projection");
  expectNear(p.force, kK * (expected - xd), 1e-7, "force");
  // Stiffness-free: the force is along the ball's normal at the contact.
  EXPECT_GT(glm::dot(glm::normalize(p.force), glm::normalize(expected)), 1.0 - 1e-12);
}

// The shaft leaning on the edge of the quarter-space x < 0, y < 0 (the Z axis),
// the axis d inside the shaft's radius at s0 = 2.5 mm from the burr centre.
// By hand, with the orientation held (kr = ∞): the tool moves d along the
// edge's normal n = (cos θ, sin θ, 0); F = k·d·n; T = (q − x_c) × F with q on
// the edge: (s0·dir − ρ·n) × k·d·n = −k·d·s0·ẑ; moment arm s0.
TEST(PhysicalReference, ShaftOnEdgeByHand) {
  const Material edge{{[](const glm::dvec3& p) {
    if (p.x <= 0.0 && p.y <= 0.0) return std::max(p.x, p.y);
    return std::hypot(std::max(p.x, 0.0), std::max(p.y, 0.0));
  }}};
  const double d = 0.1e-3, s0 = 2.5e-3;
  for (double deg : {20.0, 45.0}) {
    const double th = deg * kPi / 180.0;
    const glm::dvec3 dir(-std::sin(th), std::cos(th), 0.0), n(std::cos(th), std::sin(th), 0.0);
    const glm::dvec3 xd = n * (kTool.shaftRadius - d) - dir * s0;
    const Pose device{xd, rotationBetween({0, 1, 0}, dir)};

    const PhysicalPose held = constrainedPose(edge, kTool, device, {kK, std::numeric_limits<double>::infinity()});
    ASSERT_TRUE(held.converged) << deg;
    expectNear(held.pose.position, xd + d * n, 1e-10, "moved d along the edge normal");
    expectNear(held.force, kK * d * n, 1e-7, "force");
    expectNear(held.torque, {0, 0, -kK * d * s0}, 1e-10, "torque −k·d·s0·ẑ");
    EXPECT_NEAR(held.momentArm, s0, 1e-9);
    ASSERT_EQ(held.contacts.size(), 1u);
    EXPECT_TRUE(held.contacts[0].onShaft);
    EXPECT_LT(std::hypot(held.contacts[0].point.x, held.contacts[0].point.y), 1e-10) << "contact on the edge";

    // With the coupling's rotational stiffness: to first order the tool moves u
    // along n and turns α about ẑ with u − α·s0 = d, minimising ½k·u² + ½kr·α²,
    // so the contact force is λ = d / (1/k + s0²/kr), the torque −λ·s0·ẑ.
    const PhysicalPose free = constrainedPose(edge, kTool, device, {kK, kKr});
    ASSERT_TRUE(free.converged) << deg;
    const double lambda = d / (1.0 / kK + s0 * s0 / kKr);
    EXPECT_NEAR(glm::length(free.force), lambda, 2e-3 * lambda);
    EXPECT_NEAR(free.torque.z, -lambda * s0, 2e-3 * lambda * s0);
    EXPECT_NEAR(free.momentArm, s0, 2e-3 * s0);
    EXPECT_LT(free.stationarity, 1e-6);
    // Stiffness-free: the line of action runs through the contact on the edge.
    ASSERT_EQ(free.contacts.size(), 1u);
    const glm::dvec3 q = free.contacts[0].point, a = free.actionPoint;
    EXPECT_LT(glm::length(glm::cross(q - a, free.actionAxis)), 1e-9) << "line of action through the contact";
  }
}

// A burr pressed past a convex edge along its bisector, the tool leaning the
// same way (the shaft clear): by hand the nearest pose out of the material is
// on either face, r + a from the device (a its depth along each face), not on
// the bisector, r + √2·a away, where a symmetric start would stay (a saddle).
TEST(PhysicalReference, PressedPastAConvexEdgeTheBurrSlidesOntoAFace) {
  const Material edge{{[](const glm::dvec3& p) {
    if (p.x <= 0.0 && p.y <= 0.0) return std::max(p.x, p.y);
    return std::hypot(std::max(p.x, 0.0), std::max(p.y, 0.0));
  }}};
  const double r = kTool.tipRadius, a = 0.3e-3;
  const Pose device{{-a, -a, 0.0}, rotationBetween({0, 1, 0}, glm::normalize(glm::dvec3(1, 1, 0)))};
  const PhysicalPose held = constrainedPose(edge, kTool, device, {kK, std::numeric_limits<double>::infinity()});
  ASSERT_TRUE(held.converged);
  EXPECT_NEAR(glm::length(held.pose.position - device.position), r + a, 1e-9) << "on a face, not the bisector";
  const double onSide = glm::length(held.pose.position - glm::dvec3(r, -a, 0.0));
  const double onTop = glm::length(held.pose.position - glm::dvec3(-a, r, 0.0));
  EXPECT_LT(std::min(onSide, onTop), 1e-9);
  EXPECT_NEAR(glm::length(held.force), kK * (r + a), 1e-6);
  // The other face is exactly as near: a renderer that slid onto it is measured against it.
  ASSERT_EQ(held.alternatives.size(), 1u);
  EXPECT_NEAR(glm::length(held.alternatives[0].pose.position - device.position), r + a, 1e-9);
  EXPECT_GT(glm::length(held.alternatives[0].pose.position - held.pose.position), 1e-4) << "the other face";
}

// A tool in a drilled hole (radius 0.6 mm, 1.5 mm deep), the burr pushed d into
// the −x wall and d into the bottom. Tilted 15° toward +x the shaft is clear: by
// hand the burr is pushed d out of each (two contacts), F = k·d·(1, 1, 0), no
// torque. Tilted 30° the shaft also meets the far rim, whose push (−x, up) lifts
// the burr off the bottom: the tool is wedged between the wall and the rim, and
// the rim's force above the burr centre turns it about +z.
TEST(PhysicalReference, ToolInDrilledHole) {
  const double Rh = 0.6e-3, D = 1.5e-3, d = 0.1e-3;
  const Material hole{{[Rh](const glm::dvec3& p) {
                         const double r = std::hypot(p.x, p.z);
                         if (r >= Rh) return p.y > 0.0 ? p.y : -std::min(-p.y, r - Rh);
                         return p.y > 0.0 ? std::hypot(Rh - r, p.y) : Rh - r;
                       },
                       [D](const glm::dvec3& p) { return p.y + D; }}};
  auto device = [&](double deg) {
    const double th = deg * kPi / 180.0;
    return Pose{{-(Rh - kTool.tipRadius) - d, -D + kTool.tipRadius - d, 0.0},
                rotationBetween({0, 1, 0}, glm::dvec3(std::sin(th), std::cos(th), 0.0))};
  };
  for (double kr : {kKr, std::numeric_limits<double>::infinity()}) {
    const PhysicalPose corner = constrainedPose(hole, kTool, device(15.0), {kK, kr});
    ASSERT_TRUE(corner.converged);
    expectNear(corner.pose.position, device(15.0).position + glm::dvec3(d, d, 0), 1e-10, "out of wall and bottom");
    expectNear(corner.force, kK * d * glm::dvec3(1, 1, 0), 1e-7, "force");
    EXPECT_LT(glm::length(corner.torque), 1e-12);
    ASSERT_EQ(corner.contacts.size(), 2u);
    EXPECT_FALSE(corner.contacts[0].onShaft || corner.contacts[1].onShaft);
    EXPECT_NE(corner.contacts[0].piece, corner.contacts[1].piece) << "one on the wall, one on the bottom";

    const PhysicalPose wedged = constrainedPose(hole, kTool, device(30.0), {kK, kr});
    ASSERT_TRUE(wedged.converged);
    EXPECT_LE(wedged.violation, 1e-10);
    EXPECT_LT(wedged.stationarity, 1e-6);
    ASSERT_EQ(wedged.contacts.size(), 2u);
    for (const auto& c : wedged.contacts) {
      if (c.onShaft) EXPECT_LT(c.normal.x, -0.5) << "the rim pushes the shaft toward −x";
      else EXPECT_GT(c.normal.x, 0.99) << "the wall pushes the burr toward +x";
    }
    EXPECT_GT(wedged.pose.position.y, -D + kTool.tipRadius + 1e-5) << "lifted off the bottom";
    EXPECT_GT(wedged.torque.z, 0.0);
  }
}

// Every pose of the physical suite (measure/PhysicalScenes.h), at every voxel
// size's sub-voxel phases, with the orientation held and with #3's coupling
// ratio: the solver meets its tolerances, and every reported contact force pushes out.
TEST(PhysicalReference, ConvergesOnEverySuitePose) {
  int poses = 0;
  for (const std::string& name : physicalSceneNames()) {
    const PhysicalScene scene = physicalScene(name);
    for (double h : {0.2e-3, 0.1e-3, 0.05e-3})
      for (const PhysicalProbe& probe : physicalProbes(scene, kTool, h, 2))
        for (double kr : {kKr, std::numeric_limits<double>::infinity()}) {
          const PhysicalPose p = constrainedPose(scene.material, kTool, probe.device, {kK, kr});
          ++poses;
          ASSERT_TRUE(p.converged) << name << " h " << h << " depth " << probe.depth << " kr " << kr << ": "
                                   << p.iterations << " iterations, penetration " << p.violation
                                   << " m, KKT residual " << p.stationarity;
          EXPECT_GT(glm::length(p.force), 0.0) << name << ": every probe is pressed into material";
          for (const auto& c : p.contacts) EXPECT_GT(c.force, 0.0);
        }
  }
  EXPECT_GT(poses, 500);
}

}  // namespace
