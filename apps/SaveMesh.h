#pragma once
// --save-mesh FILE for run and replay: the milled volume's surface at the end,
// in millimetres, for comparing a preparation with an ideal one in a mesh tool
// — .stl the whole surface, .obj and .ply a solid per tissue (SurfaceExport.h).
#include <filesystem>
#include <string>

#include "millsim/core/Scene.h"

namespace millsim::app {

// Before the run: one volume and a writable .stl, .obj or .ply path, or
// std::invalid_argument saying what is wrong.
void checkSaveMesh(const Scene& scene, const std::filesystem::path& file);

// After the run (the haptic thread has stopped): writes it; returns the lines to print.
std::string saveMesh(const Scene& scene, const std::filesystem::path& file);

}  // namespace millsim::app
