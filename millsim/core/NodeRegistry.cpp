#include "millsim/core/NodeRegistry.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "millsim/core/Node.h"

namespace millsim {

void NodeRegistry::add(NodeType type) {
  if (type.name.empty() || !type.create) throw std::invalid_argument("node type needs a name and a factory");
  if (types_.count(type.name)) throw std::invalid_argument("node type '" + type.name + "' is already registered");
  std::string key = type.name;
  types_.emplace(std::move(key), std::move(type));
}

void NodeRegistry::addSceneCheck(SceneCheck check) {
  if (check && std::find(checks_.begin(), checks_.end(), check) == checks_.end()) checks_.push_back(check);
}

const NodeType* NodeRegistry::find(std::string_view name) const {
  auto it = types_.find(name);
  return it == types_.end() ? nullptr : &it->second;
}

std::shared_ptr<Node> NodeRegistry::create(std::string_view name) const {
  const NodeType* t = find(name);
  return t ? t->create() : nullptr;
}

std::vector<const NodeType*> NodeRegistry::all() const {
  std::vector<const NodeType*> out;
  for (const auto& [name, t] : types_) out.push_back(&t);
  return out;
}

std::vector<std::string> NodeRegistry::suggest(std::string_view name, std::size_t max) const {
  std::vector<std::string> names;
  for (const auto& [n, t] : types_) names.push_back(n);
  return closestNames(name, names, max);
}

std::size_t editDistance(std::string_view a, std::string_view b) {
  // Levenshtein distance with two rows; names are short.
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (same ? 0 : 1)});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::vector<std::string> closestNames(std::string_view word, const std::vector<std::string>& candidates,
                                      std::size_t max) {
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  std::vector<std::pair<std::size_t, std::string>> scored;
  for (const auto& c : candidates) {
    std::size_t d = editDistance(word, c);
    if (d <= limit) scored.emplace_back(d, c);
  }
  std::stable_sort(scored.begin(), scored.end(), [](auto& x, auto& y) { return x.first < y.first; });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < scored.size() && i < max; ++i) out.push_back(scored[i].second);
  return out;
}

std::string didYouMean(const std::vector<std::string>& suggestions) {
  std::string s;
  for (const auto& n : suggestions) s += (s.empty() ? "; did you mean '" : "', '") + n;
  return s.empty() ? s : s + "'?";
}

}  // namespace millsim
