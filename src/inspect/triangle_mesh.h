#pragma once
// The inspector's mesh is the mesh files' own type (base/triangle_mesh.h): what the file
// holds, nothing merged, reordered or repaired, so the inspector reports the file as it is.
#include "base/triangle_mesh.h"

namespace thaw::inspect {

using TriangleMesh = meshio::TriangleMesh;

}  // namespace thaw::inspect
