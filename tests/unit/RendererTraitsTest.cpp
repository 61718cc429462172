// What every registered renderer declares about itself (RendererTraits) must
// name fields the node has, of the right kind, with values those fields
// accept: measure/ and the tests trust these declarations, so a typo in a
// trait fails here, not as a skipped sweep or a silently wrong reference.
#include <gtest/gtest.h>

#include <string>

#include "measure/Renderers.h"
#include "millsim/core/NodeRegistry.h"

using namespace millsim;

namespace {

bool numeric(FieldType t) { return t == FieldType::SFInt32 || t == FieldType::SFFloat || t == FieldType::SFDouble; }

}  // namespace

class EveryRendererTraits : public ::testing::TestWithParam<std::string> {
protected:
  std::shared_ptr<HapticsRendererNode> renderer() const { return measure::makeRenderer({GetParam(), {}}); }
};

// The Z-width sweep sets this field to std::to_string(k) N/m and the accuracy
// reference reads it as its spring: every registered renderer must name one.
TEST_P(EveryRendererTraits, TheStiffnessFieldIsANumberItsNodeHas) {
  const std::string name = renderer()->traits().stiffnessField;
  ASSERT_FALSE(name.empty()) << GetParam() << " declares no stiffness field: name it in traits()";
  auto node = renderer();
  Field* f = node->field(name);
  ASSERT_NE(f, nullptr) << GetParam() << " declares stiffness field '" << name << "', which it does not have";
  EXPECT_TRUE(f->type() == FieldType::SFFloat || f->type() == FieldType::SFDouble)
      << GetParam() << "." << name << " is " << fieldTypeName(f->type()) << ", not a stiffness in N/m";
  double k = 0.0;
  ASSERT_NO_THROW(k = std::stod(f->toString())) << GetParam() << "." << name << " = '" << f->toString() << "'";
  EXPECT_GT(k, 0.0) << GetParam() << "." << name;
  EXPECT_NO_THROW(f->setFromString(std::to_string(2.0 * k))) << GetParam() << "." << name;
}

// The accuracy sweep sets each field to each value (measure::makeRenderer) and
// fits the error against the value as a number.
TEST_P(EveryRendererTraits, EverySweepValueIsAcceptedByItsField) {
  const auto sweeps = renderer()->traits().resolutionSweeps;
  for (const auto& [name, values] : sweeps) {
    auto node = renderer();
    Field* f = node->field(name);
    ASSERT_NE(f, nullptr) << GetParam() << " declares resolution field '" << name << "', which it does not have";
    EXPECT_TRUE(numeric(f->type())) << GetParam() << "." << name << " is " << fieldTypeName(f->type())
                                    << ", not a number a convergence order can be fitted against";
    EXPECT_FALSE(values.empty()) << GetParam() << "." << name << " is swept over no values";
    for (const std::string& v : values) {
      EXPECT_NO_THROW(f->setFromString(v)) << GetParam() << "." << name << " refuses its sweep value '" << v << "'";
      EXPECT_NO_THROW((void)std::stod(v)) << GetParam() << "." << name << " sweep value '" << v << "'";
      EXPECT_NO_THROW(measure::makeRenderer({GetParam(), {{name, v}}})) << GetParam() << "." << name << " = " << v;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Algorithms, EveryRendererTraits, ::testing::ValuesIn(measure::registeredRenderers()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

// A renderer that declares nothing (a plugin's, say) gets the defaults
// measure/ and the tests rely on: no stiffness field (the Z-width test then
// fails), no sweeps, the Coupling reference, and no promise never to tunnel.
namespace {
class Undeclared : public HapticsRendererNode {
public:
  static const NodeType& type() {
    static const NodeType t = makeNodeType<Undeclared>("Undeclared", "hapticsRenderer", "Test", "Declares no traits.");
    return t;
  }
  const NodeType& nodeType() const override { return type(); }
  std::unique_ptr<HapticAlgorithm> compile(const ToolGeometry&, HapticScene&) const override { return nullptr; }
};
}  // namespace

TEST(RendererTraits, ARendererThatDeclaresNothingPromisesNothing) {
  const RendererTraits t = Undeclared().traits();
  EXPECT_TRUE(t.stiffnessField.empty());
  EXPECT_TRUE(t.resolutionSweeps.empty());
  EXPECT_EQ(t.reference, ReferenceKind::Coupling);
  EXPECT_FALSE(t.constrainsTool);
}
