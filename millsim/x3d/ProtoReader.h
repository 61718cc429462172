#pragma once
// Reads the prototype elements of an X3D file for the loader: ProtoDeclare and
// ExternProtoDeclare (statements of <Scene> and <ProtoBody>), ProtoInstance
// (expanded at once into a fresh copy of its proto's body), IS/connect inside
// a body, and ROUTE ends on an instance's interface fields. It keeps which
// protos are visible where, the instances being expanded (recursion is an
// error, never a hang) and the files ExternProtoDeclare read. Private to the
// x3d room: it names libxml2 types.
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "millsim/core/Diagnostics.h"
#include "millsim/core/Node.h"
#include "millsim/x3d/ProtoDeclaration.h"
#include "millsim/x3d/ProtoExpansion.h"
#include "millsim/x3d/XmlDocument.h"

namespace millsim {

// What the proto reader needs from the loader that drives it.
class ProtoHost {
public:
  // Reads one node element (DEF/USE, fields, children) in `doc`'s current DEF namespace.
  virtual std::shared_ptr<Node> readNodeElement(Document& doc, xmlNode* el, std::size_t tag, const SourceLocation& loc,
                                                std::vector<const Node*>& ancestors) = 0;
  virtual void readRouteElement(Document& doc, xmlNode* el) = 0;
  // True for an element; reports text that does not belong inside `parent`.
  virtual bool isElement(Document& doc, xmlNode* c, std::string_view parent) = 0;
  // Reads and parses a scene file (size limit, encodings); null after an error.
  virtual std::unique_ptr<Document> openDocument(const std::filesystem::path& p, const SourceLocation& loc) = 0;
  // Is this file (canonical path) being read: the scene file or an Inline around the current element?
  virtual bool isBeingRead(const std::filesystem::path& canonical) const = 0;
  // Keeps a node that no node field holds (a body's nodes after the first).
  virtual void keepUnattached(std::shared_ptr<Node> node) = 0;

protected:
  virtual ~ProtoHost() = default;
};

class ProtoReader {
public:
  // `maxElements`: the body elements all instances of a load may expand to (protos
  // that instantiate others several times multiply).
  ProtoReader(ProtoHost& host, DiagnosticSink& sink, bool allowFileAccess, std::size_t maxElements)
      : host_(host), sink_(sink), allowFileAccess_(allowFileAccess), maxElements_(maxElements) {}

  // Reads a ProtoDeclare or ExternProtoDeclare; false for any other element.
  bool readStatement(Document& doc, xmlNode* el);
  // Expands a <ProtoInstance>: the result is the first node of its body. Null after an error.
  std::shared_ptr<Node> readInstance(Document& doc, xmlNode* el, std::size_t tag, const SourceLocation& loc,
                                     std::vector<const Node*>& ancestors);
  // An <IS> child of `node`.
  void readIs(Document& doc, xmlNode* el, Node& node);

  // Is `node` what a ProtoInstance expanded to (so USE of it may be written <ProtoInstance USE>)?
  bool isInstance(const Node* node) const { return instances_.count(node) != 0; }
  // A ROUTE end `field` on `node`: the inner fields it stands for when `node` is a proto instance.
  RouteEnds routeEnds(const Node* node, const std::string& field, bool asSource, const SourceLocation& at);
  // The interface field names of the instance `node` (for "did you mean").
  std::vector<std::string> interfaceFieldNames(const Node* node) const;

  // While an Inline file is read: its protos are its own and no ProtoBody is around it.
  class FileScope {
  public:
    explicit FileScope(ProtoReader& r, std::shared_ptr<ProtoScope> scope = std::make_shared<ProtoScope>())
        : r_(r),
          scope_(std::exchange(r.scope_, std::move(scope))),
          instance_(std::exchange(r.activeInstance_, nullptr)) {}
    ~FileScope() {
      r_.scope_ = std::move(scope_);
      r_.activeInstance_ = instance_;
    }
    FileScope(const FileScope&) = delete;
    FileScope& operator=(const FileScope&) = delete;

  private:
    ProtoReader& r_;
    std::shared_ptr<ProtoScope> scope_;
    ProtoInstanceInterface* instance_;
  };

private:
  void declare(const std::string& name, std::shared_ptr<ProtoDecl> decl, const SourceLocation& at);
  void readExtern(Document& doc, xmlNode* el);
  std::shared_ptr<ProtoScope> externScope(const std::filesystem::path& p, const std::filesystem::path& canonical,
                                          const SourceLocation& loc);
  template <class Visit>
  void forEachConnect(Document& doc, xmlNode* is, Visit&& visit);
  void readFieldValue(Document& doc, xmlNode* el, std::size_t tag, const SourceLocation& loc,
                      ProtoInstanceInterface& inst, std::vector<const Node*>& ancestors);
  std::shared_ptr<Node> expandBody(const ProtoDecl& decl, ProtoInstanceInterface& inst, const SourceLocation& at,
                                   std::vector<const Node*>& ancestors);

  ProtoHost& host_;
  DiagnosticSink& sink_;
  bool allowFileAccess_;
  std::size_t maxElements_;
  std::shared_ptr<ProtoScope> scope_ = std::make_shared<ProtoScope>();  // the protos visible here
  ProtoInstanceInterface* activeInstance_ = nullptr;                    // the instance whose ProtoBody is being read
  std::vector<const ProtoDecl*> expanding_;                             // instances being expanded, outermost first
  std::size_t expandedElements_ = 0;
  std::map<const Node*, std::shared_ptr<ProtoInstanceInterface>> instances_;  // by the node an instance is
  std::vector<std::unique_ptr<Document>> externDocs_;                         // files ExternProtoDeclare read
  std::map<std::filesystem::path, std::shared_ptr<ProtoScope>> externFiles_;  // their protos, by canonical path
  std::vector<std::filesystem::path> externLoading_;
  DefMap externDefs_;  // unused: only an extern file's declarations are read, never its nodes
};

}  // namespace millsim
