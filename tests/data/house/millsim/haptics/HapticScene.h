#pragma once
// Fixture: the renderer contract reaches OpenVDB.
#include <openvdb/openvdb.h>
