#include "millsim/x3d/ProtoDeclaration.h"

#include <set>

#include "millsim/core/NodeRegistry.h"

namespace millsim {

const ProtoFieldDecl* ProtoDecl::field(std::string_view n) const {
  for (const auto& f : fields)
    if (f.name == n) return &f;
  return nullptr;
}

std::vector<std::string> ProtoDecl::fieldNames() const {
  std::vector<std::string> names;
  for (const auto& f : fields) names.push_back(f.name);
  return names;
}

std::shared_ptr<ProtoDecl> ProtoScope::find(std::string_view name) const {
  for (const ProtoScope* s = this; s; s = s->parent.get())
    if (auto it = s->protos.find(name); it != s->protos.end()) return it->second;
  return nullptr;
}

std::vector<std::string> ProtoScope::names() const {
  std::vector<std::string> out;
  for (const ProtoScope* s = this; s; s = s->parent.get())
    for (const auto& [k, v] : s->protos) out.push_back(k);
  return out;
}

std::optional<FieldType> fieldTypeFromName(std::string_view name) {
  for (int i = 0; i <= static_cast<int>(FieldType::SFMatrix4f); ++i)
    if (fieldTypeName(static_cast<FieldType>(i)) == name) return static_cast<FieldType>(i);
  return std::nullopt;
}

std::optional<Access> accessFromName(std::string_view name) {
  for (Access a : {Access::InitializeOnly, Access::InputOnly, Access::OutputOnly, Access::InputOutput})
    if (accessName(a) == name) return a;
  return std::nullopt;
}

bool isNodeType(FieldType t) { return t == FieldType::SFNode || t == FieldType::MFNode; }

bool isNullNodeValue(std::string_view text) {
  const std::size_t b = text.find_first_not_of(" \t\r\n"), e = text.find_last_not_of(" \t\r\n");
  return b != std::string_view::npos && text.substr(b, e - b + 1) == "NULL";
}

namespace {
template <class T>
void parseAs(FieldType t, std::string_view text) {
  if (fieldTypeName(t).front() == 'M')
    (void)parseMultiple<T>(text);
  else
    (void)parseSingle<T>(text);
}
}  // namespace

std::optional<std::string> invalidValue(FieldType type, std::string_view text) {
  try {
    switch (type) {
      case FieldType::SFBool:
      case FieldType::MFBool:
        parseAs<bool>(type, text);
        break;
      case FieldType::SFInt32:
      case FieldType::MFInt32:
        parseAs<std::int32_t>(type, text);
        break;
      case FieldType::SFFloat:
      case FieldType::MFFloat:
        parseAs<float>(type, text);
        break;
      case FieldType::SFDouble:
      case FieldType::MFDouble:
        parseAs<double>(type, text);
        break;
      case FieldType::SFTime:
      case FieldType::MFTime:
        parseAs<Time>(type, text);
        break;
      case FieldType::SFString:
      case FieldType::MFString:
        parseAs<std::string>(type, text);
        break;
      case FieldType::SFVec2f:
      case FieldType::MFVec2f:
        parseAs<glm::vec2>(type, text);
        break;
      case FieldType::SFVec3f:
      case FieldType::MFVec3f:
        parseAs<glm::vec3>(type, text);
        break;
      case FieldType::SFVec3d:
      case FieldType::MFVec3d:
        parseAs<glm::dvec3>(type, text);
        break;
      case FieldType::SFVec4f:
      case FieldType::MFVec4f:
        parseAs<glm::vec4>(type, text);
        break;
      case FieldType::SFRotation:
      case FieldType::MFRotation:
        parseAs<Rotation>(type, text);
        break;
      case FieldType::SFColor:
      case FieldType::MFColor:
        parseAs<Color>(type, text);
        break;
      case FieldType::SFMatrix4f:
        (void)parseSingle<glm::mat4>(text);
        break;
      case FieldType::SFNode:
      case FieldType::MFNode:
        return std::string("a node field takes child node elements");
    }
  } catch (const ValueError& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

// X3D 4.0, 4.4.4.3: the access types an IS may connect.
bool canConnect(Access iface, Access inner) {
  if (inner == Access::InputOutput) return true;
  if (iface == Access::InputOutput) return false;
  if (iface == Access::InitializeOnly) return inner == Access::InitializeOnly;
  return iface == inner;  // inputOnly-inputOnly, outputOnly-outputOnly
}

std::vector<ProtoFieldDecl> readProtoFields(Document& doc, const xmlNode* parent, const std::string& owner,
                                            bool withValues, DiagnosticSink& sink) {
  std::vector<ProtoFieldDecl> out;
  std::set<std::string> seen;
  for (const xmlNode* c = parent->children; c; c = c->next) {
    if (c->type != XML_ELEMENT_NODE) continue;
    std::size_t tag;
    SourceLocation loc = doc.locate(c, &tag);
    if (nameOf(c) != "field") {
      if (nameOf(c).rfind("Metadata", 0) != 0)  // metadata about the interface changes nothing
        sink.error(loc, "unexpected <" + std::string(nameOf(c)) + "> in the interface of proto '" + owner +
                            "'; expected <field>");
      continue;
    }
    ProtoFieldDecl f;
    f.element = c;
    f.where = loc;
    const xmlAttr* name = findAttr(c, "name");
    const xmlAttr* type = findAttr(c, "type");
    const xmlAttr* access = findAttr(c, "accessType");
    if (!name || !type || !access) {
      sink.error(loc, std::string("a <field> of proto '") + owner + "' needs name, type and accessType (" +
                          (!name   ? "name"
                           : !type ? "type"
                                   : "accessType") +
                          " is missing)");
      continue;
    }
    f.name = doc.value(name);
    f.units = doc.units;
    const std::string typeName = doc.value(type), accessText = doc.value(access);
    auto t = fieldTypeFromName(typeName);
    if (!t) {
      sink.error(doc.locateAttr(tag, "type", loc), "field '" + f.name + "' of proto '" + owner + "': type '" +
                                                       typeName + "' is not a field type MillSim has");
      continue;
    }
    auto a = accessFromName(accessText);
    if (!a) {
      sink.error(doc.locateAttr(tag, "accessType", loc),
                 "field '" + f.name + "' of proto '" + owner + "': accessType '" + accessText +
                     "' is not one of initializeOnly, inputOnly, outputOnly, inputOutput");
      continue;
    }
    f.type = *t;
    f.access = *a;
    if (!seen.insert(f.name).second) {
      sink.error(doc.locateAttr(tag, "name", loc), "proto '" + owner + "' declares field '" + f.name + "' twice");
      continue;
    }
    const xmlAttr* value = findAttr(c, "value");
    // value="NULL" on a node field is the ClassicVRML spelling of "no node",
    // which X3D editors write into XML too: it means what no value means.
    if (value && isNodeType(f.type) && isNullNodeValue(doc.value(value))) value = nullptr;
    const bool hasNodes = [&] {
      for (const xmlNode* k = c->children; k; k = k->next)  // metadata about the field changes nothing
        if (k->type == XML_ELEMENT_NODE && nameOf(k).rfind("Metadata", 0) != 0) return true;
      return false;
    }();
    if ((value || hasNodes) && (!withValues || !settableInFile(f.access))) {
      sink.error(value ? doc.locateAttr(tag, "value", loc) : loc,
                 "field '" + f.name + "' of proto '" + owner + "' cannot have a value: " +
                     (withValues ? "it is " + std::string(accessText)
                                 : std::string("an ExternProtoDeclare lists fields without values")));
      continue;
    }
    if (value && isNodeType(f.type)) {
      sink.error(doc.locateAttr(tag, "value", loc), "field '" + f.name + "' of proto '" + owner + "' is " + typeName +
                                                        ": its default is child node elements, not a value attribute");
      continue;
    }
    if (hasNodes && !isNodeType(f.type)) {
      sink.error(loc, "field '" + f.name + "' of proto '" + owner + "' is " + typeName + " and cannot hold nodes");
      continue;
    }
    if (value) {
      std::string v = doc.value(value);
      if (auto bad = invalidValue(f.type, v)) {
        sink.error(doc.locateAttr(tag, "value", loc), "bad default '" + v + "' for " + typeName + " field '" + f.name +
                                                          "' of proto '" + owner + "': " + *bad);
        continue;
      }
      f.value = std::move(v);
    }
    // Without a value (X3D asks for one) the inner fields keep their own defaults, as most browsers do.
    out.push_back(std::move(f));
  }
  return out;
}

std::shared_ptr<ProtoDecl> readProtoDeclare(Document& doc, const xmlNode* el, DiagnosticSink& sink) {
  std::size_t tag;
  SourceLocation loc = doc.locate(el, &tag);
  // Every tag inside is found now, in document order: the body is read later, once per instance.
  doc.locateSubtree(el);
  const xmlAttr* name = findAttr(el, "name");
  if (!name || doc.value(name).empty()) {
    sink.error(loc, "a <ProtoDeclare> needs a name");
    return nullptr;
  }
  auto decl = std::make_shared<ProtoDecl>();
  decl->name = doc.value(name);
  decl->where = loc;
  decl->doc = &doc;
  bool bad = false;
  for (const xmlNode* c = el->children; c; c = c->next) {
    if (c->type != XML_ELEMENT_NODE) continue;
    const std::string_view n = nameOf(c);
    if (n == "ProtoInterface") {
      const std::size_t before = sink.errorCount();
      decl->fields = readProtoFields(doc, c, decl->name, true, sink);
      bad = bad || sink.errorCount() != before;
    } else if (n == "ProtoBody") {
      if (decl->body) {
        sink.error(doc.locate(c), "proto '" + decl->name + "' has a second <ProtoBody>");
        bad = true;
      }
      decl->body = c;
    } else if (n.rfind("Metadata", 0) != 0) {
      sink.error(doc.locate(c), "unexpected <" + std::string(n) + "> inside <ProtoDeclare name='" + decl->name +
                                    "'>; expected <ProtoInterface> and <ProtoBody>");
      bad = true;
    }
  }
  if (!decl->body) {
    sink.error(loc, "proto '" + decl->name + "' has no <ProtoBody>");
    return nullptr;
  }
  auto count = [](const xmlNode* n, auto& self) -> std::size_t {
    std::size_t k = 0;
    for (const xmlNode* c = n->children; c; c = c->next)
      if (c->type == XML_ELEMENT_NODE) k += 1 + self(c, self);
    return k;
  };
  decl->bodyElements = count(decl->body, count);
  return bad ? nullptr : decl;
}

std::optional<ExternProtoDecl> readExternProtoDeclare(Document& doc, const xmlNode* el, DiagnosticSink& sink) {
  std::size_t tag;
  SourceLocation loc = doc.locate(el, &tag);
  ExternProtoDecl ext;
  ext.where = loc;
  const xmlAttr* name = findAttr(el, "name");
  const xmlAttr* url = findAttr(el, "url");
  if (!name || doc.value(name).empty()) {
    sink.error(loc, "an <ExternProtoDeclare> needs a name");
    return std::nullopt;
  }
  ext.name = doc.value(name);
  if (!url) {
    sink.error(loc, "ExternProtoDeclare '" + ext.name + "' needs a url (e.g. url='\"protos.x3d#" + ext.name + "\"')");
    return std::nullopt;
  }
  const std::string urlText = doc.value(url);
  try {
    ext.urls = parseMultiple<std::string>(urlText);
  } catch (const ValueError&) {
    ext.urls = {urlText};  // one unquoted url, as H3DAPI files write it
  }
  std::erase_if(ext.urls, [](const std::string& u) { return u.find_first_not_of(" \t\r\n") == std::string::npos; });
  if (ext.urls.empty())  // browsers declare it and skip its instances: so does ProtoReader::readExtern
    sink.warning(doc.locateAttr(tag, "url", loc),
                 "ExternProtoDeclare '" + ext.name + "' has an empty url: there is no proto to load, and its instances are skipped");
  const std::size_t before = sink.errorCount();
  ext.fields = readProtoFields(doc, el, ext.name, false, sink);
  if (sink.errorCount() != before) return std::nullopt;
  return ext;
}

bool externMatches(const ExternProtoDecl& ext, const ProtoDecl& found, DiagnosticSink& sink) {
  bool ok = true;
  for (const auto& f : ext.fields) {
    const ProtoFieldDecl* g = found.field(f.name);
    if (!g) {
      sink.error(
          f.where, "ExternProtoDeclare '" + ext.name + "' lists field '" + f.name + "', which proto '" + found.name +
                       "' at " + found.where.str() + " does not declare" + [&] {
                         auto s = closestNames(f.name, found.fieldNames());
                         return s.empty() ? std::string() : "; did you mean '" + s.front() + "'?";
                       }());
      ok = false;
    } else if (g->type != f.type || g->access != f.access) {
      sink.error(f.where, "ExternProtoDeclare '" + ext.name + "' lists field '" + f.name + "' as " +
                              std::string(accessName(f.access)) + " " + std::string(fieldTypeName(f.type)) +
                              ", but proto '" + found.name + "' at " + found.where.str() + " declares it " +
                              std::string(accessName(g->access)) + " " + std::string(fieldTypeName(g->type)));
      ok = false;
    }
  }
  return ok;
}

}  // namespace millsim
