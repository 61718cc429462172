// Every field type read from and written to its X3D XML spelling.
#include <gtest/gtest.h>

#include <cmath>

#include "millsim/core/Field.h"
#include "millsim/core/Node.h"

using namespace millsim;

namespace {

// A node with one field of each type, for reading attribute strings.
class AllTypes : public Node {
public:
  const NodeType& nodeType() const override {
    static const NodeType type = makeNodeType<AllTypes>("AllTypes", "children", "Test", "Every field type.");
    return type;
  }
  SFBool b{this, "b", Access::InputOutput, false, ""};
  SFInt32 i{this, "i", Access::InputOutput, 0, ""};
  SFFloat f{this, "f", Access::InputOutput, 0.f, ""};
  SFDouble d{this, "d", Access::InputOutput, 0.0, ""};
  SFTime t{this, "t", Access::InputOutput, Time{}, ""};
  SFString s{this, "s", Access::InputOutput, "", ""};
  SFVec2f v2{this, "v2", Access::InputOutput, glm::vec2(0.f), ""};
  SFVec3f v3{this, "v3", Access::InputOutput, glm::vec3(0.f), ""};
  SFVec3d v3d{this, "v3d", Access::InputOutput, glm::dvec3(0.0), ""};
  SFRotation r{this, "r", Access::InputOutput, Rotation{}, ""};
  SFColor c{this, "c", Access::InputOutput, Color{}, ""};
  MFBool mb{this, "mb", Access::InputOutput, {}, ""};
  MFInt32 mi{this, "mi", Access::InputOutput, {}, ""};
  MFFloat mf{this, "mf", Access::InputOutput, {}, ""};
  MFDouble md{this, "md", Access::InputOutput, {}, ""};
  MFTime mt{this, "mt", Access::InputOutput, {}, ""};
  MFString ms{this, "ms", Access::InputOutput, {}, ""};
  MFVec2f mv2{this, "mv2", Access::InputOutput, {}, ""};
  MFVec3f mv3{this, "mv3", Access::InputOutput, {}, ""};
  MFVec3d mv3d{this, "mv3d", Access::InputOutput, {}, ""};
  MFRotation mr{this, "mr", Access::InputOutput, {}, ""};
  MFColor mc{this, "mc", Access::InputOutput, {}, ""};
  SFMatrix4f m4{this, "m4", Access::InputOutput, glm::mat4(1.f), ""};
  SFFloat positive{this, "positive", Access::InputOutput, 1.f, "", Range::positive()};
};

template <class F> std::string errorOf(F&& f) {
  try {
    f();
  } catch (const ValueError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(FieldValues, FieldsRegisterInDeclarationOrderWithTheirTypes) {
  AllTypes n;
  ASSERT_EQ(n.fields().size(), 25u);
  EXPECT_EQ(n.fields()[0]->name(), "metadata");  // every node's (X3DNode), declared by Node
  EXPECT_EQ(n.fields()[0]->type(), FieldType::SFNode);
  EXPECT_EQ(n.fields()[1]->name(), "b");
  EXPECT_EQ(fieldTypeName(n.field("m4")->type()), "SFMatrix4f");
  EXPECT_EQ(n.field("mv3")->type(), FieldType::MFVec3f);
  EXPECT_EQ(fieldTypeName(n.field("t")->type()), "SFTime");
  EXPECT_EQ(fieldTypeName(n.field("c")->type()), "SFColor");
  EXPECT_EQ(n.field("nope"), nullptr);
}

// H3DAPI's order: row by row, the translation 4th, 8th and 12th.
TEST(FieldValues, SFMatrix4fIsReadAndWrittenRowByRow) {
  AllTypes n;
  EXPECT_EQ(n.m4.toString(), "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1");
  n.m4.setFromString("1 0 0 0.01  0 2 0 -2.5,  0 0 1 3  0 0 0 1");
  const glm::mat4& m = n.m4.get();
  EXPECT_FLOAT_EQ(m[3][0], 0.01f);  // glm: m[column][row]
  EXPECT_FLOAT_EQ(m[3][1], -2.5f);
  EXPECT_FLOAT_EQ(m[3][2], 3.f);
  EXPECT_FLOAT_EQ(m[1][1], 2.f);
  EXPECT_FLOAT_EQ(m[0][3], 0.f);
  const std::string text = n.m4.toString();
  EXPECT_EQ(text, "1 0 0 0.01 0 2 0 -2.5 0 0 1 3 0 0 0 1");
  AllTypes copy;
  copy.m4.setFromString(text);
  EXPECT_EQ(copy.m4.get(), m);
  EXPECT_NE(errorOf([&] { n.m4.setFromString("1 0 0 0  0 1 0 0  0 0 1 0"); }).find("16 numbers"), std::string::npos);
  EXPECT_NE(errorOf([&] { n.m4.setFromString("1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1  7"); }).find("extra text"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { n.m4.setFromString("1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 nan"); }).find("finite"),
            std::string::npos);
}

TEST(FieldValues, SFBool) {
  AllTypes n;
  n.b.setFromString("true");
  EXPECT_TRUE(n.b.get());
  n.b.setFromString(" false ");
  EXPECT_FALSE(n.b.get());
  n.b.setFromString("TRUE");  // classic encoding accepted
  EXPECT_TRUE(n.b.get());
  EXPECT_EQ(n.b.toString(), "true");
  EXPECT_NE(errorOf([&] { n.b.setFromString("yes"); }).find("expected true or false, found 'yes'"), std::string::npos);
}

TEST(FieldValues, SFInt32DecimalHexAndLimits) {
  AllTypes n;
  n.i.setFromString("-42");
  EXPECT_EQ(n.i.get(), -42);
  n.i.setFromString("0x1F");
  EXPECT_EQ(n.i.get(), 31);
  n.i.setFromString("+7");
  EXPECT_EQ(n.i.get(), 7);
  EXPECT_NE(errorOf([&] { n.i.setFromString("3000000000"); }).find("does not fit in 32 bits"), std::string::npos);
  EXPECT_NE(errorOf([&] { n.i.setFromString("1.5"); }).find("expected an integer"), std::string::npos);
}

TEST(FieldValues, SFFloatAndDoubleRejectNonFinite) {
  AllTypes n;
  n.f.setFromString("1.5e-3");
  EXPECT_FLOAT_EQ(n.f.get(), 1.5e-3f);
  n.d.setFromString("+0.25");
  EXPECT_DOUBLE_EQ(n.d.get(), 0.25);
  EXPECT_NE(errorOf([&] { n.f.setFromString("nan"); }).find("finite"), std::string::npos);
  EXPECT_NE(errorOf([&] { n.d.setFromString("inf"); }).find("finite"), std::string::npos);
  EXPECT_NE(errorOf([&] { n.f.setFromString("1e999"); }).find("out of range for a 32-bit float"), std::string::npos);
  EXPECT_NE(errorOf([&] { n.f.setFromString("1 2"); }).find("unexpected extra text '2'"), std::string::npos);
  EXPECT_NE(errorOf([&] { n.f.setFromString(""); }).find("found the end of the value"), std::string::npos);
}

TEST(FieldValues, FloatsRoundTripThroughText) {
  AllTypes n;
  for (float v : {0.f, 1.f, -2.5f, 0.0005f, 1.2345678e-7f, 3.4e20f, 0.1f}) {
    n.f.set(v);
    AllTypes m;
    m.f.setFromString(n.f.toString());
    EXPECT_EQ(m.f.get(), v) << n.f.toString();
  }
  n.f.set(0.0005f);
  EXPECT_EQ(n.f.toString(), "0.0005");
}

TEST(FieldValues, SFTimeAndString) {
  AllTypes n;
  n.t.setFromString("12.5");
  EXPECT_DOUBLE_EQ(n.t.get().seconds, 12.5);
  // SFString in an XML attribute is the raw text: no quotes are removed.
  n.s.setFromString("a \"quoted\" word");
  EXPECT_EQ(n.s.get(), "a \"quoted\" word");
}

TEST(FieldValues, VectorsAcceptCommasAsWhitespace) {
  AllTypes n;
  n.v2.setFromString("1,2");
  EXPECT_EQ(n.v2.get(), glm::vec2(1, 2));
  n.v3.setFromString(" 1, 2 ,3 ");
  EXPECT_EQ(n.v3.get(), glm::vec3(1, 2, 3));
  n.v3d.setFromString("0.1 0.2 0.3");
  EXPECT_EQ(n.v3d.get(), glm::dvec3(0.1, 0.2, 0.3));
  EXPECT_NE(errorOf([&] { n.v3.setFromString("1 2"); }).find("expected 3 numbers (x y z), found the end"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { n.v3.setFromString("1 2 x"); }).find("found 'x'"), std::string::npos);
}

TEST(FieldValues, RotationNormalisesTheAxis) {
  AllTypes n;
  n.r.setFromString("0 2 0 1.5708");
  EXPECT_EQ(n.r.get().axis, glm::vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(n.r.get().angle, 1.5708f);
  n.r.setFromString("0 0 0 0");  // identity spelt with a zero axis
  EXPECT_EQ(n.r.get().angle, 0.f);
  EXPECT_NE(errorOf([&] { n.r.setFromString("0 0 0 1"); }).find("axis is zero"), std::string::npos);
  EXPECT_NE(errorOf([&] { n.r.setFromString("0 1 0"); }).find("4 numbers"), std::string::npos);
}

TEST(FieldValues, ColorComponentsMustBeInUnitRange) {
  AllTypes n;
  n.c.setFromString("1 0.5 0");
  EXPECT_EQ(n.c.get().rgb, glm::vec3(1, 0.5f, 0));
  EXPECT_NE(errorOf([&] { n.c.setFromString("1.5 0 0"); }).find("outside the expected range [0, 1]"),
            std::string::npos);
}

TEST(FieldValues, MultipleValueFields) {
  AllTypes n;
  n.mb.setFromString("true false true");
  EXPECT_EQ(n.mb.get(), (std::vector<bool>{true, false, true}));
  n.mi.setFromString("1, 2, -3");
  EXPECT_EQ(n.mi.get(), (std::vector<std::int32_t>{1, 2, -3}));
  n.mf.setFromString("0.5 1.5");
  EXPECT_EQ(n.mf.get(), (std::vector<float>{0.5f, 1.5f}));
  n.md.setFromString("");
  EXPECT_TRUE(n.md.get().empty());
  n.mt.setFromString("0 1");
  EXPECT_EQ(n.mt.get().size(), 2u);
  n.mv2.setFromString("1 2, 3 4");
  EXPECT_EQ(n.mv2.get()[1], glm::vec2(3, 4));
  n.mv3.setFromString("1 2 3, 4 5 6");
  ASSERT_EQ(n.mv3.get().size(), 2u);
  EXPECT_EQ(n.mv3.get()[1], glm::vec3(4, 5, 6));
  n.mv3d.setFromString("1 2 3");
  EXPECT_EQ(n.mv3d.get()[0], glm::dvec3(1, 2, 3));
  n.mr.setFromString("0 1 0 0.5, 1 0 0 1");
  EXPECT_EQ(n.mr.get()[1].axis, glm::vec3(1, 0, 0));
  n.mc.setFromString("1 0 0, 0 1 0");
  EXPECT_EQ(n.mc.get()[1].rgb, glm::vec3(0, 1, 0));
  EXPECT_EQ(n.mv3.toString(), "1 2 3, 4 5 6");
  EXPECT_NE(errorOf([&] { n.mv3.setFromString("1 2 3 4"); }).find("item 2: expected 3 numbers"), std::string::npos);
}

TEST(FieldValues, MFStringQuotingAndEscapes) {
  AllTypes n;
  n.ms.setFromString(R"("tooth.nrrd" "phantom:tooth")");
  EXPECT_EQ(n.ms.get(), (std::vector<std::string>{"tooth.nrrd", "phantom:tooth"}));
  n.ms.setFromString(R"("say \"hi\"" "back\\slash")");
  EXPECT_EQ(n.ms.get()[0], "say \"hi\"");
  EXPECT_EQ(n.ms.get()[1], "back\\slash");
  EXPECT_EQ(n.ms.toString(), R"("say \"hi\"" "back\\slash")");
  EXPECT_NE(errorOf([&] { n.ms.setFromString("tooth.nrrd"); }).find("expected a quoted string"), std::string::npos);
  EXPECT_NE(errorOf([&] { n.ms.setFromString("\"open"); }).find("unterminated"), std::string::npos);
}

TEST(FieldValues, RangesAreCheckedAndNamed) {
  AllTypes n;
  n.positive.setFromString("0.25");
  EXPECT_NE(errorOf([&] { n.positive.setFromString("0"); }).find("outside the expected range > 0"), std::string::npos);
  EXPECT_NE(errorOf([&] { n.positive.set(-1.f); }).find("-1"), std::string::npos);
  EXPECT_EQ(n.positive.constraint(), "> 0");
  EXPECT_FLOAT_EQ(n.positive.get(), 0.25f);  // the bad values left it unchanged
}
