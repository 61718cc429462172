#include "millsim/x3d/ProtoExpansion.h"

#include "millsim/core/NodeRegistry.h"

namespace millsim {

namespace {
std::string typeAndAccess(const ProtoFieldDecl& f) {
  return std::string(accessName(f.access)) + " " + std::string(fieldTypeName(f.type));
}

std::string shown(const std::string& v) { return v.size() > 40 ? v.substr(0, 37) + "..." : v; }
}  // namespace

ProtoInstanceInterface::ProtoInstanceInterface(std::shared_ptr<ProtoDecl> proto) : proto_(std::move(proto)) {
  for (const auto& f : proto_->fields) {
    InstanceField& i = fields_[f.name];
    i.decl = &f;
    i.value = f.value;
    i.valueAt = f.where;
    i.valueUnits = f.units;
  }
}

InstanceField* ProtoInstanceInterface::field(std::string_view name) {
  auto it = fields_.find(name);
  return it == fields_.end() ? nullptr : &it->second;
}

std::string ProtoInstanceInterface::unknownField(const std::string& name) const {
  std::string list;
  for (const auto& f : proto_->fields) list += (list.empty() ? "'" : ", '") + f.name + "'";
  return "proto '" + proto_->name + "' has no field '" + name + "' (" +
         (list.empty() ? std::string("it declares no fields") : "its fields are " + list) + ")" +
         didYouMean(closestNames(name, proto_->fieldNames()));
}

InstanceField* ProtoInstanceInterface::setValue(const std::string& name, const std::optional<std::string>& value,
                                                const SourceLocation& nameAt, const SourceLocation& valueAt,
                                                const UnitScale& units, DiagnosticSink& sink) {
  InstanceField* f = field(name);
  if (!f) {
    sink.error(nameAt, "fieldValue: " + unknownField(name));
    return nullptr;
  }
  const ProtoFieldDecl& d = *f->decl;
  if (!settableInFile(d.access)) {
    sink.error(nameAt, "fieldValue: field '" + name + "' of proto '" + proto_->name + "' is " +
                           std::string(accessName(d.access)) + " and cannot be given a value");
    return nullptr;
  }
  if (isNodeType(d.type)) {
    // value="NULL": no node, as ClassicVRML writes it (and X3D editors in XML).
    if (value && !isNullNodeValue(*value)) {
      sink.error(valueAt, "fieldValue: field '" + name + "' of proto '" + proto_->name + "' is " +
                              std::string(fieldTypeName(d.type)) + ": give its nodes as child elements, not a value");
      return nullptr;
    }
    f->nodes.clear();
    f->nodesGiven = true;
    f->valueAt = valueAt;
    return f;
  }
  if (!value) {
    sink.error(nameAt, "fieldValue: field '" + name + "' of proto '" + proto_->name + "' needs a value");
    return nullptr;
  }
  if (auto bad = invalidValue(d.type, *value)) {
    sink.error(valueAt, "fieldValue: bad value '" + shown(*value) + "' for field '" + name + "' of proto '" +
                            proto_->name + "', which expects " + std::string(fieldTypeName(d.type)) + ": " + *bad);
    return nullptr;
  }
  f->value = value;
  f->valueAt = valueAt;
  f->valueUnits = units;
  return f;
}

void ProtoInstanceInterface::connect(Node& node, const std::string& nodeField, const std::string& protoField,
                                     const SourceLocation& at, DiagnosticSink& sink) {
  Field* inner = node.field(nodeField);
  const std::string where = " (in proto '" + proto_->name + "')";
  if (!inner) {
    std::vector<std::string> names;
    for (Field* f : node.fields()) names.emplace_back(f->name());
    sink.error(at, "IS connect: " + node.typeName() + " has no field '" + nodeField + "'" + where +
                       didYouMean(closestNames(nodeField, names)));
    return;
  }
  InstanceField* f = field(protoField);
  if (!f) {
    sink.error(at, "IS connect of " + node.typeName() + "." + nodeField + ": " + unknownField(protoField));
    return;
  }
  const ProtoFieldDecl& d = *f->decl;
  if (inner->type() != d.type) {
    sink.error(at, "IS connect: " + node.typeName() + "." + nodeField + " is " +
                       std::string(fieldTypeName(inner->type())) + " but field '" + protoField + "' of proto '" +
                       proto_->name + "' is " + std::string(fieldTypeName(d.type)));
    return;
  }
  if (!canConnect(d.access, inner->access())) {
    sink.error(at, "IS connect: " + node.typeName() + "." + nodeField + " is " +
                       std::string(accessName(inner->access())) + " and cannot be connected to " + typeAndAccess(d) +
                       " field '" + protoField + "' of proto '" + proto_->name + "'");
    return;
  }
  f->inner.push_back(inner);
  if (!settableInFile(d.access)) return;  // events only: the routes are made to the inner field
  if (auto* nf = dynamic_cast<NodeFieldBase*>(inner)) {
    for (const auto& n : f->nodes) {
      if (inner->type() == FieldType::SFNode && !nf->nodes().empty()) break;
      try {
        nf->add(n);
      } catch (const ValueError& e) {
        sink.error(f->valueAt, "field '" + protoField + "' of proto '" + proto_->name + "' (IS " + node.typeName() +
                                   "." + nodeField + "): " + e.what());
      }
    }
    return;
  }
  if (!f->value) return;
  try {
    inner->setFromSceneText(*f->value, f->valueUnits);
  } catch (const ValueError& e) {
    sink.error(f->valueAt, "bad value '" + shown(*f->value) + "' for field '" + protoField + "' of proto '" +
                               proto_->name + "' (IS " + node.typeName() + "." + nodeField + "): " + e.what());
  }
}

InstanceField* ProtoInstanceInterface::connectNested(InstanceField& inner, const std::string& innerName,
                                                     const std::string& protoField, const SourceLocation& at,
                                                     DiagnosticSink& sink) {
  InstanceField* f = field(protoField);
  if (!f) {
    sink.error(at, "IS connect of field '" + innerName + "': " + unknownField(protoField));
    return nullptr;
  }
  const ProtoFieldDecl& d = *f->decl;
  const ProtoFieldDecl& e = *inner.decl;
  if (e.type != d.type || !canConnect(d.access, e.access)) {
    sink.error(at, "IS connect: field '" + innerName + "' (" + typeAndAccess(e) + ") cannot be connected to " +
                       typeAndAccess(d) + " field '" + protoField + "' of proto '" + proto_->name + "'");
    return nullptr;
  }
  if (settableInFile(d.access) && settableInFile(e.access)) {
    if (isNodeType(d.type)) {
      inner.nodes = f->nodes;
      inner.nodesGiven = true;
    } else if (f->value) {
      inner.value = f->value;
    }
    inner.valueAt = f->valueAt;
    inner.valueUnits = f->valueUnits;
  }
  return f;
}

RouteEnds ProtoInstanceInterface::routeEnds(const std::string& name, bool asSource, const SourceLocation& at,
                                            DiagnosticSink& sink) {
  InstanceField* f = field(name);
  if (!f) {
    const std::string prefix = "set_", suffix = "_changed";
    std::string base;
    if (!asSource && name.rfind(prefix, 0) == 0) base = name.substr(prefix.size());
    if (asSource && name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      base = name.substr(0, name.size() - suffix.size());
    f = base.empty() ? nullptr : field(base);
    if (f && f->decl->access != Access::InputOutput) f = nullptr;
  }
  if (!f) return {};
  const Access a = f->decl->access;
  const bool allowed = a == Access::InputOutput || a == (asSource ? Access::OutputOnly : Access::InputOnly);
  if (!allowed) {
    sink.error(at, "ROUTE " + std::string(asSource ? "from" : "to") + " field '" + name + "' of proto '" +
                       proto_->name + "': it is " + std::string(accessName(a)) + " and cannot be a route " +
                       (asSource ? "source" : "destination"));
    return {true, nullptr, proto_->name};
  }
  return {true, &f->inner, proto_->name};
}

}  // namespace millsim
