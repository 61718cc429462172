// The nearest translation out of a few planar contacts, and a force's split
// into non-negative pushes along them (millsim/math/ContactCone.h), on cases
// worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "millsim/math/ContactCone.h"

using namespace millsim;

namespace {

void expectNear(const glm::dvec3& a, const glm::dvec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-12);
  EXPECT_NEAR(a.y, b.y, 1e-12);
  EXPECT_NEAR(a.z, b.z, 1e-12);
}

}  // namespace

TEST(ContactCone, OutOfOnePlaneAlongItsNormal) {
  const glm::dvec3 n[] = {{0, 1, 0}};
  const double d[] = {0.1};
  glm::dvec3 s(9.0);
  ASSERT_TRUE(nearestTranslationOut(n, d, 1, s));
  expectNear(s, {0, 0.1, 0});
}

TEST(ContactCone, OutOfACornerByBothDepths) {
  const glm::dvec3 n[] = {{1, 0, 0}, {0, 1, 0}};
  const double d[] = {0.1, 0.2};
  glm::dvec3 s;
  ASSERT_TRUE(nearestTranslationOut(n, d, 2, s));
  expectNear(s, {0.1, 0.2, 0});
}

// Out of the deeper plane is already out of the shallower one at 45°.
TEST(ContactCone, OnePushCanClearBoth) {
  const glm::dvec3 n[] = {{0, 1, 0}, glm::normalize(glm::dvec3(1, 1, 0))};
  const double d[] = {1.0, 0.1};
  glm::dvec3 s;
  ASSERT_TRUE(nearestTranslationOut(n, d, 2, s));
  expectNear(s, {0, 1, 0});
}

// A contact that is clear must stay clear: out of the first along its normal
// would sink 0.6 into the second, which is only 0.2 away.
TEST(ContactCone, KeepsAClearContactClear) {
  const glm::dvec3 n[] = {{0, 1, 0}, {0, -0.6, 0.8}};
  const double d[] = {1.0, -0.2};
  glm::dvec3 s;
  ASSERT_TRUE(nearestTranslationOut(n, d, 2, s));
  EXPECT_NEAR(glm::dot(n[0], s), 1.0, 1e-12);
  EXPECT_NEAR(glm::dot(n[1], s), -0.2, 1e-12);
  EXPECT_NEAR(s.x, 0.0, 1e-12);  // nothing sideways: both normals lie in the y-z plane
}

// A clear contact only bounds the way out, it never pulls: 0.5 clear below,
// 0.1 deep above, the way out is 0.1 up (not 0.5 up, onto the clear one).
TEST(ContactCone, AClearContactDoesNotPull) {
  const glm::dvec3 n[] = {{0, -1, 0}, {0, 1, 0}};
  const double d[] = {-0.5, 0.1};
  glm::dvec3 s;
  ASSERT_TRUE(nearestTranslationOut(n, d, 2, s));
  expectNear(s, {0, 0.1, 0});
}

TEST(ContactCone, ContactsFacingEachOtherHaveNoWayOut) {
  const glm::dvec3 n[] = {{1, 0, 0}, {-1, 0, 0}};
  const double d[] = {0.1, 0.1};
  glm::dvec3 s(7.0);
  EXPECT_FALSE(nearestTranslationOut(n, d, 2, s));
  expectNear(s, glm::dvec3(7.0));  // left untouched
}

TEST(ContactCone, RefusesANonFiniteDepth) {
  const glm::dvec3 n[] = {{0, 1, 0}};
  const double d[] = {std::numeric_limits<double>::quiet_NaN()};
  glm::dvec3 s;
  EXPECT_FALSE(nearestTranslationOut(n, d, 1, s));
}

TEST(ContactCone, SplitsAForceIntoPushes) {
  const glm::dvec3 n[] = {{1, 0, 0}, {0, 1, 0}};
  double shares[2];
  splitAlongNormals(n, 2, {2, 3, 0}, shares);
  EXPECT_NEAR(shares[0], 2.0, 1e-12);
  EXPECT_NEAR(shares[1], 3.0, 1e-12);
  // A contact the force pulls away from carries nothing.
  splitAlongNormals(n, 2, {2, -3, 0}, shares);
  EXPECT_NEAR(shares[0], 2.0, 1e-12);
  EXPECT_EQ(shares[1], 0.0);
  splitAlongNormals(n, 2, {-2, -3, 0}, shares);
  EXPECT_EQ(shares[0], 0.0);
  EXPECT_EQ(shares[1], 0.0);
}
