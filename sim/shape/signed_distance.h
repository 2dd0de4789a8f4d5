#pragma once
// Signed distance of a ShapeSpec (negative inside) in 3D and, for bodies of revolution about
// the vertical y axis, in the (r, y) half plane; the wall thickness between an outer body and
// its cavity. Exact for spheres, cylinders and (rounded) boxes; OBJ meshes via
// sim/shape/obj_mesh.h. Knows nothing of grids or TOML.
#include <array>
#include <memory>

#include "sim/shape/obj_mesh.h"
#include "sim/shape/shape.h"

namespace thaw::sim {

class SignedDistance {
 public:
  /// `mesh` is required for ShapeKind::obj (read_obj_mesh), ignored otherwise.
  SignedDistance(const ShapeSpec& spec, std::shared_ptr<const ObjMesh> mesh = nullptr);
  /// Distance to the surface [m], negative inside.
  double operator()(const std::array<double, 3>& p) const;
  /// Bounding box [m].
  std::array<double, 3> lower() const;
  std::array<double, 3> upper() const;
  /// Points on the surface, about `count` of them, corners and edges included (for the
  /// containment and wall-thickness checks).
  std::vector<std::array<double, 3>> surface_samples(int count) const;

 private:
  ShapeSpec m_spec;
  std::shared_ptr<const ObjMesh> m_mesh;
};

}  // namespace thaw::sim
