#pragma once
// NodeRegistry: the node types a loader may create, by X3D name. Filled
// explicitly (registerStandardNodes, plugins' entry points), never by static
// initialisers, so what exists is exactly what was asked for.
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "millsim/core/NodeType.h"

namespace millsim {

class Scene;
class DiagnosticSink;

// A check of a whole loaded scene (the structure no single node can see:
// several devices, a device under a Transform, a tool larger than the
// volume). The loader runs every registered check after reading the main
// file, so `check`, `run`, `replay` and `render` report the same problems.
using SceneCheck = void (*)(const Scene& scene, DiagnosticSink& sink);

class NodeRegistry {
public:
  // Throws std::invalid_argument if the name is taken or the type is incomplete.
  void add(NodeType type);
  const NodeType* find(std::string_view name) const;
  std::shared_ptr<Node> create(std::string_view name) const;
  std::vector<const NodeType*> all() const;  // sorted by name
  std::size_t size() const { return types_.size(); }

  // Closest registered names to a misspelt one, for "did you mean" hints.
  std::vector<std::string> suggest(std::string_view name, std::size_t max = 3) const;

  // Adds a whole-scene check (once: adding the same function again does nothing).
  void addSceneCheck(SceneCheck check);
  const std::vector<SceneCheck>& sceneChecks() const { return checks_; }

private:
  std::map<std::string, NodeType, std::less<>> types_;
  std::vector<SceneCheck> checks_;
};

// The standard X3D node types MillSim provides.
void registerStandardNodes(NodeRegistry& registry);
// Every node type MillSim itself provides (standard X3D nodes and MillSim's own).
void registerBuiltinNodes(NodeRegistry& registry);
NodeRegistry builtinRegistry();

// Edit distance used for "did you mean" suggestions (case-insensitive).
std::size_t editDistance(std::string_view a, std::string_view b);
// Names from `candidates` close enough to `word` to suggest, best first.
std::vector<std::string> closestNames(std::string_view word, const std::vector<std::string>& candidates,
                                      std::size_t max = 3);
// "; did you mean 'a', 'b'?" for the suggestions, or "" when there are none.
std::string didYouMean(const std::vector<std::string>& suggestions);

}  // namespace millsim
