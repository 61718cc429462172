#pragma once
// Node: the base of every scene-graph node. A node is its fields; they register
// themselves on construction, in declaration order, so the node's field table
// is exactly what its class declares.
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "millsim/core/Diagnostics.h"
#include "millsim/core/Field.h"
#include "millsim/core/NodeType.h"

namespace millsim {

class Node;

// The common parent of node fields: the loader fills them without knowing the
// node class they expect.
class NodeFieldBase : public Field {
public:
  using Field::Field;
  // Name of the node kind this field accepts, e.g. "X3DChildNode".
  virtual std::string_view acceptsKind() const = 0;
  virtual bool accepts(const Node& n) const = 0;
  // Adds a node (MFNode) or sets it (SFNode). Throws ValueError if not accepted
  // or, for SFNode, already set.
  virtual void add(std::shared_ptr<Node> n) = 0;
  virtual std::vector<std::shared_ptr<Node>> nodes() const = 0;

  void setFromString(std::string_view) override {
    throw ValueError("node fields take child elements, not an attribute value");
  }
};

// X3D's `metadata` field, which every node has (X3DNode): one metadata node
// (MetadataString, MetadataSet, ...; X3DMetadataObject) about its owner.
// Node itself declares it, so it is not a template of a kind declared after Node.
class MetadataField : public NodeFieldBase {
public:
  explicit MetadataField(Node* owner);
  const std::shared_ptr<Node>& get() const {
    refresh();
    return value_;
  }
  void set(std::shared_ptr<Node> n);
  FieldType type() const override { return FieldType::SFNode; }
  std::string toString() const override;
  std::string_view acceptsKind() const override;
  bool accepts(const Node& n) const override;
  void add(std::shared_ptr<Node> n) override;
  std::vector<std::shared_ptr<Node>> nodes() const override {
    if (get()) return {get()};
    return {};
  }

protected:
  void assignFrom(const Field& source) override { value_ = static_cast<const MetadataField&>(source).get(); }
  mutable std::shared_ptr<Node> value_;
};

class Node : public std::enable_shared_from_this<Node> {
public:
  // Node fields name the kind of node they take; a kind is a class derived from
  // Node that redeclares kindName (X3DChildNode, X3DGeometryNode, ...).
  static constexpr std::string_view kindName = "a node";

  Node() = default;
  virtual ~Node() = default;
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  virtual const NodeType& nodeType() const = 0;
  const std::string& typeName() const { return nodeType().name; }

  std::span<Field* const> fields() const { return fields_; }
  Field* field(std::string_view name) const;

  // DEF name, if the scene gave one, and where the node was written.
  const std::string& defName() const { return defName_; }
  void setDefName(std::string name) { defName_ = std::move(name); }
  const SourceLocation& location() const { return location_; }
  void setLocation(SourceLocation where) { location_ = std::move(where); }

  // Called once after the node and all its children were read, in child-first
  // order. Cross-field checks go here; report problems to the sink.
  virtual void initialize(DiagnosticSink&) {}
  // False: graphics do not draw this node's descendants (an assessment
  // region's shapes mark where it is; they are not something to see).
  virtual bool showsDescendants() const { return true; }
  // False: graphics do not draw what this one of its node fields holds (a
  // Collision's proxy, which is only for collision); its other fields are drawn.
  virtual bool showsField(const Field&) const { return true; }
  // True: descendants that are shown are drawn see-through (an assessment
  // region made visible shows where it is without hiding the tooth).
  virtual bool showsDescendantsTranslucent() const { return false; }

private:
  friend class Field;
  void registerField(Field* f) { fields_.push_back(f); }
  std::vector<Field*> fields_;
  std::string defName_;
  SourceLocation location_;

public:
  // Declared after fields_ (so that it can register), before every derived
  // class's fields: the first field of every node, as in X3D's tables.
  MetadataField metadata{this};
};

// SFNode restricted to nodes of class T (a Node kind with its own kindName).
template <class T> class SFNodeOf : public NodeFieldBase {
public:
  SFNodeOf(Node* owner, std::string_view name, Access access, std::string_view doc)
      : NodeFieldBase(owner, name, access, doc) {}

  const std::shared_ptr<T>& get() const {
    refresh();
    return value_;
  }
  void set(std::shared_ptr<T> n) {
    value_ = std::move(n);
    stale_ = false;
    changed();
  }

  FieldType type() const override { return FieldType::SFNode; }
  std::string toString() const override { return get() ? std::string(get()->typeName()) : "NULL"; }
  std::string_view acceptsKind() const override { return T::kindName; }
  bool accepts(const Node& n) const override { return dynamic_cast<const T*>(&n) != nullptr; }
  void add(std::shared_ptr<Node> n) override {
    if (!accepts(*n))
      throw ValueError("field '" + std::string(name()) + "' expects " + std::string(T::kindName) + ", not " +
                       n->typeName());
    if (value_)
      throw ValueError("field '" + std::string(name()) + "' already holds a " + value_->typeName() +
                       " (an SFNode field takes one node)");
    set(std::dynamic_pointer_cast<T>(n));
  }
  std::vector<std::shared_ptr<Node>> nodes() const override {
    if (get()) return {get()};
    return {};
  }

protected:
  void assignFrom(const Field& source) override { value_ = static_cast<const SFNodeOf&>(source).get(); }
  mutable std::shared_ptr<T> value_;
};

// MFNode restricted to nodes of class T.
template <class T> class MFNodeOf : public NodeFieldBase {
public:
  MFNodeOf(Node* owner, std::string_view name, Access access, std::string_view doc)
      : NodeFieldBase(owner, name, access, doc) {}

  const std::vector<std::shared_ptr<T>>& get() const {
    refresh();
    return value_;
  }
  void set(std::vector<std::shared_ptr<T>> v) {
    value_ = std::move(v);
    stale_ = false;
    changed();
  }

  FieldType type() const override { return FieldType::MFNode; }
  std::string toString() const override {
    std::string s;
    for (const auto& n : get()) s += (s.empty() ? "" : " ") + n->typeName();
    return s;
  }
  std::string_view acceptsKind() const override { return T::kindName; }
  bool accepts(const Node& n) const override { return dynamic_cast<const T*>(&n) != nullptr; }
  void add(std::shared_ptr<Node> n) override {
    if (!accepts(*n))
      throw ValueError("field '" + std::string(name()) + "' expects " + std::string(T::kindName) + ", not " +
                       n->typeName());
    // In place: copying the list for every child made loading n siblings O(n²).
    refresh();
    value_.push_back(std::dynamic_pointer_cast<T>(n));
    stale_ = false;
    changed();
  }
  std::vector<std::shared_ptr<Node>> nodes() const override { return {get().begin(), get().end()}; }

protected:
  void assignFrom(const Field& source) override { value_ = static_cast<const MFNodeOf&>(source).get(); }
  mutable std::vector<std::shared_ptr<T>> value_;
};

}  // namespace millsim
