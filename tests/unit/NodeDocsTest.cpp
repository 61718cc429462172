// The node reference in docs/ is generated from the field declarations and must be current.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "millsim/core/Node.h"
#include "millsim/core/NodeDocs.h"
#include "millsim/core/NodeRegistry.h"

using namespace millsim;

TEST(NodeDocs, DocsNodesMdIsCurrent) {
  std::ifstream in(MILLSIM_SOURCE_DIR "/docs/nodes.md");
  ASSERT_TRUE(in) << "docs/nodes.md is missing";
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(ss.str(), nodeReferenceMarkdown(builtinRegistry()))
      << "docs/nodes.md is out of date: run `build/release/apps/millsim nodes --markdown > docs/nodes.md`";
}

TEST(NodeDocs, EveryFieldHasDocumentationAndAReadableDefault) {
  NodeRegistry r = builtinRegistry();
  for (const NodeType* t : r.all()) {
    EXPECT_FALSE(t->doc.empty()) << t->name;
    auto node = t->create();
    ASSERT_TRUE(node) << t->name;
    EXPECT_EQ(node->typeName(), t->name);
    for (Field* f : node->fields()) {
      EXPECT_FALSE(f->doc().empty()) << t->name << "." << f->name();
      if (f->isNodeField()) continue;
      // The default, written out, reads back to the same text.
      const std::string text = f->toString();
      auto copy = t->create();
      ASSERT_NO_THROW(copy->field(f->name())->setFromString(text)) << t->name << "." << f->name() << " = " << text;
      EXPECT_EQ(copy->field(f->name())->toString(), text);
    }
  }
}

TEST(NodeDocs, ContainerFieldsExistOnSomeNode) {
  // A type's default container field must be a node field of some registered type
  // (or it could never be placed without containerField).
  NodeRegistry r = builtinRegistry();
  for (const NodeType* t : r.all()) {
    bool found = false;
    for (const NodeType* parent : r.all()) {
      auto p = parent->create();
      if (Field* f = p->field(t->containerField); f && f->isNodeField()) found = true;
    }
    EXPECT_TRUE(found) << t->name << " has containerField '" << t->containerField << "'";
  }
}
