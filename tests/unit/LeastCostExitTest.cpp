// The least-cost way out of at most two contacts for a body held by springs
// (millsim/math/LeastCostExit.h), on cases worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "millsim/math/LeastCostExit.h"

using namespace millsim;

// pushesOut: a body held by springs k (and kr for turning) moved out of at
// most two contacts at least cost. Gram entries in m/N (m and rad per N).
TEST(LeastCostExit, OnePushIsTheSpringTimesTheDepth) {
  const double k = 2000.0;
  const double gram[2][2] = {{1.0 / k, 0.0}, {0.0, 0.0}};
  const double d[] = {1e-4};
  double l[2] = {-1.0, -1.0};
  ASSERT_TRUE(pushesOut(gram, d, 1, l));
  EXPECT_NEAR(l[0], k * 1e-4, 1e-12);
}

TEST(LeastCostExit, ACornerIsPushedOutOfBothFaces) {
  const double k = 2000.0;
  const double gram[2][2] = {{1.0 / k, 0.0}, {0.0, 1.0 / k}};  // normals at right angles, no moments
  const double d[] = {1e-4, 2e-4};
  double l[2];
  ASSERT_TRUE(pushesOut(gram, d, 2, l));
  EXPECT_NEAR(l[0], 0.2, 1e-12);
  EXPECT_NEAR(l[1], 0.4, 1e-12);
}

// Normals 60° apart: out of the deeper (0.2 mm along its normal) is already
// 0.1 mm along the other's, out of its 0.05 mm: the shallower does not push.
TEST(LeastCostExit, TheDeeperAloneClearsAShallowerOneNearby) {
  const double k = 2000.0, c = 0.5;  // cos 60°
  const double gram[2][2] = {{1.0 / k, c / k}, {c / k, 1.0 / k}};
  const double d[] = {0.05e-3, 0.2e-3};
  double l[2];
  ASSERT_TRUE(pushesOut(gram, d, 2, l));
  EXPECT_NEAR(l[0], 0.0, 1e-12);
  EXPECT_NEAR(l[1], k * 0.2e-3, 1e-12);
}

// A wedge, normals 150° apart: translating out costs far more than the
// depths, and a body that may turn (a lever of 2 mm on the second contact
// at kr = 0.1 N·m/rad) is pushed less than one that may not.
TEST(LeastCostExit, TurningEasesAWedge) {
  const double k = 2000.0, kr = 0.1, c = std::cos(150.0 * M_PI / 180.0), arm = 2e-3;
  const double rigid[2][2] = {{1.0 / k, c / k}, {c / k, 1.0 / k}};
  const double turning[2][2] = {{1.0 / k, c / k}, {c / k, 1.0 / k + arm * arm / kr}};
  const double d[] = {0.05e-3, 0.05e-3};
  double lr[2], lt[2];
  ASSERT_TRUE(pushesOut(rigid, d, 2, lr));
  ASSERT_TRUE(pushesOut(turning, d, 2, lt));
  // Translation only: λ = d·k / (1 + c) each, 7.5 times k·d.
  EXPECT_NEAR(lr[0], k * 0.05e-3 / (1.0 + c), 1e-9);
  EXPECT_NEAR(lr[1], lr[0], 1e-9);
  EXPECT_LT(lt[0] + lt[1], lr[0] + lr[1]);
  EXPECT_GT(lt[0], 0.0);
  EXPECT_GT(lt[1], 0.0);
}

TEST(LeastCostExit, NoPushesClearAJam) {
  const double k = 2000.0;
  const double gram[2][2] = {{1.0 / k, -1.0 / k}, {-1.0 / k, 1.0 / k}};  // facing each other
  const double d[] = {0.1e-3, 0.1e-3};
  double l[2] = {7.0, 7.0};
  EXPECT_FALSE(pushesOut(gram, d, 2, l));
  EXPECT_EQ(l[0], 7.0);
}
