#pragma once
// Turning mesh geometry nodes into TriangleMeshes (X3D 4.0, 11 and 13):
// faces split into triangles, normals computed where the file gives none
// (flat, or smoothed across edges sharper than creaseAngle), colours and
// texture coordinates per vertex or per face, X3D's default texture mapping.
// Indices out of range are skipped (the loader has already reported them).
// No OpenGL: the scene thread builds these for graphics.
#include <memory>

#include "millsim/graphics/TriangleMesh.h"

namespace millsim {

class Cone;
class IndexedFaceSet;
class IndexedTriangleSet;

TriangleMesh meshOf(const IndexedFaceSet& faces);
TriangleMesh meshOf(const IndexedTriangleSet& triangles);
TriangleMesh meshOf(const Cone& cone);

// The unit primitives of SceneDrawer with X3D's texture coordinates, for a
// textured Sphere (radius 1), Cylinder (radius 1, height 1 along Y) or Box (edge 1).
TriangleMesh texturedSphere(int slices = 48, int stacks = 24);
TriangleMesh texturedCylinder(int slices = 48);
TriangleMesh texturedBox();

}  // namespace millsim
