#pragma once
// Reading the text of a scene file: the XML encoding only (the ClassicVRML
// and JSON encodings are refused by name), gzip-compressed (.x3d.gz, .x3dz,
// or any file starting with gzip's magic bytes) or plain.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace millsim {

// A message when `file` names an X3D encoding MillSim does not read
// (.x3dv, .x3dvz, .x3dj, .wrl), else nullopt.
std::optional<std::string> unsupportedEncoding(const std::filesystem::path& file);

// A local scene file named by a url (an Inline's, or an ExternProtoDeclare's
// without its '#name'), relative to `dir`, and its canonical path (for cycle
// checks). Nullopt if it cannot be read: a network url, an encoding MillSim
// does not read, no such file; then why is appended to `tried` as "\n  reason",
// so a list of fallback urls can say what was wrong with each.
struct LocalSceneFile {
  std::filesystem::path path, canonical;
};
std::optional<LocalSceneFile> localSceneFile(const std::string& url, const std::filesystem::path& dir,
                                             std::string& tried);

// Reads `file` into `out`, inflating gzip data. Returns an error message, or
// nullopt on success. Neither the file nor its inflated text may exceed `maxBytes`.
std::optional<std::string> readSceneText(const std::filesystem::path& file, std::uintmax_t maxBytes, std::string& out);

}  // namespace millsim
