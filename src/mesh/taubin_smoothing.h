#pragma once
// Taubin's lambda|mu smoothing of a triangle surface (G. Taubin, "A signal processing approach to
// fair surface design", SIGGRAPH 1995): each pass moves every vertex towards the mean of its
// neighbours by lambda, then away by -mu (mu < -lambda), a low-pass filter on the surface that
// removes the cell-scale bumps of a surface extracted from a volume-fraction field without the
// shrinkage of plain Laplacian smoothing (or of smoothing the field itself, which moves a
// curved interface inwards by ~ sigma^2 times its mean curvature). Connectivity is unchanged.
// Knows nothing about CGAL or fields.
#include "src/mesh/triangle_mesh.h"

namespace thaw::mesh {

struct TaubinOptions {
  int passes = 10;
  double lambda = 0.5;
  /// Taubin's pass-band k_PB = 1/lambda + 1/mu = 0.1: frequencies below it (features wider than
  /// ~10 edges) pass unchanged.
  double mu = -0.5263;
};

/// Smooths `mesh` in place (uniform neighbour weights: meant for isotropic meshes). Normals are
/// left as they are (recompute them after).
void taubin_smooth(TriangleMesh& mesh, const TaubinOptions& options = {});

}  // namespace thaw::mesh
