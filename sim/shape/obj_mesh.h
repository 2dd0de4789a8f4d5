#pragma once
// A closed, outward-oriented triangle mesh read from a Wavefront OBJ file by thaw's one strict
// reader (base/obj_reader.h, a plain library), and its signed distance: distance to the
// nearest triangle, negative inside by the generalised winding number (Jacobson et al. 2013,
// "Robust inside-outside segmentation using generalized winding numbers"). Knows nothing of grids.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace thaw::sim {

struct ObjMesh {
  std::vector<std::array<double, 3>> vertices;           ///< [m] after scale and translation
  std::vector<std::array<int, 3>> triangles;             ///< counter-clockwise seen from outside
  std::array<double, 3> lower{0, 0, 0}, upper{0, 0, 0};  ///< bounding box [m]

  /// Signed distance [m]: negative inside.
  double signed_distance(const std::array<double, 3>& p) const;
  /// Enclosed volume [m^3] (divergence theorem).
  double volume() const;
};

/// Reads `file`, scales and translates its vertices, fans polygons into triangles and checks
/// that the mesh is closed, edge-manifold and consistently oriented with a positive volume.
/// Throws thaw::UserError(scenario, key, problem naming the OBJ file) otherwise.
ObjMesh read_obj_mesh(const std::filesystem::path& file, double scale,
                      const std::array<double, 3>& translate_m, const std::string& scenario,
                      const std::string& key);

}  // namespace thaw::sim
