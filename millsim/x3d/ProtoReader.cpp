#include "millsim/x3d/ProtoReader.h"

#include <algorithm>
#include <optional>
#include <utility>

#include "millsim/core/NodeRegistry.h"
#include "millsim/x3d/SceneFileText.h"

namespace millsim {

namespace fs = std::filesystem;

// ProtoDeclare and ExternProtoDeclare are statements of <Scene> and <ProtoBody>.
bool ProtoReader::readStatement(Document& doc, xmlNode* el) {
  const std::string_view n = nameOf(el);
  if (n == "ProtoDeclare") {
    if (auto decl = readProtoDeclare(doc, el, sink_)) declare(decl->name, decl, decl->where);
    return true;
  }
  if (n == "ExternProtoDeclare") {
    readExtern(doc, el);
    return true;
  }
  return false;
}

void ProtoReader::declare(const std::string& name, std::shared_ptr<ProtoDecl> decl, const SourceLocation& at) {
  if (!decl->scope.lock()) decl->scope = scope_;
  if (auto prev = scope_->protos.find(name); prev != scope_->protos.end())
    sink_.warning(at, "proto '" + name + "' is already declared at " + prev->second->where.str() +
                          "; this declaration takes the name for what follows");
  if (scope_->first.empty()) scope_->first = name;
  scope_->protos[name] = std::move(decl);
}

void ProtoReader::readExtern(Document& doc, xmlNode* el) {
  auto ext = readExternProtoDeclare(doc, el, sink_);
  if (!ext) return;
  const SourceLocation& loc = ext->where;
  if (ext->urls.empty()) {  // warned: its instances are skipped
    auto decl = std::make_shared<ProtoDecl>();
    decl->name = ext->name, decl->where = loc, decl->fields = ext->fields, decl->unavailable = true;
    declare(ext->name, decl, loc);
    return;
  }
  if (!allowFileAccess_) {
    sink_.error(loc, "ExternProtoDeclare '" + ext->name + "' is disabled for this load (no file access)");
    return;
  }
  std::string tried;
  for (const std::string& url : ext->urls) {
    if (url.find("://") != std::string::npos) {
      tried += "\n  " + url + ": network URLs are not allowed";
      continue;
    }
    const std::size_t hash = url.find('#');
    const std::string file = url.substr(0, hash);
    const std::string wanted = hash == std::string::npos ? std::string() : url.substr(hash + 1);
    if (file.empty()) {  // "#Name": a proto of this file, declared before
      auto decl = scope_->find(wanted);
      if (!decl) {
        tried += "\n  " + url + ": this file declares no proto '" + wanted + "' before it";
        continue;
      }
      if (externMatches(*ext, *decl, sink_)) declare(ext->name, decl, loc);
      return;
    }
    const auto local = localSceneFile(file, doc.dir, tried);
    if (!local) continue;
    const fs::path& p = local->path;
    const fs::path& canonical = local->canonical;
    // The files being read from the one asked for again to here: a cycle, which would never end.
    bool cycle = host_.isBeingRead(canonical);
    std::string chain = cycle ? canonical.filename().string() + " -> " : std::string();
    for (const auto& open : externLoading_) {
      if (open == canonical) cycle = true;
      if (cycle) chain += open.filename().string() + " -> ";
    }
    if (cycle) {
      sink_.error(loc, "ExternProtoDeclare '" + ext->name + "': '" + p.string() + "' is already being loaded (" +
                           (externLoading_.empty() ? std::string("it is the file being read")
                                                   : "a cycle: " + chain + canonical.filename().string()) +
                           "); declare the proto with ProtoDeclare in one of the files");
      return;
    }
    std::shared_ptr<ProtoScope> fileProtos = externScope(p, canonical, loc);
    if (!fileProtos) return;
    const std::string name = wanted.empty() ? fileProtos->first : wanted;
    auto it = fileProtos->protos.find(name);
    if (it == fileProtos->protos.end()) {
      std::vector<std::string> names;
      for (const auto& [k, d] : fileProtos->protos) names.push_back(k);
      sink_.error(loc,
                  "ExternProtoDeclare '" + ext->name + "': '" + p.string() + "' declares no proto '" + name + "'" +
                      (names.empty() ? std::string(" (it declares none)") : didYouMean(closestNames(name, names))));
      return;
    }
    if (externMatches(*ext, *it->second, sink_)) declare(ext->name, it->second, loc);
    return;
  }
  sink_.error(loc, "ExternProtoDeclare '" + ext->name + "' could not load any of its urls:" + tried);
}

// The protos a file declares at the top of its <Scene> (read once per load).
std::shared_ptr<ProtoScope> ProtoReader::externScope(const fs::path& p, const fs::path& canonical,
                                                     const SourceLocation& loc) {
  if (auto it = externFiles_.find(canonical); it != externFiles_.end()) return it->second;
  std::unique_ptr<Document> d = host_.openDocument(p, loc);
  if (!d) return nullptr;
  d->defs = &externDefs_;
  auto fileProtos = std::make_shared<ProtoScope>();
  externLoading_.push_back(canonical);
  std::optional<FileScope> inFile(std::in_place, *this, fileProtos);
  xmlNode* root = xmlDocGetRootElement(d->xml);
  xmlNode* sceneEl = root && nameOf(root) == "Scene" ? root : nullptr;
  if (root && nameOf(root) == "X3D")
    for (xmlNode* c = root->children; c; c = c->next)
      if (c->type == XML_ELEMENT_NODE && nameOf(c) == "Scene") sceneEl = c;
  if (!sceneEl) sink_.error({p.string(), 1, 1}, "'" + p.string() + "' has no <Scene> to declare protos in");
  for (xmlNode* c = sceneEl ? sceneEl->children : nullptr; c && !sink_.full(); c = c->next)
    if (c->type == XML_ELEMENT_NODE) readStatement(*d, c);  // other nodes are not read
  inFile.reset();
  externLoading_.pop_back();
  externDocs_.push_back(std::move(d));
  externFiles_[canonical] = fileProtos;
  return fileProtos;
}

// Calls visit(nodeField, protoField, where) for each <connect> of an <IS>.
template <class Visit>
void ProtoReader::forEachConnect(Document& doc, xmlNode* is, Visit&& visit) {
  for (xmlNode* c = is->children; c && !sink_.full(); c = c->next) {
    if (!host_.isElement(doc, c, "IS")) continue;
    std::size_t tag;
    SourceLocation at = doc.locate(c, &tag);
    if (nameOf(c) != "connect") {
      sink_.error(at, "unexpected <" + std::string(nameOf(c)) +
                          "> inside <IS>; expected <connect nodeField='...' protoField='...'/>");
      continue;
    }
    const xmlAttr* nf = findAttr(c, "nodeField");
    const xmlAttr* pf = findAttr(c, "protoField");
    if (!nf || !pf) {
      sink_.error(at, std::string("<connect> needs nodeField and protoField (") + (!nf ? "nodeField" : "protoField") +
                          " is missing)");
      continue;
    }
    visit(doc.value(nf), doc.value(pf), at);
  }
}

void ProtoReader::readIs(Document& doc, xmlNode* el, Node& node) {
  SourceLocation loc = doc.locate(el);
  if (!activeInstance_) {
    sink_.error(loc, "<IS> belongs inside a <ProtoBody>; this " + node.typeName() + " is not in one");
    return;
  }
  forEachConnect(doc, el, [&](const std::string& nodeField, const std::string& protoField, const SourceLocation& at) {
    activeInstance_->connect(node, nodeField, protoField, at, sink_);
  });
}

void ProtoReader::readFieldValue(Document& doc, xmlNode* el, std::size_t tag, const SourceLocation& loc,
                                 ProtoInstanceInterface& inst, std::vector<const Node*>& ancestors) {
  const xmlAttr* n = findAttr(el, "name");
  if (!n) {
    sink_.error(loc, "a <fieldValue> of ProtoInstance '" + inst.proto().name + "' needs a name");
    return;
  }
  const std::string name = doc.value(n);
  const xmlAttr* v = findAttr(el, "value");
  std::optional<std::string> value;
  if (v) value = doc.value(v);
  InstanceField* f =
      inst.setValue(name, value, doc.locateAttr(tag, "name", loc), v ? doc.locateAttr(tag, "value", loc) : loc,
                    doc.units, sink_);
  for (xmlNode* c = el->children; c && f && !sink_.full(); c = c->next) {
    if (!host_.isElement(doc, c, "fieldValue")) continue;
    std::size_t childTag;
    SourceLocation childLoc = doc.locate(c, &childTag);
    if (!isNodeType(f->decl->type)) {
      sink_.error(childLoc, "fieldValue '" + name + "' of proto '" + inst.proto().name + "' is " +
                                std::string(fieldTypeName(f->decl->type)) + ": it takes a value, not nodes");
      return;
    }
    std::shared_ptr<Node> node = host_.readNodeElement(doc, c, childTag, childLoc, ancestors);
    if (!node) continue;
    if (f->decl->type == FieldType::SFNode && !f->nodes.empty()) {
      sink_.error(childLoc, "fieldValue '" + name + "' of proto '" + inst.proto().name +
                                "' is SFNode and already holds a " + f->nodes.front()->typeName());
      continue;
    }
    f->nodes.push_back(std::move(node));
  }
}

// A ProtoInstance is the first node of a fresh copy of its proto's body,
// with the instance's field values put in through IS.
std::shared_ptr<Node> ProtoReader::readInstance(Document& doc, xmlNode* el, std::size_t tag, const SourceLocation& loc,
                                                std::vector<const Node*>& ancestors) {
  const xmlAttr* nameAttr = findAttr(el, "name");
  if (!nameAttr || doc.value(nameAttr).empty()) {
    sink_.error(loc, "a <ProtoInstance> needs a name: the proto it instantiates");
    return nullptr;
  }
  const std::string name = doc.value(nameAttr);
  std::shared_ptr<ProtoDecl> decl = scope_->find(name);
  if (!decl) {
    sink_.error(doc.locateAttr(tag, "name", loc),
                "ProtoInstance of '" + name + "': no ProtoDeclare or ExternProtoDeclare of that name before it" +
                    didYouMean(closestNames(name, scope_->names())));
    return nullptr;
  }
  if (decl->unavailable) {
    sink_.warning(loc, "ProtoInstance of '" + name + "' skipped: its ExternProtoDeclare (" + decl->where.str() +
                           ") has an empty url");
    if (const xmlAttr* def = findAttr(el, "DEF"))
      doc.skippedDefs[doc.value(def)] = "is a ProtoInstance of '" + name + "', whose ExternProtoDeclare has an empty url";
    return nullptr;
  }
  const std::size_t errorsBefore = sink_.errorCount();
  for (const xmlAttr* a = el->properties; a; a = a->next) {
    std::string_view n = nameOf(reinterpret_cast<const xmlNode*>(a));
    if (a->ns || n == "name" || n == "DEF" || n == "containerField" || n == "class" || n == "id" || n == "style")
      continue;
    sink_.error(doc.locateAttr(tag, n, loc), "ProtoInstance of '" + name +
                                                 "' takes its field values as <fieldValue name='" + std::string(n) +
                                                 "' value='...'/> children, not as attribute '" + std::string(n) + "'");
  }
  auto inst = std::make_shared<ProtoInstanceInterface>(decl);
  std::vector<std::pair<InstanceField*, InstanceField*>> nested;  // (our field, the instance's field it IS)
  for (xmlNode* c = el->children; c && !sink_.full(); c = c->next) {
    if (!host_.isElement(doc, c, "ProtoInstance")) continue;
    std::size_t childTag;
    SourceLocation childLoc = doc.locate(c, &childTag);
    const std::string_view cn = nameOf(c);
    if (cn == "fieldValue") {
      readFieldValue(doc, c, childTag, childLoc, *inst, ancestors);
    } else if (cn == "IS") {
      if (!activeInstance_) {
        sink_.error(childLoc, "<IS> belongs inside a <ProtoBody>; this ProtoInstance of '" + name + "' is not in one");
        continue;
      }
      forEachConnect(
          doc, c, [&](const std::string& nodeField, const std::string& protoField, const SourceLocation& at) {
            InstanceField* ours = inst->field(nodeField);
            if (!ours) {
              sink_.error(at, "IS connect: " + inst->unknownField(nodeField));
              return;
            }
            if (InstanceField* outer = activeInstance_->connectNested(*ours, nodeField, protoField, at, sink_))
              nested.emplace_back(outer, ours);
          });
    } else if (cn.rfind("Metadata", 0) != 0) {
      sink_.error(childLoc, "unexpected <" + std::string(cn) + "> inside <ProtoInstance name='" + name +
                                "'>; expected <fieldValue>");
    }
  }
  if (sink_.errorCount() != errorsBefore) return nullptr;
  std::string chain;
  for (const ProtoDecl* p : expanding_) chain += (chain.empty() ? "'" : " -> '") + p->name + "'";
  for (const ProtoDecl* p : expanding_)
    if (p == decl.get()) {
      sink_.error(loc, "ProtoInstance of '" + name + "' inside its own expansion (" + chain + " -> '" + name +
                           "'): the proto would never finish expanding");
      return nullptr;
    }
  if (expandedElements_ > maxElements_) return nullptr;  // reported once, below
  expandedElements_ += std::max<std::size_t>(decl->bodyElements, 1);
  if (expandedElements_ > maxElements_) {
    sink_.error(loc, "ProtoInstance of '" + name + "': expanding the protos of this scene would make more than " +
                         std::to_string(maxElements_) +
                         " elements (protos that each instantiate others several times multiply); MillSim stops here");
    return nullptr;
  }
  std::shared_ptr<Node> root = expandBody(*decl, *inst, loc, ancestors);
  if (!root) return nullptr;
  for (auto [outer, ours] : nested) outer->inner.insert(outer->inner.end(), ours->inner.begin(), ours->inner.end());
  if (const xmlAttr* def = findAttr(el, "DEF")) {
    const std::string defName = doc.value(def);
    if (!isBlank(defName)) {
      if (auto prev = doc.defs->find(defName); prev != doc.defs->end())
        sink_.warning(doc.locateAttr(tag, "DEF", loc),
                      "DEF name '" + defName + "' is already used by the " + prev->second->typeName() + " at " +
                          prev->second->location().str() + "; this ProtoInstance takes the name for what follows");
      doc.skippedDefs.erase(defName);
      root->setDefName(defName);
      (*doc.defs)[defName] = root;
    }
  }
  instances_[root.get()] = inst;
  return root;
}

std::shared_ptr<Node> ProtoReader::expandBody(const ProtoDecl& decl, ProtoInstanceInterface& inst,
                                              const SourceLocation& at, std::vector<const Node*>& ancestors) {
  Document& body = *decl.doc;
  // The body's DEF names are the instance's own; its protos see those declared around the ProtoDeclare.
  DefMap privateDefs;
  std::map<std::string, std::string, std::less<>> privateSkipped;
  DefMap* outerDefs = std::exchange(body.defs, &privateDefs);
  std::swap(body.skippedDefs, privateSkipped);
  auto bodyScope = std::make_shared<ProtoScope>();
  bodyScope->parent = decl.scope.lock();
  auto outerScope = std::exchange(scope_, bodyScope);
  auto* outerInstance = std::exchange(activeInstance_, &inst);
  expanding_.push_back(&decl);
  const std::size_t errorsBefore = sink_.errorCount();

  // SFNode/MFNode fields without a fieldValue take fresh copies of their default nodes.
  for (auto& [fieldName, f] : inst.fields()) {
    if (!isNodeType(f.decl->type) || f.nodesGiven || !settableInFile(f.decl->access)) continue;
    for (xmlNode* c = f.decl->element->children; c && !sink_.full(); c = c->next) {
      // Metadata about the field declaration is not one of its default nodes.
      if (c->type != XML_ELEMENT_NODE || nameOf(c).rfind("Metadata", 0) == 0) continue;
      std::size_t childTag;
      SourceLocation childLoc = body.locate(c, &childTag);
      if (auto node = host_.readNodeElement(body, c, childTag, childLoc, ancestors)) f.nodes.push_back(std::move(node));
    }
  }
  std::shared_ptr<Node> root;
  for (xmlNode* c = decl.body->children; c && !sink_.full(); c = c->next) {
    if (!host_.isElement(body, c, "ProtoBody")) continue;
    if (nameOf(c) == "ROUTE") {
      host_.readRouteElement(body, c);
      continue;
    }
    if (readStatement(body, c)) continue;
    std::size_t childTag;
    SourceLocation childLoc = body.locate(c, &childTag);
    std::shared_ptr<Node> node = host_.readNodeElement(body, c, childTag, childLoc, ancestors);
    if (!node) continue;
    // X3D: the first node is what the instance is; the others are not drawn but run (sensors, routes).
    if (!root)
      root = node;
    else
      host_.keepUnattached(std::move(node));
  }

  expanding_.pop_back();
  activeInstance_ = outerInstance;
  scope_ = std::move(outerScope);
  std::swap(body.skippedDefs, privateSkipped);
  body.defs = outerDefs;
  if (!root && sink_.errorCount() == errorsBefore)
    sink_.error(at, "proto '" + decl.name + "' has no node in its <ProtoBody> to be the instance");
  if (sink_.errorCount() != errorsBefore) {
    sink_.note(at, "in this ProtoInstance of '" + decl.name + "' (declared at " + decl.where.str() + ")");
    return nullptr;
  }
  return root;
}

RouteEnds ProtoReader::routeEnds(const Node* node, const std::string& field, bool asSource, const SourceLocation& at) {
  auto it = instances_.find(node);
  if (it == instances_.end()) return {};
  return it->second->routeEnds(field, asSource, at, sink_);
}

std::vector<std::string> ProtoReader::interfaceFieldNames(const Node* node) const {
  auto it = instances_.find(node);
  return it == instances_.end() ? std::vector<std::string>{} : it->second->proto().fieldNames();
}

}  // namespace millsim
