// Every standard node MillSim implements has X3D's field table: each field
// exists with X3D's type (a node field only if MillSim has it, then with X3D's
// access too); a field a file may set has X3D's
// default, an event (inputOnly, outputOnly) X3D's access. The reference is the X3D Unified Object
// Model, as tests/data/x3d-uom/fields-4.0.txt (scripts/gen-x3d-tables).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "millsim/core/Node.h"
#include "millsim/core/NodeRegistry.h"

namespace millsim {
namespace {

struct UomField {
  std::string node, name, type, access, defaultValue;
};

std::map<std::string, std::vector<UomField>> readUom() {
  std::map<std::string, std::vector<UomField>> out;
  std::ifstream in(MILLSIM_SOURCE_DIR "/tests/data/x3d-uom/fields-4.0.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> p;
    std::size_t start = 0;
    for (std::size_t bar; (bar = line.find('|', start)) != std::string::npos; start = bar + 1)
      p.push_back(line.substr(start, bar - start));
    p.push_back(line.substr(start));
    if (p.size() == 5) out[p[0]].push_back({p[0], p[1], p[2], p[3], p[4]});
  }
  return out;
}

std::vector<std::string> tokens(const std::string& s) {
  std::vector<std::string> t;
  std::string cur;
  for (char c : s) {
    if (c == ' ' || c == ',' || c == '\t') {
      if (!cur.empty()) t.push_back(cur), cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) t.push_back(cur);
  return t;
}

// Same value, allowing the spec's rounded constants (fieldOfView 0.7854).
bool sameValue(const std::string& a, const std::string& b) {
  if (a == b) return true;
  auto ta = tokens(a), tb = tokens(b);
  if (ta.size() != tb.size()) return false;
  for (std::size_t i = 0; i < ta.size(); ++i) {
    char *ea, *eb;
    const double x = std::strtod(ta[i].c_str(), &ea), y = std::strtod(tb[i].c_str(), &eb);
    if (*ea || *eb) {
      if (ta[i] != tb[i]) return false;
    } else if (std::abs(x - y) > 1e-4 * std::max(1.0, std::abs(y))) {
      return false;
    }
  }
  return true;
}

bool checked(const UomField& f) {
  return !(f.name == "DEF" || f.name == "USE" || f.name == "class" || f.name == "id" || f.name == "style" ||
           f.name == "IS");
}

bool isNodeType(const std::string& type) { return type == "SFNode" || type == "MFNode"; }

bool isEvent(const std::string& access) { return access == "inputOnly" || access == "outputOnly"; }

// What differs between the node type's fields and the spec's rows.
std::vector<std::string> mismatches(const NodeType& t, const std::vector<UomField>& rows) {
  std::vector<std::string> out;
  auto node = t.create();
  for (const UomField& u : rows) {
    if (!checked(u)) continue;
    const std::string where = t.name + "." + u.name;
    Field* f = node->field(u.name);
    // A node field (metadata, proxy, children) need not exist (children of node
    // types MillSim does not have are skipped), but one that does has X3D's type and access.
    if (isNodeType(u.type)) {
      if (f && (fieldTypeName(f->type()) != u.type || accessName(f->access()) != u.access))
        out.push_back(where + ": " + std::string(accessName(f->access())) + " " +
                      std::string(fieldTypeName(f->type())) + ", X3D says " + u.access + " " + u.type);
      continue;
    }
    if (!f) {
      out.push_back(where + ": missing (X3D: " + u.type + ", default '" + u.defaultValue + "')");
      continue;
    }
    if (fieldTypeName(f->type()) != u.type) {
      out.push_back(where + ": type " + std::string(fieldTypeName(f->type())) + ", X3D says " + u.type);
      continue;
    }
    // An event has no default; it must be one in MillSim too (a settable field's access may be narrower).
    if (isEvent(u.access) || isEvent(std::string(accessName(f->access())))) {
      if (accessName(f->access()) != u.access)
        out.push_back(where + ": access " + std::string(accessName(f->access())) + ", X3D says " + u.access);
      continue;
    }
    auto fresh = t.create();
    Field* g = fresh->field(u.name);
    try {
      g->setFromString(u.defaultValue);
    } catch (const std::exception& e) {
      out.push_back(where + ": X3D's default '" + u.defaultValue + "' is refused: " + e.what());
      continue;
    }
    if (!sameValue(f->toString(), g->toString()))
      out.push_back(where + ": default '" + f->toString() + "', X3D says '" + u.defaultValue + "'");
  }
  return out;
}

TEST(X3dUom, ImplementedStandardNodesHaveTheStandardFields) {
  const auto uom = readUom();
  ASSERT_GT(uom.size(), 200u) << "tests/data/x3d-uom/fields-4.0.txt is missing or short";
  NodeRegistry r = builtinRegistry();
  std::size_t compared = 0;
  for (const NodeType* t : r.all()) {
    auto it = uom.find(t->name);
    if (it == uom.end()) continue;
    ++compared;
    for (const std::string& m : mismatches(*t, it->second)) ADD_FAILURE() << m;
  }
  // The 31 standard nodes MillSim registers (ImportLibrary and Scene are not X3D
  // nodes, nor is H3DAPI's MatrixTransform).
  EXPECT_GE(compared, 31u);
}

// The comparison can fail: a wrong default, a wrong type and a missing field are each reported.
TEST(X3dUom, AWrongTableIsReported) {
  const NodeRegistry registry = builtinRegistry();  // kept: find() points into it
  const NodeType* t = registry.find("Transform");
  ASSERT_NE(t, nullptr);
  EXPECT_TRUE(mismatches(*t, {{"Transform", "scale", "SFVec3f", "inputOutput", "1 1 1"}}).empty());
  EXPECT_EQ(mismatches(*t, {{"Transform", "scale", "SFVec3f", "inputOutput", "2 1 1"}}).size(), 1u);
  EXPECT_EQ(mismatches(*t, {{"Transform", "scale", "SFVec3d", "inputOutput", "1 1 1"}}).size(), 1u);
  EXPECT_EQ(mismatches(*t, {{"Transform", "skew", "SFFloat", "inputOutput", "0"}}).size(), 1u);
  EXPECT_EQ(mismatches(*t, {{"Transform", "scale", "SFVec3f", "outputOnly", ""}}).size(), 1u);
  EXPECT_TRUE(mismatches(*t, {{"Transform", "metadata", "SFNode", "inputOutput", "NULL"}}).empty());
  EXPECT_EQ(mismatches(*t, {{"Transform", "metadata", "MFNode", "inputOutput", ""}}).size(), 1u);
  EXPECT_EQ(mismatches(*t, {{"Transform", "children", "MFNode", "initializeOnly", ""}}).size(), 1u);
  EXPECT_TRUE(mismatches(*t, {{"Transform", "addChildren", "MFNode", "inputOnly", ""}}).empty());
}

}  // namespace
}  // namespace millsim
