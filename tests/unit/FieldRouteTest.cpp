// Routes and lazy evaluation: a change marks downstream fields stale, and a
// computed field recomputes only when read after a change.
#include <gtest/gtest.h>

#include "millsim/core/Field.h"
#include "millsim/core/Node.h"

using namespace millsim;

namespace {

class Probe : public Node {
public:
  const NodeType& nodeType() const override {
    static const NodeType t = makeNodeType<Probe>("Probe", "children", "Test", "Route test node.");
    return t;
  }
  SFFloat in{this, "in", Access::InputOutput, 0.f, ""};
  SFFloat other{this, "other", Access::InputOutput, 0.f, ""};
  SFFloat inputOnly{this, "inputOnly", Access::InputOnly, 0.f, ""};
  SFFloat initOnly{this, "initOnly", Access::InitializeOnly, 0.f, ""};
  SFVec3f vec{this, "vec", Access::InputOutput, glm::vec3(0.f), ""};
  Computed<SFFloat> sum{this, "sum", "in + other", {&in, &other}, [this] { return in.get() + other.get(); }};
};

}  // namespace

TEST(Routes, ValueFlowsOnRead) {
  Probe a, b;
  a.in.routeTo(b.in);
  a.in.set(3.f);
  EXPECT_FALSE(b.in.upToDate());
  EXPECT_FLOAT_EQ(b.in.get(), 3.f);
  EXPECT_TRUE(b.in.upToDate());
}

TEST(Routes, ANewRouteDeliversTheCurrentValue) {
  Probe a, b;
  a.in.set(5.f);
  a.in.routeTo(b.in);
  EXPECT_FLOAT_EQ(b.in.get(), 5.f);
}

TEST(Routes, ChainsPropagateAndTheLatestEventWins) {
  Probe a, b, c, d;
  a.in.routeTo(b.in);
  b.in.routeTo(c.in);
  d.in.routeTo(c.in);
  d.in.set(1.f);
  a.in.set(2.f);  // later than d's event
  EXPECT_FLOAT_EQ(c.in.get(), 2.f);
  d.in.set(7.f);
  EXPECT_FLOAT_EQ(c.in.get(), 7.f);
}

TEST(Routes, DirectSetOnADestinationDoesNotHideLaterEvents) {
  Probe a, b, c;
  a.in.routeTo(b.in);
  b.in.routeTo(c.in);
  a.in.set(1.f);
  c.in.set(9.f);  // c set directly while b is stale
  a.in.set(4.f);
  EXPECT_FLOAT_EQ(c.in.get(), 4.f);
}

TEST(Routes, CyclesTerminate) {
  Probe a, b;
  a.in.routeTo(b.in);
  b.in.routeTo(a.in);
  a.in.set(2.f);
  EXPECT_FLOAT_EQ(b.in.get(), 2.f);
  EXPECT_FLOAT_EQ(a.in.get(), 2.f);
  b.in.set(6.f);
  EXPECT_FLOAT_EQ(a.in.get(), 6.f);
}

TEST(Routes, TypeAndAccessAreChecked) {
  Probe a, b;
  EXPECT_THROW(a.in.routeTo(b.vec), RouteError);         // SFFloat -> SFVec3f
  EXPECT_THROW(a.inputOnly.routeTo(b.in), RouteError);   // inputOnly cannot send
  EXPECT_THROW(a.initOnly.routeTo(b.in), RouteError);    // initializeOnly cannot send
  EXPECT_THROW(a.in.routeTo(b.initOnly), RouteError);    // initializeOnly cannot receive
  EXPECT_THROW(a.in.routeTo(b.sum), RouteError);         // outputOnly cannot receive
  EXPECT_THROW(a.in.routeTo(a.in), RouteError);
  a.in.routeTo(b.inputOnly);
  EXPECT_THROW(a.in.routeTo(b.inputOnly), RouteError);   // duplicate
  try {
    a.in.routeTo(b.vec);
  } catch (const RouteError& e) {
    EXPECT_NE(std::string(e.what()).find("SFFloat cannot be routed to SFVec3f"), std::string::npos);
  }
}

TEST(Routes, DestroyingAFieldRemovesItsRoutes) {
  Probe a;
  const std::size_t before = a.in.routesOut().size();  // a.sum reads a.in
  {
    Probe b;
    a.in.routeTo(b.in);
    EXPECT_EQ(a.in.routesOut().size(), before + 1);
  }
  EXPECT_EQ(a.in.routesOut().size(), before);
  a.in.set(1.f);  // must not touch the destroyed field
}

TEST(LazyEvaluation, ComputedFieldRunsOnlyWhenReadAfterAChange) {
  Probe p;
  EXPECT_EQ(p.sum.computeCount(), 0u);
  p.in.set(1.f);
  p.other.set(2.f);
  p.in.set(3.f);
  EXPECT_EQ(p.sum.computeCount(), 0u);  // nothing read yet: nothing computed
  EXPECT_FLOAT_EQ(p.sum.get(), 5.f);
  EXPECT_EQ(p.sum.computeCount(), 1u);
  EXPECT_FLOAT_EQ(p.sum.get(), 5.f);
  EXPECT_EQ(p.sum.computeCount(), 1u);  // no change: no recompute
  p.other.set(10.f);
  EXPECT_EQ(p.sum.computeCount(), 1u);
  EXPECT_FLOAT_EQ(p.sum.get(), 13.f);
  EXPECT_EQ(p.sum.computeCount(), 2u);
}

TEST(LazyEvaluation, ComputedFieldsFeedRoutes) {
  Probe p, q;
  p.sum.routeTo(q.in);
  p.in.set(2.f);
  EXPECT_FLOAT_EQ(q.in.get(), 2.f);
  EXPECT_EQ(p.sum.computeCount(), 1u);
  p.other.set(1.f);
  EXPECT_FLOAT_EQ(q.in.get(), 3.f);
  EXPECT_EQ(p.sum.computeCount(), 2u);
}
