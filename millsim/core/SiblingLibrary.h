#pragma once
// Opening one of MillSim's optional libraries (graphics, window, audio) that
// sit next to libmillsim: dlopen, look up its entry point, and say in one
// sentence why not. Shared by loadGraphicsModule(), loadWindowModule() and
// loadAudioModule().
#include <string>

namespace millsim {

// `fileName` next to libmillsim unless the environment variable `overrideVar`
// names another path; returns the entry function's result (the module table)
// or null with `error` set. `hint` ends the error (which package is missing).
const void* openSiblingLibrary(const char* fileName, const char* overrideVar, const char* entry, const char* what,
                               const char* hint, std::string& error);

}  // namespace millsim
