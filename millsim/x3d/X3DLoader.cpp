#include "millsim/x3d/X3DLoader.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "millsim/std/ImportLibrary.h"
#include "millsim/std/Inline.h"
#include "millsim/std/MetadataSet.h"
#include "millsim/x3d/H3dNodeNames.h"
#include "millsim/x3d/ProtoReader.h"
#include "millsim/x3d/SceneFileText.h"
#include "millsim/x3d/SourceText.h"
#include "millsim/x3d/UnitStatement.h"
#include "millsim/x3d/X3dStandardNodes.h"

namespace millsim {

namespace fs = std::filesystem;

std::string LoadResult::report() const {
  std::string out;
  for (const auto& d : diagnostics) out += d.str() + "\n";
  return out;
}

namespace {

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
  return s;
}

class Loader : private ProtoHost {
public:
  Loader(const NodeRegistry& registry, const LoadOptions& options)
      : options_(options), sink_(options.maxErrors), scene_(std::make_unique<Scene>()),
        protos_(*this, sink_, options.allowFileAccess, options.maxProtoElements) {
    scene_->registry = registry;
    sink_.setProgress(options.progress);
  }

  LoadResult load(std::string text, std::string label, fs::path dir, fs::path canonical) {
    if (!canonical.empty()) inlineStack_.push_back(canonical);
    Document doc(SourceText(std::move(label), std::move(text)), std::move(dir), &scene_->defs);
    if (parseXml(doc)) readTopLevel(doc, scene_->root->children, true);
    for (std::size_t i = 0; i < options_.overrides.size(); ++i)
      if (!sink_.hasErrors() && overridesApplied_[i] == 0)
        sink_.error(overrideLocation(options_.overrides[i]),
                    "the scene has no " + options_.overrides[i].type + " whose field to set");
    // Whole-scene checks (NodeRegistry::addSceneCheck) need a scene whose nodes all loaded.
    if (!sink_.hasErrors())
      for (SceneCheck check : scene_->registry.sceneChecks()) check(*scene_, sink_);
    std::vector<Diagnostic> all = sink_.take();
    if (options_.strict)
      for (auto& d : all)
        if (d.severity == Severity::Warning) {
          d.severity = Severity::Error;
          d.message += " (an error with --strict)";
        }
    for (auto& d : all)
      if (d.severity == Severity::Error) return {nullptr, std::move(all)};
    return {std::move(scene_), std::move(all)};
  }

private:
  // ---- XML ----------------------------------------------------------------
  bool parseXml(Document& doc) {
    struct Collected {
      bool have = false;
      int line = 0, column = 0;
      std::string message;
    } first;
    auto handler = [](void* user, xmlErrorPtr e) {
      auto* c = static_cast<Collected*>(user);
      if (c->have || !e || e->level < XML_ERR_ERROR) return;
      c->have = true;
      c->line = e->line;
      c->column = e->int2;
      c->message = e->message ? e->message : "malformed XML";
      while (!c->message.empty() && (c->message.back() == '\n' || c->message.back() == ' ')) c->message.pop_back();
      // libxml2 suggests an option the user cannot set; say what the limit is instead.
      if (e->code == XML_ERR_INTERNAL_ERROR && c->message.rfind("Excessive depth in document", 0) == 0)
        c->message = "elements nest deeper than 256 levels, the most MillSim reads (libxml2's limit); "
                     "flatten the scene, e.g. fewer nested Transforms or Groups";
      // A bare '&' (as in phantom:tooth?size=...&voxel=...) starts an entity reference in XML.
      const bool entityRef = e->code == XML_ERR_ENTITYREF_SEMICOL_MISSING || e->code == XML_ERR_UNDECLARED_ENTITY ||
                             e->code == XML_WAR_UNDECLARED_ENTITY ||
                             (e->code == XML_ERR_NAME_REQUIRED && c->message.find("EntityRef") != std::string::npos);
      if (entityRef)
        c->message += " (an '&' in an attribute must be written '&amp;' in XML, e.g. "
                      "url='\"phantom:tooth?size=64,64,64&amp;voxel=0.0004\"')";
    };
    const std::string& text = doc.src.text();
    if (isBlank(text)) {
      sink_.error({doc.src.file(), 1, 1}, "the file is empty; expected an <X3D> document");
      return false;
    }
    // Entity declarations (and so expansion bombs) are refused before libxml2
    // expands anything; only the prolog can declare them.
    const std::size_t root = text.find("<X3D");
    const std::size_t entity = text.find("<!ENTITY");
    if (entity != std::string::npos && (root == std::string::npos || entity < root)) {
      sink_.error(doc.src.at(entity), "entity declarations are not allowed in X3D scenes");
      return false;
    }
    xmlSetStructuredErrorFunc(&first, handler);
    // No NOENT (entities stay unexpanded), no DTDLOAD, no network.
    const int opts = XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_BIG_LINES;
    doc.xml = xmlReadMemory(text.data(), static_cast<int>(text.size()), doc.src.file().c_str(), nullptr, opts);
    xmlSetStructuredErrorFunc(nullptr, nullptr);
    if (!doc.xml || first.have) {
      sink_.error({doc.src.file(), first.line, first.column},
                  "malformed XML: " + (first.have ? first.message : std::string("the document could not be read")));
      return false;
    }
    if (doc.xml->intSubset && doc.xml->intSubset->entities) {
      sink_.error({doc.src.file(), 0, 0}, "entity declarations are not allowed in X3D scenes");
      return false;
    }
    return true;
  }

  SourceLocation locate(Document& doc, const xmlNode* el, std::size_t* tagStart = nullptr) {
    return doc.locate(el, tagStart);
  }

  SourceLocation locateAttr(Document& doc, std::size_t tagStart, std::string_view attr, const SourceLocation& fallback) {
    return doc.locateAttr(tagStart, attr, fallback);
  }

  // ---- X3D / head / Scene ---------------------------------------------------
  // Reads <X3D><head/><Scene/></X3D>, putting the Scene's nodes into `target`.
  void readTopLevel(Document& doc, MFNodeOf<ChildNode>& target, bool isMainFile) {
    xmlNode* root = xmlDocGetRootElement(doc.xml);
    if (!root) {
      sink_.error({doc.src.file(), 1, 1}, "the document has no root element; expected <X3D>");
      return;
    }
    if (nameOf(root) != "X3D") {
      readFragment(doc, root, target);
      return;
    }
    std::size_t rootTag;
    SourceLocation rootLoc = locate(doc, root, &rootTag);
    for (const xmlAttr* a = root->properties; a; a = a->next) {
      if (a->ns) continue;  // xmlns:xsd, xsd:noNamespaceSchemaLocation
      std::string_view n = nameOf(reinterpret_cast<const xmlNode*>(a));
      if (n == "profile" || n == "version") {
        if (isMainFile) (n == "profile" ? scene_->profile : scene_->version) = attrValue(doc.xml, a);
      } else {
        sink_.warning(locateAttr(doc, rootTag, n, rootLoc), "unknown attribute '" + std::string(n) + "' on <X3D> ignored");
      }
    }
    bool sawScene = false;
    for (xmlNode* c = root->children; c && !sink_.full(); c = c->next) {
      if (!checkNonElement(doc, c, "X3D")) continue;
      std::string_view n = nameOf(c);
      if (n == "head") {
        readHead(doc, c, isMainFile);
      } else if (n == "Scene") {
        SourceLocation loc = locate(doc, c);
        if (sawScene) {
          sink_.error(loc, "a second <Scene> element; an X3D file has exactly one");
          continue;
        }
        sawScene = true;
        readSceneChildren(doc, c, target);
      } else {
        sink_.error(locate(doc, c), "unexpected <" + std::string(n) + "> inside <X3D>; expected <head> or <Scene>");
      }
    }
    if (!sawScene && !sink_.hasErrors()) sink_.error(rootLoc, "the <X3D> element has no <Scene>");
  }

  void readSceneChildren(Document& doc, xmlNode* scene, MFNodeOf<ChildNode>& target) {
    std::vector<const Node*> ancestors;
    forEachChild(doc, scene, "Scene", [&](xmlNode* child) {
      const std::string_view n = nameOf(child);
      if (n == "ROUTE") readRoute(doc, child);
      else if (n == "EXPORT") readExport(doc, child);
      else if (n == "IMPORT") readImport(doc, child);
      else if (!protos_.readStatement(doc, child)) readAndAttach(doc, child, target, "Scene", ancestors);
    });
  }

  // EXPORT localDEF [AS]: a node of this file an Inline's importer may name.
  void readExport(Document& doc, xmlNode* el) {
    std::size_t tag;
    const SourceLocation loc = locate(doc, el, &tag);
    const xmlAttr* local = findAttr(el, "localDEF");
    const xmlAttr* as = findAttr(el, "AS");
    if (!local) {
      sink_.error(loc, "EXPORT needs a localDEF: the DEF name of the node it exports");
      return;
    }
    const std::string name = attrValue(doc.xml, local);
    const std::string exported = as && !attrValue(doc.xml, as).empty() ? attrValue(doc.xml, as) : name;
    if (auto it = doc.defs->find(name); it != doc.defs->end()) {
      doc.exports[exported] = it->second;
    } else if (auto skipped = doc.skippedDefs.find(name); skipped != doc.skippedDefs.end()) {
      doc.exports[exported] = nullptr;  // an importer skips it too, with a warning
    } else {
      sink_.error(locateAttr(doc, tag, "localDEF", loc), "EXPORT localDEF '" + name + "' names no DEF before it");
    }
  }

  // IMPORT inlineDEF importedDEF [AS]: an Inline's exported node under a
  // name of this file, for ROUTEs. One the Inline does not export (or whose
  // Inline was not loaded) is skipped with a warning, as browsers do, and so
  // are the ROUTEs that name it.
  void readImport(Document& doc, xmlNode* el) {
    std::size_t tag;
    const SourceLocation loc = locate(doc, el, &tag);
    const xmlAttr* inlineAttr = findAttr(el, "inlineDEF");
    const xmlAttr* importedAttr = findAttr(el, "importedDEF");
    const xmlAttr* as = findAttr(el, "AS");
    if (!inlineAttr || !importedAttr) {
      sink_.error(loc, "IMPORT needs an inlineDEF (the Inline's DEF name) and an importedDEF (the name it EXPORTs)");
      return;
    }
    const std::string inlineName = attrValue(doc.xml, inlineAttr), imported = attrValue(doc.xml, importedAttr);
    const std::string name = as && !attrValue(doc.xml, as).empty() ? attrValue(doc.xml, as) : imported;
    const auto it = doc.defs->find(inlineName);
    const auto* inl = it == doc.defs->end() ? nullptr : dynamic_cast<const Inline*>(it->second.get());
    if (!inl) {
      sink_.error(locateAttr(doc, tag, "inlineDEF", loc),
                  "IMPORT inlineDEF '" + inlineName + "' " +
                      (it == doc.defs->end() ? "names no DEF before it" : "is a " + it->second->typeName() + ", not an Inline"));
      return;
    }
    const auto& exports = inlineExports_[inl];
    const auto e = exports.find(imported);
    if (e == exports.end() || !e->second) {
      std::string known;
      for (const auto& [k, n] : exports) known += (known.empty() ? "" : ", ") + ("'" + k + "'");
      sink_.warning(locateAttr(doc, tag, "importedDEF", loc),
                    "IMPORT of '" + imported + "' from Inline '" + inlineName + "' ignored: " +
                        (!inl->load.get() ? std::string("the Inline is not loaded (load FALSE)")
                         : e != exports.end() ? "the node it exports is one MillSim skipped"
                         : known.empty()      ? std::string("its file EXPORTs nothing (or it did not load)")
                                              : "its file EXPORTs only " + known));
      doc.skippedDefs[name] = "could not be IMPORTed from Inline '" + inlineName + "'";
      return;
    }
    if (doc.defs->count(name)) {
      sink_.error(as ? locateAttr(doc, tag, "AS", loc) : locateAttr(doc, tag, "importedDEF", loc),
                  "IMPORT names '" + name + "', which is already a DEF name of this file; give it another AS name");
      return;
    }
    (*doc.defs)[name] = e->second;
  }

  // H3DLoad reads a file whose root is <Scene> or a node (<Group>,
  // <Transform>, <DeviceInfo>, ...) as that scene fragment; so does MillSim.
  void readFragment(Document& doc, xmlNode* root, MFNodeOf<ChildNode>& target) {
    const std::string name(nameOf(root));
    if (name == "Scene") {
      locate(doc, root);
      readSceneChildren(doc, root, target);
      return;
    }
    if (name == "DeviceInfo" || scene_->registry.find(name) || findStandardNode(name) || findH3dNode(name)) {
      std::vector<const Node*> ancestors;
      if (name == "DeviceInfo") {
        locate(doc, root);
        forEachChild(doc, root, "DeviceInfo", [&](xmlNode* child) {
          if (nameOf(child) == "ROUTE") readRoute(doc, child);
          else readAndAttach(doc, child, target, "Scene", ancestors);
        });
      } else {
        readAndAttach(doc, root, target, "Scene", ancestors);
      }
      return;
    }
    sink_.error(locate(doc, root), "the root element is <" + name +
                                       ">; expected <X3D>, or a <Scene> or node element (e.g. <Group>) as H3DLoad reads");
  }

  // The element children of `parent`, with the children of any <DeviceInfo>
  // in its place: H3DAPI's DeviceInfo only groups the scene's devices, and
  // MillSim's device nodes work the same inside it as outside.
  // Visits in document order, as the source locator's cursor needs.
  template <class Visit> void forEachChild(Document& doc, xmlNode* parent, std::string_view label, Visit&& visit) {
    for (xmlNode* c = parent->children; c && !sink_.full(); c = c->next) {
      if (!checkNonElement(doc, c, label)) continue;
      if (nameOf(c) != "DeviceInfo") {
        visit(c);
        continue;
      }
      std::size_t tag;
      SourceLocation loc = locate(doc, c, &tag);
      for (const xmlAttr* a = c->properties; a; a = a->next) {
        std::string_view n = nameOf(reinterpret_cast<const xmlNode*>(a));
        if (!a->ns && n != "containerField" && n != "class" && n != "id")
          sink_.warning(locateAttr(doc, tag, n, loc), "attribute '" + std::string(n) +
                                                          "' of <DeviceInfo> ignored: MillSim reads DeviceInfo only "
                                                          "as a group of device nodes");
      }
      forEachChild(doc, c, "DeviceInfo", visit);
    }
  }

  void readHead(Document& doc, xmlNode* head, bool isMainFile) {
    locate(doc, head);
    for (xmlNode* c = head->children; c; c = c->next) {
      if (!checkNonElement(doc, c, "head")) continue;
      std::string_view n = nameOf(c);
      std::size_t tag;
      SourceLocation loc = locate(doc, c, &tag);
      if (n == "meta") {
        const xmlAttr* name = findAttr(c, "name");
        const xmlAttr* content = findAttr(c, "content");
        if (isMainFile && name) scene_->meta.emplace_back(attrValue(doc.xml, name), content ? attrValue(doc.xml, content) : "");
      } else if (n == "unit") {
        readUnit(doc, c, tag, loc);
      } else if (n != "component") {
        sink_.error(loc, "unexpected <" + std::string(n) + "> inside <head>; expected <meta>, <component> or <unit>");
      }
    }
  }

  // X3D 4.0 units: from here on the file's values of that category (and of
  // quantities derived from it, e.g. N/m) are converted to SI as they are read.
  void readUnit(Document& doc, xmlNode* el, std::size_t tag, const SourceLocation& loc) {
    UnitStatement u;
    const xmlAttr* attrs[3] = {findAttr(el, "category"), findAttr(el, "name"), findAttr(el, "conversionFactor")};
    if (attrs[0]) u.category = attrValue(doc.xml, attrs[0]);
    if (attrs[1]) u.name = attrValue(doc.xml, attrs[1]);
    if (attrs[2]) u.conversionFactor = attrValue(doc.xml, attrs[2]);
    if (auto bad = invalidUnit(u)) {
      const char* culprit = bad->rfind("unit category", 0) == 0 ? "category"
                            : bad->find("needs a name") != std::string::npos ? "name"
                                                                              : "conversionFactor";
      sink_.error(locateAttr(doc, tag, culprit, loc), "invalid <unit> statement: " + *bad);
      return;
    }
    if (!doc.unitCategories.insert(u.category).second) {
      sink_.error(locateAttr(doc, tag, "category", loc),
                  "a second <unit> statement for category '" + u.category + "'; X3D allows one per category");
      return;
    }
    double& factor = u.category == "length" ? doc.units.length
                     : u.category == "angle" ? doc.units.angle
                     : u.category == "mass"  ? doc.units.mass
                                             : doc.units.force;
    factor = unitFactor(u);
  }

  // Comments and whitespace are fine anywhere; other text is a mistake.
  // Returns true when `c` is an element to process.
  bool checkNonElement(Document& doc, xmlNode* c, std::string_view parent) {
    if (c->type == XML_ELEMENT_NODE) return true;
    if (c->type == XML_TEXT_NODE || c->type == XML_CDATA_SECTION_NODE) {
      std::string text = c->content ? reinterpret_cast<const char*>(c->content) : "";
      if (!isBlank(text)) {
        const std::size_t first = text.find_first_not_of(" \t\r\n");
        std::size_t lineEnd = text.find_first_of("\r\n", first);
        std::string shown = text.substr(first, std::min<std::size_t>(lineEnd == std::string::npos ? 40 : lineEnd - first, 40));
        while (!shown.empty() && (shown.back() == ' ' || shown.back() == '\t')) shown.pop_back();
        const std::size_t at = doc.src.findText(shown);
        sink_.error(at == std::string::npos ? doc.src.atLine(xmlGetLineNo(c)) : doc.src.at(at),
                    "unexpected text '" + shown + "' inside <" + std::string(parent) + ">; only elements belong here");
      }
    } else if (c->type == XML_ENTITY_REF_NODE) {
      sink_.error(doc.src.atLine(xmlGetLineNo(c)), "entity references are not allowed in X3D scenes");
    }
    return false;
  }

  // ---- nodes ------------------------------------------------------------------
  // Reads the node element `el` and adds it to `target` (a parent's node field).
  void readAndAttach(Document& doc, xmlNode* el, NodeFieldBase& target, std::string_view parentLabel,
                     std::vector<const Node*>& ancestors) {
    std::size_t tag;
    SourceLocation loc = locate(doc, el, &tag);
    std::shared_ptr<Node> node = readNode(doc, el, tag, loc, ancestors);
    if (node) attach(node, target, parentLabel, loc);
  }

  void attach(const std::shared_ptr<Node>& node, NodeFieldBase& target, std::string_view parentLabel,
              const SourceLocation& loc) {
    if (!target.accepts(*node)) {
      sink_.error(loc, node->typeName() + " cannot go in field '" + std::string(target.name()) + "' of " +
                           std::string(parentLabel) + ": that field takes " + std::string(target.acceptsKind()));
      return;
    }
    if (const auto held = target.type() == FieldType::SFNode ? target.nodes() : std::vector<std::shared_ptr<Node>>{};
        !held.empty()) {
      sink_.error(loc, node->typeName() + " cannot go in field '" + std::string(target.name()) + "' of " +
                           std::string(parentLabel) + ": it already holds the " + held.front()->typeName() + " at " +
                           held.front()->location().str() + " (an SFNode field takes one node)");
      return;
    }
    try {
      target.add(node);
    } catch (const ValueError& e) {
      sink_.error(loc, e.what());
    }
  }

  std::shared_ptr<Node> readNode(Document& doc, xmlNode* el, std::size_t tag, const SourceLocation& loc,
                                 std::vector<const Node*>& ancestors) {
    const std::string type(nameOf(el));
    if (const xmlAttr* use = findAttr(el, "USE")) return readUse(doc, el, tag, loc, attrValue(doc.xml, use), ancestors);

    if (type == "ProtoInstance") return protos_.readInstance(doc, el, tag, loc, ancestors);
    if (type == "ProtoDeclare" || type == "ExternProtoDeclare") {
      sink_.error(loc, "<" + type + "> belongs in <Scene> or a <ProtoBody>, not inside a node");
      return nullptr;
    }
    std::shared_ptr<Node> node = scene_->registry.create(type);
    if (!node) {
      unknownNode(doc, el, type, loc);
      return nullptr;
    }
    node->setLocation(loc);

    if (const xmlAttr* def = findAttr(el, "DEF")) {
      std::string name = attrValue(doc.xml, def);
      SourceLocation defLoc = locateAttr(doc, tag, "DEF", loc);
      if (name.empty() || isBlank(name)) {
        sink_.warning(defLoc, "empty DEF name ignored; the " + type + " has no name");
      } else {
        // As in H3DAPI, a later DEF of the same name wins (for later USEs and ROUTEs).
        if (auto prev = doc.defs->find(name); prev != doc.defs->end())
          sink_.warning(defLoc, "DEF name '" + name + "' is already used by the " + prev->second->typeName() + " at " +
                                    prev->second->location().str() + "; this " + type +
                                    " takes the name for what follows (as in H3DAPI)");
        doc.skippedDefs.erase(name);
        node->setDefName(name);
        (*doc.defs)[name] = node;
      }
    }
    readFields(doc, el, *node, tag, loc);

    // Plugins register their node types before the rest of the file is read.
    if (auto* lib = dynamic_cast<ImportLibrary*>(node.get())) importLibrary(doc, *lib, loc);

    ancestors.push_back(node.get());
    forEachChild(doc, el, type, [&](xmlNode* c) {
      if (nameOf(c) == "ROUTE") {
        readRoute(doc, c);
        return;
      }
      if (nameOf(c) == "IS") {
        protos_.readIs(doc, c, *node);
        return;
      }
      std::size_t childTag;
      SourceLocation childLoc = locate(doc, c, &childTag);
      std::shared_ptr<Node> child = readNode(doc, c, childTag, childLoc, ancestors);
      if (!child) return;
      // containerField chooses the parent field; otherwise the child type's default.
      std::string fieldName = child->nodeType().containerField;
      // X3D 4.0: a metadata node inside a MetadataSet is one of its values; elsewhere it is the node's metadata.
      if (dynamic_cast<const MetadataSet*>(node.get()) && dynamic_cast<const MetadataObject*>(child.get()))
        fieldName = "value";
      if (const xmlAttr* cf = findAttr(c, "containerField")) fieldName = attrValue(doc.xml, cf);
      placeChild(doc, *node, child, fieldName, childTag, childLoc);
    });
    ancestors.pop_back();

    // After the children: a proto body's IS connections set fields too.
    applyOverrides(*node);
    if (auto* inl = dynamic_cast<Inline*>(node.get())) loadInline(doc, *inl, loc);
    node->initialize(sink_);
    return node;
  }

  // A name the registry does not know: a standard X3D node MillSim does not
  // implement is skipped with a warning (and its subtree with it); an H3DAPI
  // node says what MillSim has instead; anything else is an error.
  void unknownNode(Document& doc, xmlNode* el, const std::string& type, const SourceLocation& loc) {
    if (findStandardNode(type)) {
      // A scene of a thousand Cones should not print a thousand lines.
      const int seen = ++unsupportedSeen_[type];
      if (seen <= kWarningsPerUnsupportedType)
        sink_.warning(loc, "X3D node '" + type + "' is not supported by MillSim; ignored" +
                               (seen == kWarningsPerUnsupportedType
                                    ? " (further '" + type + "' nodes are ignored without a warning)"
                                    : std::string()));
      skipSubtree(doc, el);
      return;
    }
    if (const H3dNodeName* h3d = findH3dNode(type)) {
      std::string offer;
      if (h3d->kind != H3dNodeKind::Other) {
        std::vector<std::string> names;
        for (const NodeType* t : scene_->registry.all()) {
          // Renderers fill a device's hapticsRenderer field; devices are in the devices component.
          const bool match = h3d->kind == H3dNodeKind::Renderer ? t->containerField == "hapticsRenderer"
                                                                : t->component.find("devices") != std::string::npos;
          if (match) names.push_back(t->name);
        }
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        offer = std::string("; its ") + (h3d->kind == H3dNodeKind::Renderer ? "haptics renderers" : "devices") +
                " are " + list;
      }
      sink_.error(loc, "H3DAPI node '" + type + "' is not provided by MillSim" + offer);
      return;
    }
    sink_.error(loc, "unknown node type '" + type + "'" + didYouMean(scene_->registry.suggest(type)));
  }

  // Remembers the DEF names inside a skipped element, so that their USEs and ROUTEs are skipped too.
  void skipSubtree(Document& doc, xmlNode* el) {
    if (el->type != XML_ELEMENT_NODE) return;
    if (const xmlAttr* def = findAttr(el, "DEF")) {
      const std::string name = attrValue(doc.xml, def);
      if (!name.empty() && !doc.defs->count(name))
        doc.skippedDefs[name] = "is a " + std::string(nameOf(el)) + ", which MillSim does not support";
    }
    for (xmlNode* c = el->children; c; c = c->next) skipSubtree(doc, c);
  }

  void placeChild(Document& doc, Node& parent, const std::shared_ptr<Node>& child, const std::string& fieldName,
                  std::size_t childTag, const SourceLocation& childLoc) {
    Field* f = parent.field(fieldName);
    auto* nf = dynamic_cast<NodeFieldBase*>(f);
    if (!nf || !settableInFile(nf->access())) {
      std::vector<std::string> nodeFields;
      for (Field* pf : parent.fields())
        // Every node's metadata field is named only when the child could go there.
        if (pf->isNodeField() && settableInFile(pf->access()) &&
            (pf != &parent.metadata || parent.metadata.accepts(*child)))
          nodeFields.emplace_back(pf->name());
      std::string where = nodeFields.empty() ? parent.typeName() + " takes no child nodes"
                                             : parent.typeName() + "'s node fields are " + joinNames(nodeFields);
      SourceLocation at = locateAttr(doc, childTag, "containerField", childLoc);
      sink_.error(at, child->typeName() + " cannot be a child of " + parent.typeName() + ": no field '" + fieldName +
                          "' to hold it (" + where + ")" + didYouMean(closestNames(fieldName, nodeFields)));
      return;
    }
    attach(child, *nf, parent.typeName(), childLoc);
  }

  std::shared_ptr<Node> readUse(Document& doc, xmlNode* el, std::size_t tag, const SourceLocation& loc,
                                const std::string& name, const std::vector<const Node*>& ancestors) {
    for (const xmlAttr* a = el->properties; a; a = a->next) {
      std::string_view n = nameOf(reinterpret_cast<const xmlNode*>(a));
      if (!a->ns && n != "USE" && n != "containerField" && !(n == "name" && nameOf(el) == "ProtoInstance")) {
        sink_.error(locateAttr(doc, tag, n, loc),
                    "a USE element takes no other attributes (found '" + std::string(n) + "'); set fields on the DEF");
        return nullptr;
      }
    }
    for (xmlNode* c = el->children; c; c = c->next)
      if (c->type == XML_ELEMENT_NODE) {
        sink_.error(loc, "a USE element cannot have children");
        return nullptr;
      }
    auto it = doc.defs->find(name);
    if (it == doc.defs->end() && doc.skippedDefs.count(name)) return nullptr;  // its DEF was skipped, with a warning
    if (it == doc.defs->end()) {
      // X3D needs the DEF first; browsers skip a USE that comes before it with a warning.
      if (const xmlNode* later = name.empty() ? nullptr : laterDef(doc, el, name)) {
        sink_.warning(locateAttr(doc, tag, "USE", loc),
                      "USE '" + name + "' comes before its DEF (line " + std::to_string(xmlGetLineNo(later)) +
                          "); X3D needs the DEF first, so this USE is skipped");
        return nullptr;
      }
      std::vector<std::string> names;
      for (const auto& [k, v] : *doc.defs) names.push_back(k);
      sink_.error(locateAttr(doc, tag, "USE", loc), "USE '" + name + "' names no DEF earlier in this file" +
                                                        didYouMean(closestNames(name, names)));
      return nullptr;
    }
    if (it->second->typeName() != nameOf(el) && !(nameOf(el) == "ProtoInstance" && protos_.isInstance(it->second.get()))) {
      sink_.error(loc, "USE '" + name + "' refers to a " + it->second->typeName() + ", but the element is <" +
                           std::string(nameOf(el)) + ">");
      return nullptr;
    }
    for (const Node* a : ancestors)
      if (a == it->second.get()) {
        sink_.error(loc, "USE '" + name + "' inside its own definition would make a cycle");
        return nullptr;
      }
    return it->second;
  }

  static void indexDefs(const xmlNode* el, Document::DefPositions& index) {
    for (; el; el = el->next) {
      if (el->type != XML_ELEMENT_NODE) continue;
      const std::size_t at = index.order.size();
      index.order[el] = at;
      if (const xmlAttr* def = findAttr(el, "DEF"); def && def->children && def->children->content)
        index.defs.emplace(reinterpret_cast<const char*>(def->children->content), std::make_pair(at, el));
      if (nameOf(el) != "ProtoDeclare") indexDefs(el->children, index);
    }
  }
  // The first element after `use` whose DEF is `name`, or null.
  const xmlNode* laterDef(Document& doc, const xmlNode* use, const std::string& name) {
    Document::DefPositions& index = doc.defPositions;
    if (index.order.empty()) indexDefs(xmlDocGetRootElement(doc.xml), index);
    const auto at = index.order.find(use);
    if (at == index.order.end()) return nullptr;
    const auto [from, to] = index.defs.equal_range(name);
    for (auto it = from; it != to; ++it)
      if (it->second.first > at->second) return it->second.second;
    return nullptr;
  }

  void readFields(Document& doc, xmlNode* el, Node& node, std::size_t tag, const SourceLocation& loc) {
    for (const xmlAttr* a = el->properties; a && !sink_.full(); a = a->next) {
      if (a->ns) continue;  // namespaced attributes (xmlns:*, xsd:*) carry no field
      std::string_view n = nameOf(reinterpret_cast<const xmlNode*>(a));
      // X3D 4's id, class and style are for HTML pages and stylesheets; they set no field.
      if (n == "DEF" || n == "containerField" || n == "class" || n == "id" || n == "style") continue;
      SourceLocation at = locateAttr(doc, tag, n, loc);
      Field* f = node.field(n);
      if (!f) {
        std::vector<std::string> names;
        for (Field* nf : node.fields())
          if (settableInFile(nf->access()) && !nf->isNodeField()) names.emplace_back(nf->name());
        // A standard node's field no X3D version has is a browser's own
        // extension (Castle's Shape.shading, X_ITE's): browsers ignore what
        // they do not know, with a warning; so does MillSim (--strict: an
        // error). MillSim's own nodes stay strict: a misspelt tipRadius must
        // not pass.
        const std::string what = "unknown field '" + std::string(n) + "' of " + node.typeName();
        if (findStandardNode(node.typeName()))
          sink_.warning(at, what + " (no X3D version has it; another browser's extension?); ignored" +
                                didYouMean(closestNames(n, names)));
        else
          sink_.error(at, what + didYouMean(closestNames(n, names)));
        continue;
      }
      if (!settableInFile(f->access())) {
        sink_.error(at, "field '" + std::string(n) + "' of " + node.typeName() + " is " +
                            std::string(accessName(f->access())) + " and cannot be set in a file");
        continue;
      }
      if (f->isNodeField()) {
        sink_.error(at, "field '" + std::string(n) + "' of " + node.typeName() +
                            " takes a child node element, not an attribute value");
        continue;
      }
      const std::string value = attrValue(doc.xml, a);
      try {
        f->setFromSceneText(value, doc.units);
        warnOfUnitSlip(*f, node, at, value, doc.units);
      } catch (const ValueError& e) {
        if (readUnquotedString(*f, value, node, at)) continue;
        std::string shown = value.size() > 40 ? value.substr(0, 37) + "..." : value;
        const bool converted = !doc.units.si() && f->range() && !f->range()->quantity.dimensionless();
        sink_.error(at, "bad value '" + shown + "' for " + std::string(fieldTypeName(f->type())) + " field '" +
                            std::string(n) + "' of " + node.typeName() + ": " + e.what() +
                            (converted ? " (in SI units, after converting from the file's <unit> statements)" : ""));
      }
    }
  }

  // A value ten times or more outside what lessons use (Range::usually) is
  // most often written in another unit than the one it is read in: a torque
  // limit meant in N·m in a file whose <unit> makes lengths millimetres.
  void warnOfUnitSlip(const Field& f, const Node& node, const SourceLocation& at, const std::string& text,
                      const UnitScale& units) {
    const Range* r = f.range();
    if (!r || !r->hasUsual() || (f.type() != FieldType::SFFloat && f.type() != FieldType::SFDouble)) return;
    const std::string unit = siUnit(r->quantity);
    double v = 0.0;
    try {
      v = std::stod(f.toString());
    } catch (const std::exception&) {
      return;
    }
    // (A float field holds 0.002 as a hair over it: ten times is ten times to a float's precision.)
    const bool low = v > 0.0 && v * 10.0 <= r->usualLo * (1.0 + 1e-6), high = v >= r->usualHi * 10.0 * (1.0 - 1e-6);
    if (!low && !high) return;
    const double factor = units.factor(r->quantity);
    std::string read = "'" + text + "'";
    if (factor != 1.0) read += " (in this file's <unit> statements: " + formatNumber(v) + " " + unit + ")";
    else read += " " + unit;
    sink_.warning(at, std::string(f.name()) + " of " + node.typeName() + " is " + read + ", " +
                          formatNumber(std::round((low ? r->usualLo / v : v / r->usualHi) * 10.0) / 10.0) +
                          " times " + (low ? "below" : "above") + " the usual " + formatNumber(r->usualLo) + " to " +
                          formatNumber(r->usualHi) + " " + unit + ": is it in the unit the file means? " +
                          (units.si() ? "This file is in SI units (m, N, N·m)"
                                      : "This file's <unit> statements scale its lengths by " +
                                            formatNumber(units.length) + " m and its forces by " +
                                            formatNumber(units.force) + " N, and every value with them"));
  }

  // H3DAPI files often write one MFString item unquoted (url='Cylinder.x3d');
  // H3DAPI and Castle read it as that one string, and so does MillSim, with a warning.
  bool readUnquotedString(Field& f, const std::string& value, const Node& node, const SourceLocation& at) {
    auto* mf = dynamic_cast<MFString*>(&f);
    if (!mf || value.find('"') != std::string::npos || isBlank(value)) return false;
    const std::size_t first = value.find_first_not_of(" \t\r\n");
    const std::size_t last = value.find_last_not_of(" \t\r\n");
    const std::string item = value.substr(first, last - first + 1);
    try {
      mf->set({item});
    } catch (const ValueError&) {
      return false;
    }
    sink_.warning(at, "unquoted MFString value for field '" + std::string(f.name()) + "' of " + node.typeName() +
                          " read as the one string \"" + item + "\"; X3D quotes each item: " +
                          std::string(f.name()) + "='\"" + item + "\"'");
    return true;
  }

  // ---- ROUTE --------------------------------------------------------------------
  Field* routeField(Node& node, const std::string& name, bool asSource) {
    if (Field* f = node.field(name)) return f;
    // X3D lets inputOutput fields be named set_x (as input) and x_changed (as output).
    const std::string prefix = "set_", suffix = "_changed";
    std::string base;
    if (!asSource && name.rfind(prefix, 0) == 0) base = name.substr(prefix.size());
    if (asSource && name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      base = name.substr(0, name.size() - suffix.size());
    Field* f = base.empty() ? nullptr : node.field(base);
    return f && f->access() == Access::InputOutput ? f : nullptr;
  }

  void readRoute(Document& doc, xmlNode* el) {
    std::size_t tag;
    SourceLocation loc = locate(doc, el, &tag);
    std::string v[4];
    const char* names[4] = {"fromNode", "fromField", "toNode", "toField"};
    for (int i = 0; i < 4; ++i) {
      const xmlAttr* a = findAttr(el, names[i]);
      if (!a) {
        sink_.error(loc, std::string("ROUTE is missing its '") + names[i] +
                             "' attribute (a ROUTE needs fromNode, fromField, toNode and toField)");
        return;
      }
      v[i] = attrValue(doc.xml, a);
    }
    Node* ends[2] = {nullptr, nullptr};
    for (int i = 0; i < 2; ++i) {
      auto it = doc.defs->find(v[2 * i]);
      if (auto skipped = doc.skippedDefs.find(v[2 * i]); it == doc.defs->end() && skipped != doc.skippedDefs.end()) {
        sink_.warning(locateAttr(doc, tag, names[2 * i], loc),
                      "ROUTE " + v[0] + "." + v[1] + " TO " + v[2] + "." + v[3] + " ignored: '" + v[2 * i] + "' " +
                          skipped->second);
        return;
      }
      if (it == doc.defs->end()) {
        std::vector<std::string> defNames;
        for (const auto& [k, n] : *doc.defs) defNames.push_back(k);
        sink_.error(locateAttr(doc, tag, names[2 * i], loc),
                    "ROUTE " + std::string(names[2 * i]) + " '" + v[2 * i] +
                        "' names no DEF before it" + didYouMean(closestNames(v[2 * i], defNames)));
        return;
      }
      ends[i] = it->second.get();
    }
    // A ProtoInstance's interface field stands for the inner fields IS connects to it.
    std::vector<Field*> endFields[2];
    for (int i = 0; i < 2; ++i) {
      const SourceLocation fieldAt = locateAttr(doc, tag, names[2 * i + 1], loc);
      if (RouteEnds r = protos_.routeEnds(ends[i], v[2 * i + 1], i == 0, fieldAt); r.isInterfaceField) {
        if (!r.fields) return;
        if (r.fields->empty()) {
          sink_.warning(fieldAt, "ROUTE " + v[0] + "." + v[1] + " TO " + v[2] + "." + v[3] + " does nothing: field '" +
                                     v[2 * i + 1] + "' of proto '" + r.proto + "' is connected (IS) to no field inside it");
          return;
        }
        endFields[i] = *r.fields;
        continue;
      }
      if (Field* f = routeField(*ends[i], v[2 * i + 1], i == 0)) {
        endFields[i] = {f};
        continue;
      }
      std::vector<std::string> fieldNames;
      for (Field* nf : ends[i]->fields()) fieldNames.emplace_back(nf->name());
      for (auto& pf : protos_.interfaceFieldNames(ends[i])) fieldNames.push_back(std::move(pf));
      sink_.error(fieldAt, "ROUTE " + std::string(names[2 * i + 1]) + ": " + ends[i]->typeName() + " '" + v[2 * i] +
                               "' has no field '" + v[2 * i + 1] + "'" +
                               didYouMean(closestNames(v[2 * i + 1], fieldNames)));
      return;
    }
    for (Field* from : endFields[0])
      for (Field* to : endFields[1]) try {
          from->routeTo(*to);
          scene_->routes.push_back({from->owner()->shared_from_this(), from, to->owner()->shared_from_this(), to, loc});
        } catch (const RouteError& e) {
          sink_.error(loc, "cannot ROUTE " + v[0] + "." + v[1] + " TO " + v[2] + "." + v[3] + ": " + e.what());
          return;
        }
  }


  // ---- Inline and ImportLibrary --------------------------------------------
  void loadInline(Document& doc, Inline& inl, const SourceLocation& loc) {
    if (!inl.load.get()) return;
    if (!options_.allowFileAccess) {
      sink_.error(loc, "Inline is disabled for this load (no file access)");
      return;
    }
    if (inl.url.get().empty()) {
      sink_.error(loc, "Inline has an empty url");
      return;
    }
    if (static_cast<int>(inlineStack_.size()) > options_.maxInlineDepth) {
      sink_.error(loc, "Inline nesting deeper than " + std::to_string(options_.maxInlineDepth) + " files");
      return;
    }
    std::string tried;
    for (const std::string& url : inl.url.get()) {
      const auto local = localSceneFile(url, doc.dir, tried);
      if (!local) continue;
      const fs::path& p = local->path;
      const fs::path& canonical = local->canonical;
      for (const auto& open : inlineStack_)
        if (open == canonical) {
          sink_.error(loc, "Inline cycle: '" + p.string() + "' is already being loaded");
          return;
        }
      std::string text;
      if (!readFile(p, text, loc)) return;
      // A fallback url is used: say why each earlier one was not.
      for (std::size_t at = tried.find("\n  "); at != std::string::npos;) {
        const std::size_t next = tried.find("\n  ", at + 3);
        sink_.note(loc, "Inline url failed, a later one was used: " +
                            tried.substr(at + 3, next == std::string::npos ? std::string::npos : next - at - 3));
        at = next;
      }
      inlineStack_.push_back(canonical);
      DefMap privateDefs;
      Document sub(SourceText(p.string(), std::move(text)), p.parent_path(), &privateDefs);
      {
        ProtoReader::FileScope ownProtos(protos_);  // an Inline's protos are its own
        if (parseXml(sub)) readTopLevel(sub, inl.loaded, false);
      }
      inlineStack_.pop_back();
      inlineExports_[&inl] = std::move(sub.exports);  // what an IMPORT of the including file may name
      return;
    }
    sink_.error(loc, "Inline could not load any of its urls:" + tried);
  }

  void importLibrary(Document& doc, ImportLibrary& lib, const SourceLocation& loc) {
    if (!options_.allowFileAccess) {
      sink_.error(loc, "ImportLibrary is disabled for this load (no file access)");
      return;
    }
    std::vector<std::string> urls = lib.url.get();
    urls.insert(urls.end(), lib.library.get().begin(), lib.library.get().end());
    if (urls.empty()) {
      sink_.error(loc, "ImportLibrary has an empty url (and no H3DAPI-style library)");
      return;
    }
    std::string tried;
    for (const std::string& url : urls) {
      fs::path file;
      try {
        file = resolvePlugin(url, doc.dir, options_.plugins);
      } catch (const PluginError& e) {
        tried += std::string(tried.empty() ? "" : "; ") + e.what();
        continue;
      }
      std::error_code ec;
      fs::path canonical = fs::weakly_canonical(file, ec);
      for (const auto& loaded : scene_->plugins)
        if (loaded == canonical) return;  // a second ImportLibrary of the same file is harmless
      try {
        loadPlugin(file, scene_->registry);
        scene_->plugins.push_back(canonical);
      } catch (const PluginError& e) {
        sink_.error(loc, e.what());
      }
      return;
    }
    sink_.error(loc, "ImportLibrary: " + tried);
  }

  bool readFile(const fs::path& p, std::string& out, const SourceLocation& loc) {
    if (auto problem = readSceneText(p, options_.maxFileBytes, out)) {
      sink_.error(loc, *problem);
      return false;
    }
    return true;
  }

  static SourceLocation overrideLocation(const LoadOptions::FieldOverride& o) { return {"--set " + o.text(), 0, 0}; }

  // Field overrides (LoadOptions::overrides) on a node whose attributes,
  // children and IS connections are read. A mistake is reported once per
  // override, not once per node of its type.
  void applyOverrides(Node& node) {
    for (std::size_t i = 0; i < options_.overrides.size(); ++i) {
      const LoadOptions::FieldOverride& o = options_.overrides[i];
      if (node.typeName() != o.type) continue;
      if (overridesApplied_[i]++ > 0 && overrideFailed_[i]) continue;
      Field* f = node.field(o.field);
      if (!f || !settableInFile(f->access()) || f->isNodeField()) {
        std::vector<std::string> names;
        for (Field* nf : node.fields())
          if (settableInFile(nf->access()) && !nf->isNodeField()) names.emplace_back(nf->name());
        sink_.error(overrideLocation(o), o.type + " has no field '" + o.field + "' a value can set" +
                                             didYouMean(closestNames(o.field, names)));
        overrideFailed_[i] = true;
        continue;
      }
      try {
        f->setFromSceneText(o.value, UnitScale{});  // SI, whatever the file says
      } catch (const ValueError& e) {
        sink_.error(overrideLocation(o), "bad value '" + o.value + "' for " + std::string(fieldTypeName(f->type())) +
                                             " field '" + o.field + "' of " + o.type + ": " + e.what());
        overrideFailed_[i] = true;
      }
    }
  }

  const LoadOptions& options_;
  std::vector<int> overridesApplied_ = std::vector<int>(options_.overrides.size(), 0);
  std::vector<bool> overrideFailed_ = std::vector<bool>(options_.overrides.size(), false);
  DiagnosticSink sink_;
  std::unique_ptr<Scene> scene_;
  std::vector<fs::path> inlineStack_;
  static constexpr int kWarningsPerUnsupportedType = 10;
  std::map<std::string, int> unsupportedSeen_;  // warnings given per unsupported type
  // Each loaded Inline's EXPORTs, for the IMPORT statements of the file that includes it.
  std::map<const Inline*, std::map<std::string, std::shared_ptr<Node>, std::less<>>> inlineExports_;
  ProtoReader protos_;  // prototypes: declarations, expansion, routes to instances

  // ---- ProtoHost: what the proto reader asks of the loader ---------------------
  std::shared_ptr<Node> readNodeElement(Document& doc, xmlNode* el, std::size_t tag, const SourceLocation& loc,
                                        std::vector<const Node*>& ancestors) override {
    return readNode(doc, el, tag, loc, ancestors);
  }
  void readRouteElement(Document& doc, xmlNode* el) override { readRoute(doc, el); }
  bool isElement(Document& doc, xmlNode* c, std::string_view parent) override { return checkNonElement(doc, c, parent); }
  std::unique_ptr<Document> openDocument(const fs::path& p, const SourceLocation& loc) override {
    std::string text;
    if (!readFile(p, text, loc)) return nullptr;
    auto d = std::make_unique<Document>(SourceText(p.string(), std::move(text)), p.parent_path(), nullptr);
    if (!parseXml(*d)) return nullptr;
    return d;
  }
  bool isBeingRead(const fs::path& canonical) const override {
    return std::find(inlineStack_.begin(), inlineStack_.end(), canonical) != inlineStack_.end();
  }
  void keepUnattached(std::shared_ptr<Node> node) override { scene_->unattached.push_back(std::move(node)); }

  friend LoadResult millsim::loadSceneFile(const fs::path&, const NodeRegistry&, const LoadOptions&);
};

}  // namespace

namespace {
// Built by push_back rather than a braced list: g++ 12 reports a false
// -Wmaybe-uninitialized for an initializer_list of Diagnostics.
LoadResult fileError(const fs::path& file, const char* message) {
  LoadResult r;
  r.diagnostics.push_back(Diagnostic{Severity::Error, SourceLocation{file.string(), 0, 0}, message});
  return r;
}
}  // namespace

std::optional<LoadOptions::FieldOverride> parseFieldOverride(std::string_view text) {
  const std::size_t eq = text.find('='), dot = text.substr(0, eq).find('.');
  if (eq == std::string_view::npos || dot == std::string_view::npos || dot == 0 || dot + 1 == eq) return std::nullopt;
  return LoadOptions::FieldOverride{std::string(text.substr(0, dot)), std::string(text.substr(dot + 1, eq - dot - 1)),
                                    std::string(text.substr(eq + 1))};
}

LoadResult loadSceneFile(const fs::path& file, const NodeRegistry& registry, const LoadOptions& options) {
  Loader loader(registry, options);
  std::error_code ec;
  if (!fs::exists(file, ec)) return fileError(file, "no such file");
  if (!fs::is_regular_file(file, ec)) return fileError(file, "not a regular file");
  if (auto unsupported = unsupportedEncoding(file)) return fileError(file, unsupported->c_str());
  std::string text;
  if (!loader.readFile(file, text, {file.string(), 0, 0})) return {nullptr, loader.sink_.take()};
  fs::path canonical = fs::weakly_canonical(file, ec);
  LoadResult r = loader.load(std::move(text), file.string(), file.parent_path(), canonical);
  if (r.scene) r.scene->file = file;
  return r;
}

LoadResult loadSceneString(std::string_view text, std::string fileLabel, const NodeRegistry& registry,
                           const LoadOptions& options, const fs::path& baseDir) {
  Loader loader(registry, options);
  return loader.load(std::string(text), std::move(fileLabel), baseDir, {});
}

}  // namespace millsim
