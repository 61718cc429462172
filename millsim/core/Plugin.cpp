#include "millsim/core/Plugin.h"

#include <dlfcn.h>

#include <cstdlib>

namespace millsim {

namespace fs = std::filesystem;

std::vector<fs::path> pluginPathFromEnvironment() {
  std::vector<fs::path> dirs;
  const char* env = std::getenv("MILLSIM_PLUGIN_PATH");
  if (!env) return dirs;
  std::string s(env);
  std::size_t start = 0;
  while (start <= s.size()) {
    std::size_t end = s.find(':', start);
    if (end == std::string::npos) end = s.size();
    if (end > start) dirs.emplace_back(s.substr(start, end - start));
    start = end + 1;
  }
  return dirs;
}

fs::path resolvePlugin(const std::string& url, const fs::path& sceneDir, const PluginPolicy& policy) {
  if (url.empty()) throw PluginError("empty library name");
  if (url.find("://") != std::string::npos) throw PluginError("'" + url + "' is a URL; plugins load from local files only");
  const fs::path given(url);
  bool climbs = false;
  for (const auto& part : given)
    if (part == "..") climbs = true;
  if (!policy.allowAnyPath && (given.is_absolute() || climbs))
    throw PluginError("refusing plugin path '" + url +
                      "': absolute paths and '..' are not allowed (run millsim with --allow-plugin-path to permit them)");

  // Accept the name as written, or the platform's spelling of it.
  std::vector<fs::path> names{given};
  if (given.extension() != ".so") {
    names.push_back(fs::path(url + ".so"));
    if (given.filename().string().rfind("lib", 0) != 0)
      names.push_back(given.parent_path() / ("lib" + given.filename().string() + ".so"));
  }
  if (given.is_absolute()) {
    for (const auto& n : names)
      if (fs::is_regular_file(n)) return n;
    throw PluginError("plugin library '" + url + "' does not exist");
  }
  std::vector<fs::path> dirs{sceneDir.empty() ? fs::path(".") : sceneDir};
  dirs.insert(dirs.end(), policy.searchPath.begin(), policy.searchPath.end());
  std::string looked;
  for (const auto& d : dirs) {
    for (const auto& n : names) {
      fs::path candidate = d / n;
      std::error_code ec;
      if (fs::is_regular_file(candidate, ec)) return candidate;
    }
    looked += (looked.empty() ? "" : ", ") + d.string();
  }
  throw PluginError("plugin library '" + url + "' not found; looked in: " + looked +
                    " (the scene's folder, then MILLSIM_PLUGIN_PATH)");
}

void loadPlugin(const fs::path& library, NodeRegistry& registry) {
  // RTLD_LOCAL keeps one plugin's symbols from satisfying another's; the handle
  // is never closed because nodes made by the plugin run its code.
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw PluginError("cannot load plugin '" + library.string() + "': " + (why ? why : "unknown error"));
  }
  using VersionFn = int (*)();
  using RegisterFn = void (*)(NodeRegistry&);
  auto version = reinterpret_cast<VersionFn>(dlsym(handle, "millsim_plugin_abi_version"));
  auto registerNodes = reinterpret_cast<RegisterFn>(dlsym(handle, "millsim_register_nodes"));
  if (!version || !registerNodes)
    throw PluginError("'" + library.string() +
                      "' is not a MillSim plugin: it must export millsim_plugin_abi_version and millsim_register_nodes");
  if (int v = version(); v != kPluginAbiVersion)
    throw PluginError("plugin '" + library.string() + "' was built for plugin ABI " + std::to_string(v) +
                      ", this MillSim expects " + std::to_string(kPluginAbiVersion));
  try {
    registerNodes(registry);
  } catch (const std::exception& e) {
    throw PluginError("plugin '" + library.string() + "' failed to register its nodes: " + e.what());
  }
}

}  // namespace millsim
