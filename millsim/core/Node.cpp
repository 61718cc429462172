#include "millsim/core/Node.h"

#include "millsim/core/NodeKinds.h"

namespace millsim {

Field* Node::field(std::string_view name) const {
  for (Field* f : fields_)
    if (f->name() == name) return f;
  return nullptr;
}

MetadataField::MetadataField(Node* owner)
    : NodeFieldBase(owner, "metadata", Access::InputOutput,
                    "Information about this node: a Metadata* node (MetadataString, MetadataSet, ...). Accepted; not "
                    "acted on by MillSim.") {}

void MetadataField::set(std::shared_ptr<Node> n) {
  value_ = std::move(n);
  stale_ = false;
  changed();
}

std::string MetadataField::toString() const { return get() ? get()->typeName() : "NULL"; }
std::string_view MetadataField::acceptsKind() const { return MetadataObject::kindName; }
bool MetadataField::accepts(const Node& n) const { return dynamic_cast<const MetadataObject*>(&n) != nullptr; }

void MetadataField::add(std::shared_ptr<Node> n) {
  if (!accepts(*n)) throw ValueError("field 'metadata' expects X3DMetadataObject, not " + n->typeName());
  if (value_)
    throw ValueError("field 'metadata' already holds a " + value_->typeName() +
                     " (an SFNode field takes one node; gather several in a MetadataSet)");
  set(std::move(n));
}

}  // namespace millsim
