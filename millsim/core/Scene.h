#pragma once
// Scene: what the loader made of one X3D file: the top-level nodes, the DEF
// names, the routes, the node types it could use (built-ins plus plugins), and
// where it came from. The Scene owns its nodes; fields and routes refer to each
// other by plain pointers inside it.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "millsim/core/NodeKinds.h"
#include "millsim/core/NodeRegistry.h"

namespace millsim {

// A route owns both its nodes: one that the graph no longer holds (a later
// DEF of the same name took the name, or its parent refused it) is still
// routed, and its fields must outlive the route (the fuzzer found the
// Scene unrouting a freed node's field).
struct RouteRecord {
  std::shared_ptr<Node> fromNode;
  Field* fromField;
  std::shared_ptr<Node> toNode;
  Field* toField;
  SourceLocation where;
};

// The <Scene> element: the holder of the top-level nodes. Not a registered
// node type, because no X3D file names it as a node.
class SceneRoot : public Node {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }
  MFNodeOf<ChildNode> children{this, "children", Access::InputOutput, "The scene's top-level nodes."};
};

class Scene {
public:
  Scene();
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  std::filesystem::path file;  // empty for scenes read from a string
  std::string profile;
  std::string version;
  std::vector<std::pair<std::string, std::string>> meta;  // <meta name content>
  std::shared_ptr<SceneRoot> root;                      // the <Scene> element's children
  // Nodes that no node field holds: a ProtoInstance's body nodes after the
  // first (X3D draws only the first; the others, e.g. sensors, keep their
  // routes). Owned here; forEachNode visits them after the tree.
  std::vector<std::shared_ptr<Node>> unattached;
  std::map<std::string, std::shared_ptr<Node>, std::less<>> defs;
  std::vector<RouteRecord> routes;
  NodeRegistry registry;                                  // built-ins plus loaded plugins
  std::vector<std::filesystem::path> plugins;             // libraries ImportLibrary loaded

  std::shared_ptr<Node> def(std::string_view name) const;

  // Visits every node once (depth first, document order), including those
  // inside Inline files and reached through several USEs.
  void forEachNode(const std::function<void(Node&)>& visit) const;
  template <class T> std::vector<T*> nodesOfType() const {
    std::vector<T*> out;
    forEachNode([&](Node& n) {
      if (auto* t = dynamic_cast<T*>(&n)) out.push_back(t);
    });
    return out;
  }
  std::size_t nodeCount() const;
};

// The node tree as `millsim check` prints it: one node per line, fields that
// differ from their defaults, DEF/USE, then the routes.
std::string describeScene(const Scene& scene);

}  // namespace millsim
