#pragma once
// One X3D file as the loader reads it: its text (for columns), its libxml2
// tree, its folder (for relative urls) and its DEF namespace. Private to the
// x3d room: it names libxml2 types.
#include <libxml/tree.h>

#include <filesystem>
#include <map>
#include <set>
#include <memory>
#include <string>
#include <string_view>

#include "millsim/core/Node.h"
#include "millsim/core/Quantity.h"
#include "millsim/x3d/SourceText.h"

namespace millsim {

using DefMap = std::map<std::string, std::shared_ptr<Node>, std::less<>>;

inline std::string_view nameOf(const xmlNode* n) { return reinterpret_cast<const char*>(n->name); }

inline std::string attrValue(xmlDocPtr doc, const xmlAttr* a) {
  xmlChar* v = xmlNodeListGetString(doc, a->children, 1);
  std::string s = v ? reinterpret_cast<const char*>(v) : "";
  xmlFree(v);
  return s;
}

inline const xmlAttr* findAttr(const xmlNode* el, std::string_view name) {
  for (const xmlAttr* a = el->properties; a; a = a->next)
    if (!a->ns && nameOf(reinterpret_cast<const xmlNode*>(a)) == name) return a;
  return nullptr;
}

struct Document {
  SourceText src;
  xmlDocPtr xml = nullptr;
  std::filesystem::path dir;
  DefMap* defs;  // an Inline's and a ProtoInstance's DEF names are private to it, as X3D specifies
  // DEF name -> why its node was skipped ("is a ProximitySensor, which MillSim
  // does not support"): a USE or ROUTE of one is skipped too, saying so.
  std::map<std::string, std::string, std::less<>> skippedDefs;
  // Each element's place in document order and where each DEF name is (not
  // inside ProtoDeclares, whose names are their own): made on the file's first
  // USE of a name not defined yet, to tell a USE before its DEF from a typo.
  struct DefPositions {
    std::map<const xmlNode*, std::size_t> order;
    std::multimap<std::string, std::pair<std::size_t, const xmlNode*>, std::less<>> defs;
  };
  DefPositions defPositions;
  // Its EXPORT statements: the name an importer uses -> the node (X3D 4.0 §4.4.6).
  std::map<std::string, std::shared_ptr<Node>, std::less<>> exports;
  // Where each element's start tag begins, once found. A ProtoBody is read
  // once per instance, after the source cursor has passed it, so its tags
  // are found when its ProtoDeclare is read (see locateSubtree).
  std::map<const xmlNode*, std::size_t> tagOffsets;
  // The file's own <unit> statements: its values are converted to SI with
  // these, so an Inline or an ExternProto file keeps its own units.
  UnitScale units;
  std::set<std::string, std::less<>> unitCategories;  // those a <unit> statement set

  Document(SourceText text, std::filesystem::path folder, DefMap* names)
      : src(std::move(text)), dir(std::move(folder)), defs(names) {}
  ~Document() {
    if (xml) xmlFreeDoc(xml);
  }
  Document(const Document&) = delete;
  Document& operator=(const Document&) = delete;

  std::string value(const xmlAttr* a) const { return attrValue(xml, a); }

  SourceLocation locate(const xmlNode* el, std::size_t* tagStart = nullptr) {
    std::size_t pos;
    if (auto it = tagOffsets.find(el); it != tagOffsets.end()) {
      pos = it->second;
    } else {
      pos = src.findStartTag(nameOf(el), xmlGetLineNo(const_cast<xmlNode*>(el)));
      if (pos != std::string::npos) tagOffsets.emplace(el, pos);
    }
    if (tagStart) *tagStart = pos;
    if (pos == std::string::npos) return src.atLine(xmlGetLineNo(const_cast<xmlNode*>(el)));
    return src.at(pos);
  }

  // Finds every start tag below `el` now, in document order.
  void locateSubtree(const xmlNode* el) {
    for (const xmlNode* c = el->children; c; c = c->next)
      if (c->type == XML_ELEMENT_NODE) {
        locate(c);
        locateSubtree(c);
      }
  }

  SourceLocation locateAttr(std::size_t tagStart, std::string_view attr, const SourceLocation& fallback) const {
    std::size_t pos = src.findAttribute(tagStart, attr);
    return pos == std::string::npos ? fallback : src.at(pos);
  }

  // Where attribute `attr` of `el` is written (the element's start when it is not found).
  SourceLocation locateAttr(const xmlNode* el, std::string_view attr) {
    std::size_t tag;
    SourceLocation loc = locate(el, &tag);
    return locateAttr(tag, attr, loc);
  }
};

}  // namespace millsim
