#pragma once
// X3D prototypes as declared: <ProtoDeclare> (its <ProtoInterface> fields and
// where its <ProtoBody> is) and <ExternProtoDeclare> (a name, urls and the
// fields it expects). Reading a declaration makes no node; a ProtoInstance is
// expanded from it later (millsim/x3d/ProtoExpansion.h). Private to the x3d
// room: it names libxml2 types.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "millsim/core/Diagnostics.h"
#include "millsim/core/FieldValues.h"
#include "millsim/x3d/XmlDocument.h"

namespace millsim {

// One <field> of a ProtoInterface or ExternProtoDeclare.
struct ProtoFieldDecl {
  std::string name;
  FieldType type = FieldType::SFBool;
  Access access = Access::InitializeOnly;
  std::optional<std::string> value;  // the default as written (not for SFNode/MFNode)
  const xmlNode* element = nullptr;  // its child elements are an SFNode/MFNode field's default nodes
  SourceLocation where;
  UnitScale units;  // the declaring file's units, in which the default is written
};

struct ProtoScope;

struct ProtoDecl {
  std::string name;
  SourceLocation where;
  std::vector<ProtoFieldDecl> fields;
  const xmlNode* body = nullptr;      // <ProtoBody>
  std::size_t bodyElements = 0;       // elements inside it: what one instance costs to expand
  bool unavailable = false;           // an ExternProtoDeclare with an empty url: its instances are skipped
  Document* doc = nullptr;            // the file that declares it (its text, tree and folder)
  // The protos its body may instantiate: the scope that declares it. Weak, as
  // that scope holds this declaration (a shared one leaked the pair); the
  // reader keeps file scopes alive, and a body's scope lives while it expands.
  std::weak_ptr<ProtoScope> scope;

  const ProtoFieldDecl* field(std::string_view n) const;
  std::vector<std::string> fieldNames() const;
};

// The protos declared in one file, or in one ProtoBody (which also sees its parent's).
struct ProtoScope {
  std::shared_ptr<ProtoScope> parent;
  std::map<std::string, std::shared_ptr<ProtoDecl>, std::less<>> protos;
  std::string first;  // the first proto declared here (an ExternProtoDeclare url without '#name' names it)

  std::shared_ptr<ProtoDecl> find(std::string_view name) const;
  std::vector<std::string> names() const;
};

// "SFVec3f" -> FieldType; nullopt for a type MillSim has no field of (SFImage, SFMatrix4f, ...).
std::optional<FieldType> fieldTypeFromName(std::string_view name);
std::optional<Access> accessFromName(std::string_view name);
// Why `text` is not a value of `type`, or nullopt when it is one.
std::optional<std::string> invalidValue(FieldType type, std::string_view text);
// May an inner field of access `inner` be IS-connected to an interface field of access `iface`?
bool canConnect(Access iface, Access inner);
bool isNodeType(FieldType t);
// "NULL" (white space around it allowed): an SFNode or MFNode value that holds no node.
bool isNullNodeValue(std::string_view text);

// Reads the <field> children of a ProtoInterface or ExternProtoDeclare;
// `owner` names the proto in messages. Bad fields are reported and left out.
std::vector<ProtoFieldDecl> readProtoFields(Document& doc, const xmlNode* parent, const std::string& owner,
                                            bool withValues, DiagnosticSink& sink);

// Reads a <ProtoDeclare>: its name, its interface and where its body is.
// Null (with an error) when it cannot be used.
std::shared_ptr<ProtoDecl> readProtoDeclare(Document& doc, const xmlNode* el, DiagnosticSink& sink);

struct ExternProtoDecl {
  std::string name;
  std::vector<std::string> urls;
  std::vector<ProtoFieldDecl> fields;
  SourceLocation where;
};
std::optional<ExternProtoDecl> readExternProtoDeclare(Document& doc, const xmlNode* el, DiagnosticSink& sink);

// Checks that `found` (the ProtoDeclare an extern url names) has every field
// the ExternProtoDeclare lists, with the same type and access.
bool externMatches(const ExternProtoDecl& ext, const ProtoDecl& found, DiagnosticSink& sink);

}  // namespace millsim
