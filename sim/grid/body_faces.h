#pragma once
// The named faces of a grid body's outer surface, for the heat that enters through each
// (DIR/boundary_heat.csv): a box has x_min, x_max, y_min, y_max, z_min, z_max; a (vertical)
// cylinder top, bottom and side; any other body one face, surface. A surface cell's heat is
// split between the faces by the components of the surface's outward normal there (box: |n_a| /
// sum |n| to the face of n_a's sign; cylinder: |n_y| to top or bottom, the horizontal part to
// side), so a flat face's cells go to it alone, an edge's cells half to each of the two faces,
// and a melted, rounded corner by the way its surface faces. A cell without a normal (no
// gradient of material around it) goes to the face its centre's direction from the body's
// centre points at, measured against the body's half sizes. Knows nothing of files or heat.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/shape/shape.h"

namespace thaw::sim {

/// At most this many faces (a box's).
constexpr std::size_t kMaxBodyFaces = 6;
using FaceWeights = std::array<double, kMaxBodyFaces>;

/// The faces of a body of kind `kind`, in their order (boundary_heat.csv's row order).
std::vector<std::string> body_face_names(ShapeKind kind);

/// The face (index into body_face_names(outer.kind)) of the point `p_m` (scenario coordinates;
/// axisymmetric grids pass (r, y, 0)): the largest of |p_a - c_a| / (size_a / 2) (box; ties to
/// the earlier axis) or of |y - c_y| / (height / 2) against r / radius (cylinder; ties to the
/// ends).
std::uint8_t body_face_of_point(const ShapeSpec& outer, const std::array<double, 3>& p_m,
                                bool axisymmetric);

/// The weights (summing to 1) of the faces of a body of kind `kind` for a surface whose outward
/// normal is `n` (any length; axisymmetric: (n_r, n_y, 0)); a zero normal gives all to
/// `fallback`.
FaceWeights body_face_weights(ShapeKind kind, const std::array<double, 3>& n, bool axisymmetric,
                              std::uint8_t fallback);

}  // namespace thaw::sim
