#include "millsim/core/Scene.h"

#include <set>


namespace millsim {

const NodeType& SceneRoot::type() {
  static const NodeType t = makeNodeType<SceneRoot>("Scene", "children", "Core", "The top-level nodes of a scene.");
  return t;
}

Scene::Scene() : root(std::make_shared<SceneRoot>()) {}

// Routes point into nodes; drop them before the nodes go.
Scene::~Scene() {
  for (auto& r : routes) r.fromField->unrouteTo(*r.toField);
}

std::shared_ptr<Node> Scene::def(std::string_view name) const {
  auto it = defs.find(name);
  return it == defs.end() ? nullptr : it->second;
}

void Scene::forEachNode(const std::function<void(Node&)>& visit) const {
  std::set<const Node*> seen;
  std::function<void(Node&)> walk = [&](Node& n) {
    if (!seen.insert(&n).second) return;
    visit(n);
    for (Field* f : n.fields())
      if (auto* nf = dynamic_cast<NodeFieldBase*>(f))
        for (auto& child : nf->nodes()) walk(*child);
  };
  for (auto& n : root->children.get()) walk(*n);
  for (auto& n : unattached) walk(*n);
}

std::size_t Scene::nodeCount() const {
  std::size_t count = 0;
  forEachNode([&](Node&) { ++count; });
  return count;
}

namespace {

// Default values of a node type, as text, from a fresh instance.
const std::map<std::string, std::string>& defaultsOf(const NodeType& type) {
  static std::map<const NodeType*, std::map<std::string, std::string>> cache;
  auto it = cache.find(&type);
  if (it != cache.end()) return it->second;
  auto& values = cache[&type];
  auto proto = type.create();
  for (Field* f : proto->fields())
    if (!f->isNodeField()) values[std::string(f->name())] = f->toString();
  return values;
}

void describeNode(const Node& n, int depth, std::string_view viaField, std::set<const Node*>& printed,
                  std::string& out) {
  std::string indent(static_cast<std::size_t>(depth) * 2, ' ');
  out += indent;
  if (!viaField.empty() && viaField != "children" && viaField != "loaded") out += std::string(viaField) + ": ";
  if (!printed.insert(&n).second) {
    out += "USE " + n.defName() + "\n";
    return;
  }
  out += n.typeName();
  if (!n.defName().empty()) out += " DEF=" + n.defName();
  const auto& defaults = defaultsOf(n.nodeType());
  for (Field* f : n.fields()) {
    if (f->isNodeField() || f->access() == Access::InputOnly || f->access() == Access::OutputOnly) continue;
    std::string v = f->toString();
    auto d = defaults.find(std::string(f->name()));
    if (d != defaults.end() && d->second == v) continue;
    if (v.size() > 80) v = v.substr(0, 77) + "...";
    out += " " + std::string(f->name()) + "='" + v + "'";
    // The SI unit the value is in, after any <unit> conversion (a quantity
    // carried by only part of the value, as a plane's d, is left unnamed).
    if (const Range* r = f->range();
        r && !r->quantity.lastOnly && !r->quantity.translationOnly &&
        !(r->quantity.minusOneIsNone && v.find_first_not_of("-1 ") == std::string::npos))  // -1: "none", no unit
      if (const std::string unit = siUnit(r->quantity); !unit.empty()) out += " " + unit;
  }
  out += "\n";
  for (Field* f : n.fields())
    if (auto* nf = dynamic_cast<const NodeFieldBase*>(f))
      for (auto& child : nf->nodes()) describeNode(*child, depth + 1, f->name(), printed, out);
}

}  // namespace

std::string describeScene(const Scene& scene) {
  std::string out = "Scene";
  if (!scene.profile.empty()) out += " profile=" + scene.profile;
  if (!scene.version.empty()) out += " version=" + scene.version;
  out += "\n";
  std::set<const Node*> printed;
  for (auto& n : scene.root->children.get()) describeNode(*n, 1, "children", printed, out);
  for (const auto& r : scene.routes)
    out += "  ROUTE " + r.fromNode->defName() + "." + std::string(r.fromField->name()) + " TO " +
           r.toNode->defName() + "." + std::string(r.toField->name()) + "\n";
  return out;
}

}  // namespace millsim
