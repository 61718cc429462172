#pragma once
// Reads X3D (XML encoding) into a Scene with libxml2. Network access, DTD
// loading and entity expansion are off. Every problem is a Diagnostic with
// file:line:column; a scene with errors yields no Scene, never a crash.
#include <filesystem>
#include <optional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "millsim/core/Diagnostics.h"
#include "millsim/core/Plugin.h"
#include "millsim/core/Scene.h"

namespace millsim {

struct LoadOptions {
  PluginPolicy plugins{false, pluginPathFromEnvironment()};
  // false: Inline and ImportLibrary are refused (for untrusted text and fuzzing).
  bool allowFileAccess = true;
  std::size_t maxErrors = 25;
  int maxInlineDepth = 16;
  std::uintmax_t maxFileBytes = 64u << 20;  // X3D text, not volume data
  // Body elements all ProtoInstances of a load may expand to: protos that
  // instantiate others several times multiply, like an XML entity bomb.
  std::size_t maxProtoElements = 1000000;
  // true: every warning is an error too (the verbs' --strict), so a scene that
  // loads only by skipping or guessing is refused.
  bool strict = false;
  // `--set TYPE.FIELD=VALUE` (a sweep's field axis): the field of every node of
  // that type is set to the value after the file's attributes and before the
  // node initialises, so an initializeOnly field (VolumeObject.voxelSize)
  // takes effect too. A type the scene does not have, a field it does not
  // have or a bad value is an error naming the override.
  struct FieldOverride {
    std::string type, field, value;
    std::string text() const { return type + "." + field + "=" + value; }
  };
  std::vector<FieldOverride> overrides;
  // Hears the load's long steps as they start and end (millsim/core/Progress.h); not owned.
  LoadProgress* progress = nullptr;
};

// Parses TYPE.FIELD=VALUE; std::nullopt if it has no '.' before the '=' or an empty part.
std::optional<LoadOptions::FieldOverride> parseFieldOverride(std::string_view text);

struct LoadResult {
  std::unique_ptr<Scene> scene;  // null when there were errors
  std::vector<Diagnostic> diagnostics;
  bool ok() const { return scene != nullptr; }
  std::string report() const;  // all diagnostics, one per line
};

LoadResult loadSceneFile(const std::filesystem::path& file, const NodeRegistry& registry,
                         const LoadOptions& options = {});
// `fileLabel` names the text in diagnostics; `baseDir` resolves Inline and ImportLibrary.
LoadResult loadSceneString(std::string_view text, std::string fileLabel, const NodeRegistry& registry,
                           const LoadOptions& options = {}, const std::filesystem::path& baseDir = {});

}  // namespace millsim
