#pragma once
// Which surface of the shell a mesh is, for drawing it (surface_actor.h): the shared vocabulary
// of the inspector's pictures and the GUI's 3D view. VTK-free.
namespace thaw::inspect {

/// How a surface is drawn: a lone mesh (opaque grey), an inner surface (opaque water blue) or an
/// outer surface (translucent ice).
enum class SurfaceRole { single, inner, outer };

}  // namespace thaw::inspect
