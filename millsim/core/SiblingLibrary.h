#pragma once
// Opening one of MillSim's libraries that are loaded on demand (graphics,
// window, audio, medical, the voxels' libmillsim, the command's verbs), which
// sit next to libmillsim_scene: dlopen, look up its entry point, and say in
// one sentence why not.
#include <string>

namespace millsim {

// `fileName` next to libmillsim_scene, unless the environment variable
// `overrideVar` names another path or the process has already loaded a
// library of that name (that copy is used); returns the entry function's
// result (the module table, whose first member is its `int abiVersion`) when
// that table is of `abiVersion`, else null with `error` set. `hint` ends the
// error when the library cannot be loaded (which package is missing).
const void* openSiblingLibrary(const char* fileName, const char* overrideVar, const char* entry, int abiVersion,
                               const char* what, const char* hint, std::string& error);

}  // namespace millsim
