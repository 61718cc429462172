#pragma once
// NodeType: what the registry knows about a kind of node before any exists:
// its X3D name, the parent field it fills by default, one line of
// documentation, and how to make one. The fields themselves are declared on the
// node class (see Field.h); tools list them from a freshly made instance.
#include <functional>
#include <memory>
#include <string>

namespace millsim {

class Node;

struct NodeType {
  std::string name;            // X3D element name, e.g. "Transform"
  std::string containerField;  // parent field filled when containerField is not given
  std::string component;       // grouping for docs, e.g. "Grouping", "Haptics"
  std::string doc;             // one line
  std::function<std::shared_ptr<Node>()> create;
};

// Builds the NodeType of a node class T that has a default constructor.
template <class T>
NodeType makeNodeType(std::string name, std::string containerField, std::string component, std::string doc) {
  return NodeType{std::move(name), std::move(containerField), std::move(component), std::move(doc),
                  [] { return std::make_shared<T>(); }};
}

}  // namespace millsim
