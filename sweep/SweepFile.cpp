#include "sweep/SweepFile.h"

#include <glob.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>

#include "millsim/core/NaturalOrder.h"

namespace millsim::sweep {
namespace fs = std::filesystem;
using millsim::naturalLess;

namespace {

constexpr std::uintmax_t kMaxFileBytes = 1u << 20;

std::string listOf(const std::vector<std::string>& names, const char* last = "or") {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i)
    s += (i == 0 ? "" : i + 1 == names.size() ? std::string(" ") + last + " " : ", ") + names[i];
  return s;
}

bool inside(const fs::path& folder, const fs::path& p) {
  auto f = folder.begin(), q = p.begin();
  for (; f != folder.end(); ++f, ++q)
    if (q == p.end() || *f != *q) return false;
  return true;
}

class Reader {
public:
  Reader(const fs::path& file, const SweepContext& context) : context_(context) {
    sweep_.file = fs::absolute(file).lexically_normal();
    sweep_.folder = fs::weakly_canonical(sweep_.file.parent_path());
    label_ = file.string();
  }

  Sweep read() {
    std::error_code ec;
    if (!fs::is_regular_file(sweep_.file, ec)) throw SweepError(label_ + ": no such sweep file");
    if (fs::file_size(sweep_.file, ec) > kMaxFileBytes)
      throw SweepError(label_ + ": larger than 1 MiB; a sweep file names a grid, not its data");
    std::ifstream in(sweep_.file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    if (!in && !in.eof()) throw SweepError(label_ + ": cannot read it");
    const JsonValue root = parseJsonWithPlaces(text.str(), label_);
    if (root.kind != JsonValue::Kind::Object)
      fail(root.at, "a sweep file is a JSON object ({\"verb\": ..., \"grid\": {...}}), not " + std::string(root.kindName()));

    const JsonValue* fixed = nullptr;
    const JsonValue* grid = nullptr;
    const JsonValue* verb = nullptr;
    // The file's stem, made a name Slurm and a folder take as one word.
    sweep_.name = sweep_.file.stem().string();
    for (char& c : sweep_.name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
    if (sweep_.name.size() > 64) sweep_.name.resize(64);
    for (std::size_t i = 0; i < root.members.size(); ++i) {
      const auto& [key, value] = root.members[i];
      if (key == "verb") verb = &value;
      else if (key == "fixed") fixed = &value;
      else if (key == "grid") grid = &value;
      else if (key == "sweep") sweep_.name = name(value);
      else if (key == "slurm") slurm(value);
      else fail(root.keyPlaces[i], "unknown key \"" + key + "\"; expected sweep, verb, fixed, grid or slurm");
    }
    if (!verb) fail(root.at, "no \"verb\"; expected one of " + verbNames());
    if (verb->kind != JsonValue::Kind::String) fail(verb->at, "\"verb\" is " + std::string(verb->kindName()) + "; expected one of " + verbNames());
    sweep_.verb = findVerb(verb->text);
    if (!sweep_.verb)
      fail(verb->at, "unknown verb '" + verb->text + "'; expected " + verbNames() +
                         (verb->text == "bench resolution"
                              ? " (MillSim has no `" + verb->text + "` yet)"
                              : ""));
    if (fixed) readParams(*fixed, "fixed", sweep_.fixed, false);
    if (!grid) fail(root.at, "no \"grid\": a sweep varies at least one parameter, e.g. \"grid\": {\"renderer\": [...]}");
    readParams(*grid, "grid", sweep_.axes, true);
    if (sweep_.axes.empty()) fail(grid->at, "the grid is empty; give at least one parameter and its values");
    for (const ParamSpec& p : sweep_.verb->params)
      if (p.required && !given(p.name))
        fail(root.at, sweep_.verb->name + " needs \"" + p.name + "\" (" + p.help + "), in \"fixed\" or on the grid");
    checkSize(grid->at);
    return std::move(sweep_);
  }

private:
  [[noreturn]] void fail(Place at, const std::string& what) const {
    throw SweepError(label_ + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": " + what);
  }

  static std::string verbNames() {
    std::vector<std::string> names;
    for (const VerbSpec& v : sweepVerbs()) names.push_back(v.name);
    return listOf(names);
  }

  bool given(const std::string& param) const {
    for (const auto* list : {&sweep_.fixed, &sweep_.axes})
      for (const SweepParam& p : *list)
        if (p.spec->name == param) return true;
    return false;
  }

  std::string name(const JsonValue& v) const {
    const bool ok = v.kind == JsonValue::Kind::String && !v.text.empty() && v.text.size() <= 64 &&
                    std::all_of(v.text.begin(), v.text.end(), [](char c) {
                      return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
                    });
    if (!ok) fail(v.at, "\"sweep\" names the sweep: 1 to 64 letters, digits, '-', '_' or '.'");
    return v.text;
  }

  void slurm(const JsonValue& v) {
    if (v.kind != JsonValue::Kind::Object) fail(v.at, "\"slurm\" is " + std::string(v.kindName()) + "; expected an object");
    for (std::size_t i = 0; i < v.members.size(); ++i) {
      // Named references, not a structured binding: clang 14 cannot capture those in a lambda.
      const std::string& key = v.members[i].first;
      const JsonValue& value = v.members[i].second;
      auto word = [&](const char* allowed, const char* what) {
        const bool ok = value.kind == JsonValue::Kind::String && !value.text.empty() && value.text.size() <= 64 &&
                        std::all_of(value.text.begin(), value.text.end(), [&](char c) {
                          return std::isalnum(static_cast<unsigned char>(c)) || std::string_view(allowed).find(c) != std::string_view::npos;
                        });
        if (!ok) fail(value.at, "\"" + key + "\" is " + what);
        return value.text;
      };
      if (key == "max_parallel") {
        if (value.kind != JsonValue::Kind::Number || !value.integer || value.number < 1 || value.number > 100000)
          fail(value.at, "\"max_parallel\" is how many cells run at once: a whole number from 1 to 100000");
        sweep_.slurm.maxParallel = int(value.number);
      } else if (key == "partition") {
        sweep_.slurm.partition = word("_.-", "a Slurm partition's name");
      } else if (key == "time") {
        sweep_.slurm.time = word(":-", "a time limit as Slurm writes it, e.g. \"00:30:00\" or \"1-00:00:00\"");
      } else {
        fail(v.keyPlaces[i], "unknown key \"" + key + "\" in \"slurm\"; expected max_parallel, partition or time");
      }
    }
  }

  void readParams(const JsonValue& object, const char* where, std::vector<SweepParam>& out, bool axis) {
    if (object.kind != JsonValue::Kind::Object)
      fail(object.at, "\"" + std::string(where) + "\" is " + object.kindName() + "; expected an object of parameters");
    for (std::size_t i = 0; i < object.members.size(); ++i) {
      const auto& [key, value] = object.members[i];
      const ParamSpec* spec = findParam(*sweep_.verb, key);
      if (!spec) {
        std::vector<std::string> names;
        for (const ParamSpec& p : sweep_.verb->params) names.push_back(p.name);
        fail(object.keyPlaces[i], "unknown parameter \"" + key + "\" of " + sweep_.verb->name + "; expected " + listOf(names));
      }
      for (const SweepParam& p : sweep_.fixed)
        if (axis && p.spec == spec)
          fail(object.keyPlaces[i], "\"" + key + "\" is both fixed (line " + std::to_string(p.at.line) +
                                        ") and on the grid; give it in one of them");
      SweepParam param{spec, {}, object.keyPlaces[i]};
      std::set<std::string> seen;  // a number by its value: 1000 and 1e3 are one cell
      const bool repeatable = spec->kind == ParamKind::Override || spec->kind == ParamKind::RendererField;
      if (spec->kind == ParamKind::Path && value.kind == JsonValue::Kind::Object && axis) {
        param.values = glob(value);
      } else if (value.kind == JsonValue::Kind::Array && (axis || repeatable)) {
        if (value.items.empty())
          fail(value.at, axis ? "an empty list: a grid axis needs at least one value" : "an empty list");
        for (const JsonValue& item : value.items) {
          std::string v = checked(*spec, item);
          std::ostringstream identity;
          if (item.kind == JsonValue::Kind::Number) identity.precision(17), identity << item.number;
          else identity << v;
          if (!seen.insert(identity.str()).second)
            fail(item.at, "'" + (item.kind == JsonValue::Kind::String || item.kind == JsonValue::Kind::Number ? item.text : v) +
                              "' is given twice for \"" + key + "\": the two cells would be the same");
          param.values.push_back(std::move(v));
        }
      } else if (axis) {
        fail(value.at, "\"" + key + "\" on the grid is " + value.kindName() + "; expected a list of its values" +
                           (spec->kind == ParamKind::Path ? " or {\"glob\": \"folder/*.csv\"}" : ""));
      } else {
        param.values.push_back(checked(*spec, value));
      }
      out.push_back(std::move(param));
    }
  }

  std::string checked(const ParamSpec& spec, const JsonValue& v) const {
    const std::string expected = "\"" + spec.name + "\" is " + kindName(spec.kind) + " (" + spec.help + ")";
    switch (spec.kind) {
      case ParamKind::Flag:
        if (v.kind != JsonValue::Kind::Bool) fail(v.at, v.kindName() + std::string(" where ") + expected);
        return v.boolean ? "true" : "false";
      case ParamKind::Number:
        if (v.kind != JsonValue::Kind::Number || !std::isfinite(v.number))
          fail(v.at, v.kindName() + std::string(" where ") + expected);
        if (spec.integer && (!v.integer || v.text.find_first_of(".eE") != std::string::npos))
          fail(v.at, "\"" + spec.name + "\" " + v.text + " is not a whole number (" + spec.help + ")");
        if (v.number < spec.lo || v.number > spec.hi) {
          std::ostringstream range;
          range << spec.lo << " to " << spec.hi;
          fail(v.at, "\"" + spec.name + "\" " + v.text + " is outside " + range.str() + " (" + spec.help + ")");
        }
        return v.text;
      default: break;
    }
    if (v.kind != JsonValue::Kind::String || v.text.empty()) fail(v.at, v.kindName() + std::string(" where ") + expected);
    if (std::any_of(v.text.begin(), v.text.end(), [](char c) { return std::iscntrl(static_cast<unsigned char>(c)); }))
      fail(v.at, "a control character in \"" + spec.name + "\"");
    switch (spec.kind) {
      case ParamKind::Path: return path(v);
      case ParamKind::Renderer:
        if (std::find(context_.renderers.begin(), context_.renderers.end(), v.text) == context_.renderers.end())
          fail(v.at, "unknown renderer '" + v.text + "'; registered: " + listOf(context_.renderers, "and"));
        return v.text;
      case ParamKind::Override: {
        const std::size_t eq = v.text.find('='), dot = v.text.substr(0, eq).find('.');
        if (eq == std::string::npos || dot == std::string::npos || dot == 0 || dot + 1 == eq)
          fail(v.at, "'" + v.text + "' is not TYPE.FIELD=VALUE, e.g. BarbicRenderer.pointShellScale=2");
        return v.text;
      }
      case ParamKind::RendererField:
        if (const std::size_t eq = v.text.find('='); eq == std::string::npos || eq == 0)
          fail(v.at, "'" + v.text + "' is not FIELD=VALUE, e.g. pointShellScale=2");
        return v.text;
      default: return v.text;
    }
  }

  std::string inFolder(const std::string& written, Place at) const {
    if (std::any_of(written.begin(), written.end(), [](char c) { return std::iscntrl(static_cast<unsigned char>(c)); }))
      fail(at, "a control character in the file name '" + written + "'");
    const fs::path p = fs::weakly_canonical(sweep_.folder / written);
    if (!inside(sweep_.folder, p))
      fail(at, "'" + written + "' lies outside the sweep's folder " + sweep_.folder.string() +
                   "; a sweep reads only files beside it or below it (move the sweep file up)");
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) fail(at, "no such file '" + written + "' in " + sweep_.folder.string());
    return p.string();
  }

  std::string path(const JsonValue& v) const { return inFolder(v.text, v.at); }

  std::vector<std::string> glob(const JsonValue& v) const {
    if (v.members.size() != 1 || v.members[0].first != "glob" || v.members[0].second.kind != JsonValue::Kind::String)
      fail(v.at, "a path axis is a list of files or {\"glob\": \"folder/*.csv\"}");
    const JsonValue& pattern = v.members[0].second;
    if (fs::path(pattern.text).is_absolute() || pattern.text.find("..") != std::string::npos)
      fail(pattern.at, "the glob '" + pattern.text + "' must name files below the sweep's folder (no '..', not absolute)");
    // The folder's own name is matched literally, only the pattern as a glob.
    std::string folder;
    for (const char c : sweep_.folder.string() + "/") {
      if (std::string_view("*?[\\").find(c) != std::string_view::npos) folder += '\\';
      folder += c;
    }
    glob_t g{};
    const int r = ::glob((folder + pattern.text).c_str(), GLOB_NOSORT, nullptr, &g);
    std::vector<std::string> found;
    for (std::size_t i = 0; r == 0 && i < g.gl_pathc; ++i) found.emplace_back(g.gl_pathv[i]);
    globfree(&g);
    if (found.empty()) fail(pattern.at, "the glob '" + pattern.text + "' matches no file in " + sweep_.folder.string());
    if (found.size() > kMaxCells) fail(pattern.at, "the glob '" + pattern.text + "' matches more than a sweep runs");
    std::sort(found.begin(), found.end(), naturalLess);
    std::vector<std::string> out;
    for (const std::string& f : found) out.push_back(inFolder(fs::path(f).lexically_relative(sweep_.folder).string(), pattern.at));
    return out;
  }

  void checkSize(Place at) const {
    std::uint64_t n = 1;
    std::string product;
    for (const SweepParam& a : sweep_.axes) {
      product += (product.empty() ? "" : " × ") + std::to_string(a.values.size()) + " " + a.spec->name;
      n = n > kMaxCells ? n : n * a.values.size();
    }
    if (n > kMaxCells)
      fail(at, "the grid has more than " + std::to_string(kMaxCells) + " cells (" + product + "); split the sweep");
    if (n > kCellsWithoutYes && !context_.yes)
      fail(at, "the grid has " + std::to_string(n) + " cells (" + product + "), more than " +
                   std::to_string(kCellsWithoutYes) + ": pass --yes to run them all");
  }

  const SweepContext& context_;
  Sweep sweep_;
  std::string label_;
};

}  // namespace

std::uint64_t Sweep::cellCount() const {
  std::uint64_t n = 1;
  for (const SweepParam& a : axes) n *= a.values.size();
  return n;
}

Sweep readSweep(const fs::path& file, const SweepContext& context) { return Reader(file, context).read(); }

Cell cellAt(const Sweep& sweep, std::uint64_t index) {
  Cell c;
  c.index = index;
  const std::uint64_t n = sweep.cellCount();
  const std::size_t width = std::max<std::size_t>(4, std::to_string(n > 0 ? n - 1 : 0).size());
  c.id = std::to_string(index);
  c.id.insert(0, width - std::min(width, c.id.size()), '0');
  c.values.resize(sweep.axes.size());
  std::uint64_t rest = index;
  for (std::size_t a = sweep.axes.size(); a-- > 0;) {
    const auto& values = sweep.axes[a].values;
    c.values[a] = values[rest % values.size()];
    rest /= values.size();
  }
  c.args = sweep.verb->words;
  for (const ParamSpec& spec : sweep.verb->params) {
    std::vector<std::string> values;
    for (const SweepParam& p : sweep.fixed)
      if (p.spec == &spec) values.insert(values.end(), p.values.begin(), p.values.end());
    for (std::size_t a = 0; a < sweep.axes.size(); ++a)
      if (sweep.axes[a].spec == &spec) values.push_back(c.values[a]);
    for (const std::string& v : values) {
      if (spec.kind == ParamKind::Flag) {
        if (v == "true") c.args.push_back(spec.option);
        continue;
      }
      if (!spec.option.empty()) c.args.push_back(spec.option);
      c.args.push_back(v);
    }
  }
  c.args.insert(c.args.end(), sweep.verb->resultArgs.begin(), sweep.verb->resultArgs.end());
  return c;
}

std::string shownValue(const Sweep& sweep, const SweepParam& param, const std::string& value) {
  if (param.spec->kind != ParamKind::Path) return value;
  return fs::path(value).lexically_relative(sweep.folder).string();
}

}  // namespace millsim::sweep
