#pragma once
// One expanded ProtoInstance: the value each interface field has for it
// (its fieldValue, else the declared default) and the inner fields that IS
// connects to it. Connecting an inner field copies an initializeOnly or
// inputOutput value into it; a ROUTE to or from the instance's interface
// field is made to or from the connected inner fields (routeEnds).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "millsim/core/Diagnostics.h"
#include "millsim/core/Node.h"
#include "millsim/x3d/ProtoDeclaration.h"

namespace millsim {

struct InstanceField {
  const ProtoFieldDecl* decl = nullptr;
  std::optional<std::string> value;          // SF/MF values other than nodes
  std::vector<std::shared_ptr<Node>> nodes;  // SFNode/MFNode values
  bool nodesGiven = false;                   // a fieldValue gave the nodes (else the default is read)
  SourceLocation valueAt;                    // where the value was written
  UnitScale valueUnits;                      // the units of the file it was written in
  std::vector<Field*> inner;                 // the fields IS connects to this one
};

// What a ROUTE end on a proto instance's field stands for.
struct RouteEnds {
  bool isInterfaceField = false;                // false: not a field of the proto (try the node's own fields)
  const std::vector<Field*>* fields = nullptr;  // null: refused, with an error
  std::string proto;                            // the proto's name
};

class ProtoInstanceInterface {
public:
  explicit ProtoInstanceInterface(std::shared_ptr<ProtoDecl> proto);
  const ProtoDecl& proto() const { return *proto_; }
  InstanceField* field(std::string_view name);
  std::map<std::string, InstanceField, std::less<>>& fields() { return fields_; }

  // <fieldValue name value> on the instance: checks the field exists, can take
  // a value and that the value has the field's type. `units` are those of the
  // file that wrote it. Returns the field set, or null after an error.
  InstanceField* setValue(const std::string& name, const std::optional<std::string>& value,
                          const SourceLocation& nameAt, const SourceLocation& valueAt, const UnitScale& units,
                          DiagnosticSink& sink);

  // <connect nodeField protoField> inside the body: `node`'s field `nodeField`
  // IS this instance's field `protoField`.
  void connect(Node& node, const std::string& nodeField, const std::string& protoField, const SourceLocation& at,
               DiagnosticSink& sink);
  // The same for a nested ProtoInstance: its interface field `inner` IS our `protoField`.
  // Returns the outer field, so that `inner`'s connections can be added to it once expanded.
  InstanceField* connectNested(InstanceField& inner, const std::string& innerName, const std::string& protoField,
                               const SourceLocation& at, DiagnosticSink& sink);

  // The inner fields a ROUTE from (asSource) or to this instance's field `name`
  // stands for; null when the proto has no such field (set_x and x_changed
  // name an inputOutput x). Reports an access that does not allow the route.
  RouteEnds routeEnds(const std::string& name, bool asSource, const SourceLocation& at, DiagnosticSink& sink);

  // "proto 'P' has no field 'x' (its fields are ...)"
  std::string unknownField(const std::string& name) const;

private:
  std::shared_ptr<ProtoDecl> proto_;
  std::map<std::string, InstanceField, std::less<>> fields_;
};

}  // namespace millsim
