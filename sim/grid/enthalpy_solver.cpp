#include "sim/grid/enthalpy_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <omp.h>

#include "base/check.h"
#include "sim/grid/block_team.h"

namespace thaw::sim {

double enthalpy_of_temperature(const Materials& m, double t_c, bool liquid) {
  const double u = t_c - m.melting_point_c;
  if (liquid) return m.latent_heat_per_volume() + m.water_heat_capacity() * std::max(u, 0.0);
  return m.ice_heat_capacity() * std::min(u, 0.0);
}

namespace {

/// Cells per block of the deterministic sums: partial sums of fixed blocks added in order, so
/// results do not depend on the thread count.
constexpr long kBlock = 4096;
/// Below this many cells a step runs on one thread (the barriers would cost more than the work).
constexpr long kParallelCells = 16384;

/// Sum of f(c) over the cells by fixed blocks added in order (the same bits as the solver's
/// parallel block sums). Serial: a per-step reduction is too little work for a parallel region.
template <class F>
double sum_cells(long n, F&& f) {
  double total = 0;
  for (long b = 0; b * kBlock < n; ++b) {
    double s = 0;
    const long end = std::min(n, (b + 1) * kBlock);
    for (long c = b * kBlock; c < end; ++c) s += f(c);
    total += s;
  }
  return total;
}

enum CellType : unsigned char { kAir = 0, kIce = 1, kWater = 2, kMushy = 3 };

/// Newton stops when every cell's balance residual, expressed as a temperature, is below this
/// [K]. Tight enough that mirror-image cells of a symmetric body, whose Newton paths can part
/// where round-off decides on which side of a kink of T(h) a cell lies, still agree far below
/// 1e-9 L_v (tests/sim/grid/test_grid_runs.cpp); it costs about one iteration over 1e-5 K.
constexpr double kNewtonTolerance_K = 1e-7;
constexpr int kMaxNewton = 12;
/// Newton stalling (the residual not halved by an iteration: cells at a kink of T(h) trading
/// places between the melting plateau and a pure phase) is accepted below this residual [K].
constexpr double kStagnantResidual_K = 1e-5;
/// A Newton that has not reached kNewtonTolerance_K in kMaxNewton iterations (it can cycle
/// between the sides of a kink of T(h)) is still accepted below this residual [K]: the final
/// conservative update keeps the energy exact, the residual is only a temperature error.
constexpr double kAcceptableResidual_K = 1e-3;
constexpr int kMaxCg = 5000;
/// A melting cell's Newton update that leaves the plateau stops this far (relative to L_v)
/// past its end: in the new phase, at T_m within L_v kKinkStep / (rho c) ~ 2e-7 K.
constexpr double kKinkStep = 1e-9;
/// A melting cell's update that ends this close (relative to L_v) to an end of the plateau
/// lands on it: the last digits of an enthalpy near a kink are round-off, and its sign decides
/// the cell's phase in the next iteration (mirror-image cells must decide alike).
constexpr double kKinkSnap = 1e-10;
/// Newton failing at this step accepts its last iterate (energy is conserved by the final
/// update whatever the iterate) and counts it in GridStatistics::unconverged_steps.
constexpr double kMinStep_s = 1e-3;
/// Ice left in a drained cell below this fraction is removed with it: at T_m its enthalpy is
/// zero, so the energy balance is untouched; the volume is booked as removed_ice_m3.
constexpr double kRemnantFraction = 1e-3;
/// The ice is gone (fully_melted, the run ends) below this fraction of the initial material
/// volume: stray sub-cell remnants would otherwise linger for minutes at a few mm^3.
constexpr double kGoneFraction = 1e-5;

}  // namespace

struct EnthalpySolver::Impl {
  GridProblem p;
  long n = 0;
  int nx = 0, ny = 0, nz = 0;
  bool axisymmetric = false;
  double s = 0, latent = 0, tm = 0, ci = 0, cw = 0, ki = 0, kw = 0;

  std::vector<double> vol;     ///< cell volume [m^3]
  std::vector<double> area_x;  ///< area of the face between i and i+1 (per i) [m^2]
  std::vector<double> area_y;  ///< area of a y face (per i) [m^2]
  double area_z = 0;           ///< area of a z face [m^2]
  std::vector<double> m, h, hn, t, t_start, f_start;
  std::vector<double> rate;  ///< each cell's rate of temperature change in the last step [K/s]
  std::vector<double> kx, ky, kz;    ///< face conductances to the +x, +y, +z neighbour [W/K]
  std::vector<double> bq0, bq1;      ///< boundary heat into the cell: bq0 - bq1 T [W]
  std::vector<double> surface_area;  ///< material | air area assigned to the cell [m^2]
  std::vector<unsigned char> type;
  std::vector<double> cg_r, cg_z, cg_p, cg_p2, cg_q, dtemp, diag, rhs;
  std::vector<double> partial_rz, partial_res, partial_pq, partial_newton;  ///< per-block partials
  std::vector<double> area_g, area_w, area_share;  ///< update_surface_area's work arrays
  /// m with the surface moved half a step ahead (update_surface_area)
  std::vector<double> m_moved;
  /// The fractions whose gradient gives the surface area: m itself, or m_moved.
  const double* m_geo = nullptr;
  double recession_m_s = 0;  ///< mean speed of the draining surface in the last step [m/s]
  bool area_stale = false;   ///< the surface moved, or the area was taken ahead: recompute
  bool area_ahead = false;   ///< the current area was taken ahead of the fractions
  std::vector<char> open_prev, enclosed_prev, exposed, open_now, outside_now;
  std::vector<long> queue;  ///< the flood fill's breadth-first queue

  double time = 0;
  double dt = 0;       ///< the step being taken [s]
  double dt_next = 0;  ///< the next step's size [s]
  bool done = false, broke_through = false, melt_started = false, core_frozen = false;
  bool had_enclosed_liquid = false;
  double e0 = 0, heat_in = 0, drained = 0, reference = 0, initial_material = 0;
  std::vector<GridEvent> events;
  GridStatistics stats;

  explicit Impl(GridProblem problem) : p(std::move(problem)) {
    nx = p.cells[0];
    ny = p.cells[1];
    nz = p.cells[2];
    n = static_cast<long>(nx) * ny * nz;
    axisymmetric = p.geometry == GridField::Geometry::axisymmetric;
    THAW_CHECK(nx > 0 && ny > 0 && nz > 0 && p.spacing_m > 0, "grid problem with an empty grid");
    THAW_CHECK(!axisymmetric || nz == 1, "axisymmetric grids have one cell in z");
    THAW_CHECK(static_cast<long>(p.material_fraction.size()) == n &&
                   static_cast<long>(p.enthalpy_j_m3.size()) == n,
               "grid problem arrays must have one value per cell");
    s = p.spacing_m;
    const Materials& mat = p.materials;
    latent = mat.latent_heat_per_volume();
    tm = mat.melting_point_c;
    ci = mat.ice_heat_capacity();
    cw = mat.water_heat_capacity();
    ki = mat.ice_conductivity_w_mk;
    kw = mat.water_conductivity_w_mk;
    build_metric();
    m = p.material_fraction;
    h = p.enthalpy_j_m3;
    for (long c = 0; c < n; ++c) {
      THAW_CHECK(m[c] >= 0 && m[c] <= 1 && std::isfinite(h[c]), "material fraction outside [0, 1]");
      if (m[c] == 0) h[c] = 0;
    }
    // every work array once, here: a step allocates nothing
    for (auto* v :
         {&rate, &hn,           &t,      &t_start,    &f_start, &kx,    &ky,   &kz,    &bq0,
          &bq1,  &surface_area, &cg_r,   &cg_z,       &cg_p,    &cg_p2, &cg_q, &dtemp, &diag,
          &rhs,  &area_g,       &area_w, &area_share, &m_moved})
      v->assign(static_cast<std::size_t>(n), 0.0);
    const auto blocks = static_cast<std::size_t>(block_count());
    for (auto* v : {&partial_rz, &partial_res, &partial_pq, &partial_newton})
      v->assign(blocks, 0.0);
    block_sums.assign(blocks, BlockSums{});
    type.assign(static_cast<std::size_t>(n), kAir);
    for (auto* v : {&open_prev, &enclosed_prev, &exposed, &open_now, &outside_now})
      v->assign(static_cast<std::size_t>(n), 0);
    queue.reserve(static_cast<std::size_t>(n));
    initial_material = sum_cells(n, [&](long c) { return m[c] * vol[c]; });
    reference = latent * initial_material;
    THAW_CHECK(reference > 0, "a grid problem needs some material");
    // The initial state drains nothing by definition: only classify which liquid is enclosed.
    TeamShared alone;  // the constructor's phases on this thread only
    BlockTeam team(alone, 0, block_count());
    classify_openness(team);
    had_enclosed_liquid = enclosed_liquid_volume() > 0;
    update_surface_area(team);
    e0 = energy();
    dt_next = p.fixed_step_s > 0 ? p.fixed_step_s : std::min(p.max_step_s, 0.05);
  }

  // --- geometry -------------------------------------------------------------------------------
  void build_metric() {
    vol.assign(static_cast<std::size_t>(n), 0.0);
    area_x.assign(static_cast<std::size_t>(nx), 0.0);
    area_y.assign(static_cast<std::size_t>(nx), 0.0);
    const double pi = std::numbers::pi;
    for (int i = 0; i < nx; ++i) {
      if (axisymmetric) {
        // Full rings about the y axis: volumes and areas of the whole revolution.
        const double r0 = i * s, r1 = (i + 1) * s;
        area_x[i] = 2 * pi * r1 * s;
        area_y[i] = pi * (r1 * r1 - r0 * r0);
      } else {
        area_x[i] = s * s;
        area_y[i] = s * s;
      }
    }
    area_z = s * s;
    for (long c = 0; c < n; ++c) vol[c] = area_y[c % nx] * s;
  }
  std::array<double, 3> centre(long c) const {
    const int i = static_cast<int>(c % nx), j = static_cast<int>((c / nx) % ny),
              k = static_cast<int>(c / (static_cast<long>(nx) * ny));
    return {p.origin_m[0] + (i + 0.5) * s, p.origin_m[1] + (j + 0.5) * s,
            axisymmetric ? 0.0 : p.origin_m[2] + (k + 0.5) * s};
  }

  // --- phase relation -------------------------------------------------------------------------
  double temperature(double hc) const {
    if (hc < 0) return tm + hc / ci;
    if (hc > latent) return tm + (hc - latent) / cw;
    return tm;
  }
  double liquid(double hc) const { return std::clamp(hc / latent, 0.0, 1.0); }
  double conductivity(double hc) const {
    const double f = liquid(hc);
    return (1 - f) * ki + f * kw;
  }
  double energy() const {
    return sum_cells(n, [&](long c) { return m[c] * vol[c] * h[c]; });
  }
  double ice_fraction(long c) const { return m[c] * (1 - liquid(h[c])); }
  double enclosed_liquid_volume() const {
    return sum_cells(n, [&](long c) { return exposed[c] ? 0.0 : m[c] * vol[c] * liquid(h[c]); });
  }

  /// Conductance per unit face area [W/(m^2 K)] between neighbouring material cells a and b.
  /// Sub-cell front reconstruction: a cell at the melting point (0 <= h <= L_v) next to a cell
  /// in a pure phase P holds the front, at T_m, at depth f_P s from their shared face, where
  /// f_P is its volume fraction of P (the phase on the neighbour's side of a front crossing the
  /// cell parallel to the face). The heat between the pure cell's centre and the front flows
  /// through phase P only, over s/2 + f_P s. (The plain enthalpy method puts T_m at the cell
  /// centre whatever f is: an O(1) relative flux error next to the front, which makes the front
  /// position first order; see docs/simulate.md for the measured orders.) Otherwise the
  /// harmonic mean of the fraction-weighted conductivities over the two half cells.
  double face_conductance_per_area(long a, long b) const {
    const bool melting_a = h[a] >= 0 && h[a] <= latent, melting_b = h[b] >= 0 && h[b] <= latent;
    if (melting_a != melting_b) {
      const long front_cell = melting_a ? a : b, pure_cell = melting_a ? b : a;
      const bool water = h[pure_cell] > latent;
      const double f = liquid(h[front_cell]);
      return (water ? kw : ki) / (s * (0.5 + (water ? f : 1 - f)));
    }
    const double ka = conductivity(h[a]), kb = conductivity(h[b]);
    return 2 * ka * kb / ((ka + kb) * s);  // harmonic mean over two half cells
  }

  // --- per-step coefficients ------------------------------------------------------------------
  /// Cell c's conductances (to its +x, +y, +z neighbours) and boundary terms, frozen over one
  /// step at the step's initial state.
  void build_coefficients(long c, int i, int j, int k) {
    const long nxy = static_cast<long>(nx) * ny;
    {
      kx[c] = ky[c] = kz[c] = bq0[c] = bq1[c] = 0;
      if (m[c] == 0) return;
      const double kc = conductivity(h[c]);
      auto face = [&](long nb, double area) {
        return m[nb] == 0 ? 0.0 : area * face_conductance_per_area(c, nb);
      };
      if (i + 1 < nx) kx[c] = face(c + 1, area_x[i]);
      if (j + 1 < ny) ky[c] = face(c + nx, area_y[i]);
      if (k + 1 < nz) kz[c] = face(c + nxy, area_z);
      // Held walls: two-point flux over half a cell.
      auto wall = [&](const GridWall& w, double area) {
        if (!w.held || area == 0) return;
        const double g = area * kc / (0.5 * s);
        bq0[c] += g * w.temperature_c;
        bq1[c] += g;
      };
      if (i == 0) wall(p.walls[0], axisymmetric ? 0.0 : area_x[0]);
      if (i == nx - 1) wall(p.walls[1], area_x[i]);
      if (j == 0) wall(p.walls[2], area_y[i]);
      if (j == ny - 1) wall(p.walls[3], area_y[i]);
      if (!axisymmetric && k == 0) wall(p.walls[4], area_z);
      if (!axisymmetric && k == nz - 1) wall(p.walls[5], area_z);
      const double a = surface_area[c];
      if (a > 0) {
        switch (p.surface_kind) {
          case OuterBoundary::convective: {
            // The film h in series with the conduction between the cell's temperature point and
            // the surface, half a cell (as for a held surface below): h (T_air - T_c) alone
            // puts the surface at the cell centre, an O(h s / k) relative excess of the flux
            // (first order; 1.4 % at h = 100, s = 0.625 mm). A cell at the melting point holds
            // the front, at T_m, on the surface (ablation) or within it: no added resistance.
            const double film = p.heat_transfer_coefficient_w_m2k;
            const bool at_front = h[c] >= 0 && h[c] <= latent;
            const double g = at_front ? a * film : a / (1 / film + 0.5 * s / kc);
            bq0[c] += g * p.surface_temperature_c;
            bq1[c] += g;
            break;
          }
          case OuterBoundary::temperature: {
            const double g = a * kc / (0.5 * s);
            bq0[c] += g * p.surface_temperature_c;
            bq1[c] += g;
            break;
          }
          case OuterBoundary::flux:
            bq0[c] += a * p.flux_w_m2;
            break;
          case OuterBoundary::insulated:
            break;
        }
      }
    }
  }

  /// Net heat rate into cell c (at i, j, k) at temperatures t [W].
  double heat_rate(long c, int i, int j, int k) const {
    const double tc = t[c];
    return neighbour_sum_of(
        c, i, j, k, [&](long nb) { return t[nb] - tc; }, bq0[c] - bq1[c] * tc);
  }
  double conductance_sum(long c, int i, int j, int k) const {
    const long nxy = static_cast<long>(nx) * ny;
    double g = bq1[c];
    if (i + 1 < nx) g += kx[c];
    if (i > 0) g += kx[c - 1];
    if (j + 1 < ny) g += ky[c];
    if (j > 0) g += ky[c - nx];
    if (k + 1 < nz) g += kz[c];
    if (k > 0) g += kz[c - nxy];
    return g;
  }
  /// q0 + the sum over neighbours of K * v(nb), v a function of the neighbour's index; cell c
  /// is at (i, j, k). The terms are added in a fixed order (+x, -x, +y, -y, +z, -z): the same
  /// bits wherever it is called.
  template <class V>
  double neighbour_sum_of(long c, int i, int j, int k, V&& v, double q0 = 0) const {
    const long nxy = static_cast<long>(nx) * ny;
    double q = q0;
    if (i + 1 < nx) q += kx[c] * v(c + 1);
    if (i > 0) q += kx[c - 1] * v(c - 1);
    if (j + 1 < ny) q += ky[c] * v(c + nx);
    if (j > 0) q += ky[c - nx] * v(c - nx);
    if (k + 1 < nz) q += kz[c] * v(c + nxy);
    if (k > 0) q += kz[c - nxy] * v(c - nxy);
    return q;
  }

  // --- one backward Euler step ----------------------------------------------------------------
  /// Residual of cell c's balance: M/dt (h - h_n) - heat rate [W].
  double residual(long c, int i, int j, int k) const {
    return m[c] * vol[c] / dt * (h[c] - hn[c]) - heat_rate(c, i, j, k);
  }

  long block_count() const { return (n + kBlock - 1) / kBlock; }
  long block_end(long bl) const { return std::min(n, (bl + 1) * kBlock); }
  /// f(c, i, j, k) for the cells c of block bl in order, with their grid indices kept by
  /// counting (three integer divisions per block instead of per cell).
  template <class F>
  void for_cells(long bl, F&& f) const {
    long c = bl * kBlock;
    const long end = block_end(bl), row = c / nx;
    int i = static_cast<int>(c % nx), j = static_cast<int>(row % ny),
        k = static_cast<int>(row / ny);
    for (; c < end; ++c) {
      f(c, i, j, k);
      if (++i == nx) {
        i = 0;
        if (++j == ny) {
          j = 0;
          ++k;
        }
      }
    }
  }
  static double ordered_sum(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s;
  }
  static double largest(const std::vector<double>& v) {
    double m = 0;
    for (double x : v) m = std::max(m, x);
    return m;
  }
  bool pure(long c) const { return type[c] == kIce || type[c] == kWater; }

  /// The conjugate gradients' start on block bl (x = 0, r = rhs, z = r / diag, p = 0) and its
  /// partials of r.z and of the residual; done with the Newton residual, which saves a barrier
  /// (wasted only when Newton has converged).
  void start_cg(long bl) {
    double rz = 0, res = 0;
    for (long c = bl * kBlock; c < block_end(bl); ++c) {
      dtemp[c] = 0;
      cg_r[c] = pure(c) ? rhs[c] : 0.0;
      cg_z[c] = pure(c) ? cg_r[c] / diag[c] : 0.0;
      cg_p[c] = 0;  // so that the first fused update gives p = z
      rz += cg_r[c] * cg_z[c];
      res = std::max(res, pure(c) ? std::abs(cg_r[c]) / diag[c] : 0.0);
    }
    partial_rz[static_cast<std::size_t>(bl)] = rz;
    partial_res[static_cast<std::size_t>(bl)] = res;
  }

  /// Conjugate gradients with a Jacobi preconditioner on the pure cells' temperature changes:
  /// (diag_c) x_c - sum K x_nb = b_c. Run by the team's leader; returns iterations.
  ///
  /// Two phases per iteration: the direction update p = z + beta p is fused into the matrix
  /// product by double-buffering p (each cell recomputes its neighbours' new p from z and the
  /// old p: the same operations, so the same bits). Every reduction goes over fixed blocks whose
  /// partials the leader adds in block order, so the result does not depend on the thread
  /// count.
  int conjugate_gradients(BlockTeam& team, double tol) {
    std::vector<double>& x = dtemp;
    // x = 0, r = b, z = r / diag, p = 0 and the partials of r.z and of the residual were set by
    // prepare_newton_iteration (start_cg), one phase earlier.
    double rz = ordered_sum(partial_rz), res = largest(partial_res), beta = 0;
    std::vector<double>* po = &cg_p;
    std::vector<double>* pn = &cg_p2;
    for (int it = 0;; ++it) {
      if (res <= tol || rz == 0 || it == kMaxCg) return it;
      const std::vector<double>& p_old = *po;
      std::vector<double>& p_new = *pn;
      // z and the old p are zero outside the pure cells (start_cg, and p_new below), so the
      // direction there is exactly 0: the same term the product needs from a non-pure neighbour.
      auto direction = [&](long c) { return cg_z[c] + beta * p_old[c]; };
      team.for_blocks([&](long bl) {
        double pq = 0;
        for_cells(bl, [&](long c, int i, int j, int k) {
          if (!pure(c)) {
            p_new[c] = cg_q[c] = 0;
            return;
          }
          const double pc = direction(c);
          p_new[c] = pc;
          cg_q[c] = diag[c] * pc - neighbour_sum_of(c, i, j, k, direction);
          pq += pc * cg_q[c];
        });
        partial_pq[static_cast<std::size_t>(bl)] = pq;
      });
      const double alpha = rz / ordered_sum(partial_pq);
      team.for_blocks([&](long bl) {
        double rz_b = 0, res_b = 0;
        for (long c = bl * kBlock; c < block_end(bl); ++c) {
          if (!pure(c)) continue;
          x[c] += alpha * p_new[c];
          cg_r[c] -= alpha * cg_q[c];
          cg_z[c] = cg_r[c] / diag[c];
          rz_b += cg_r[c] * cg_z[c];
          res_b = std::max(res_b, std::abs(cg_r[c]) / diag[c]);
        }
        partial_rz[static_cast<std::size_t>(bl)] = rz_b;
        partial_res[static_cast<std::size_t>(bl)] = res_b;
      });
      const double rz_new = ordered_sum(partial_rz);
      res = largest(partial_res);
      beta = rz_new / rz;
      rz = rz_new;
      std::swap(po, pn);
    }
  }

  /// The previous Newton iteration's update of cell c from the temperature changes dtemp
  /// (zero outside the pure cells) and the right-hand side it was solved with.
  void apply_update(long c, int i, int j, int k) {
    if (type[c] == kAir) return;
    if (type[c] == kMushy) {
      // dT = 0 here: the cell's own balance gives its enthalpy change, which stops just past
      // the plateau's end if it would leave it (the next iteration then solves the new phase's
      // temperature with its heat capacity). Unclipped, a cell holding little material jumps
      // far into the other phase (its capacity is m V), the next iteration's stop at the kink
      // puts it back on the plateau, and Newton cycles: 72 of the first 134 steps of the hollow
      // cube used all 12 iterations.
      const double next =
          h[c] + (rhs[c] + neighbour_sum_of(c, i, j, k, [&](long nb) { return dtemp[nb]; })) * dt /
                     (m[c] * vol[c]);
      h[c] = std::clamp(next, -kKinkStep * latent, (1 + kKinkStep) * latent);
      if (std::abs(h[c]) <= kKinkSnap * latent) h[c] = 0;
      if (std::abs(h[c] - latent) <= kKinkSnap * latent) h[c] = latent;
    } else if (type[c] == kIce) {
      h[c] = std::min(h[c] + ci * dtemp[c], 0.0);  // stop at the kink: melting starts next
    } else {
      h[c] = std::max(h[c] + cw * dtemp[c], latent);
    }
  }

  /// Newton's start for cell c: a pure phase continues its last step's rate of temperature
  /// change (stopping at the kink, as an update does); a melting cell starts where it is. Only
  /// the start moves, not the solution: it saves about one Newton iteration per step (the
  /// first residual is what the rate's change leaves, not the whole step's change).
  void predict(long c) {
    if (m[c] == 0 || rate[c] == 0) return;
    if (h[c] < 0) {
      h[c] = std::min(h[c] + ci * rate[c] * dt, 0.0);
    } else if (h[c] > latent) {
      h[c] = std::max(h[c] + cw * rate[c] * dt, latent);
    }
  }

  /// Applies the previous Newton iteration's update (if any), then temperatures, cell types,
  /// the CG diagonal and the residual; returns the largest residual as a temperature [K].
  /// apply_update reads the neighbours' dtemp, which nothing writes here, and writes only its
  /// own h, which the residuals read after the barrier.
  double prepare_newton_iteration(BlockTeam& team, bool apply) {
    team.for_blocks([&](long bl) {
      for_cells(bl, [&](long c, int i, int j, int k) {
        if (apply) {
          apply_update(c, i, j, k);
        } else {
          predict(c);
        }
        t[c] = m[c] > 0 ? temperature(h[c]) : 0.0;
      });
    });
    team.for_blocks([&](long bl) {
      double res = 0;
      for_cells(bl, [&](long c, int i, int j, int k) {
        if (m[c] == 0) {
          type[c] = kAir;
          rhs[c] = 0;
          return;
        }
        type[c] = h[c] < 0 ? kIce : (h[c] > latent ? kWater : kMushy);
        const double mv = m[c] * vol[c] / dt;
        diag[c] = mv * (type[c] == kWater ? cw : ci) + conductance_sum(c, i, j, k);
        rhs[c] = -residual(c, i, j, k);
        res = std::max(res, std::abs(rhs[c]) / diag[c]);
      });
      partial_newton[static_cast<std::size_t>(bl)] = res;
      start_cg(bl);
    });
    return largest(partial_newton);
  }

  /// Semismooth Newton on the backward Euler balance, run by the team's leader; true when
  /// converged.
  bool newton(BlockTeam& team) {
    double best = std::numeric_limits<double>::infinity();
    for (int it = 0; it < kMaxNewton; ++it) {
      const double res = prepare_newton_iteration(team, it > 0);
      if (res <= kNewtonTolerance_K) return true;
      if (res <= kStagnantResidual_K && res > 0.5 * best) {
        if (team.leader()) ++stats.stagnant_steps;
        return true;
      }
      best = std::min(best, res);
      if (it + 1 == kMaxNewton) {
        if (res > kAcceptableResidual_K) return false;
        if (team.leader()) ++stats.loose_steps;
        return true;
      }
      const int cg = conjugate_gradients(team, std::max(1e-3 * res, 0.1 * kNewtonTolerance_K));
      if (team.leader()) {
        ++stats.newton_iterations;
        stats.cell_updates += n;
        stats.cg_iterations += cg;
      }
    }
    return false;
  }

  // --- the step's reductions ------------------------------------------------------------------
  /// One block's share of a step's sums and maxima, written in one phase and read by the leader
  /// after it, which adds the blocks' shares in block order: the same bits for any thread
  /// count.
  struct BlockSums {
    double energy_start = 0, heat = 0, drained = 0, most_drained = 0, removed = 0;
    double energy_end = 0, enclosed = 0, wettest = 0, ice = 0, dtemp = 0, dmelt = 0;
    double drained_m3 = 0;  ///< material volume drained
    long most_drained_cell = -1, wettest_cell = -1;
  };
  std::vector<BlockSums> block_sums;
  template <class G>
  double sum_blocks(G&& g) const {
    double total = 0;
    for (const BlockSums& b : block_sums) total += g(b);
    return total;
  }
  template <class G>
  double max_blocks(G&& g) const {
    double most = 0;
    for (const BlockSums& b : block_sums) most = std::max(most, g(b));
    return most;
  }

  /// Drains cell c if it is exposed and holds liquid; adds to the block's drained enthalpy, the
  /// most drained cell (first among equals) and the removed ice remnants.
  void drain_cell(long c, BlockSums& b) {
    if (!(p.drain && exposed[c] && m[c] > 0 && h[c] > 0)) return;
    const double e = m[c] * vol[c] * h[c];
    b.drained += e;
    if (e > b.most_drained) {
      b.most_drained = e;
      b.most_drained_cell = c;
    }
    const double f = liquid(h[c]);
    m[c] = f >= 1 ? 0.0 : m[c] * (1 - f);
    if (m[c] < kRemnantFraction) {
      b.removed += m[c] * vol[c];
      m[c] = 0;
    }
    h[c] = 0;
  }
  /// The enclosed liquid and the wettest enclosed cell (core_frozen), which depend on exposure.
  void add_enclosed(long c, BlockSums& b) const {
    b.enclosed += exposed[c] ? 0.0 : m[c] * vol[c] * liquid(h[c]);
    const double wet = exposed[c] ? 0.0 : m[c] * liquid(h[c]);
    if (wet > b.wettest) {
      b.wettest = wet;
      b.wettest_cell = c;
    }
  }

  /// One step of size dt from the current state, run by the team's leader: coefficients, Newton,
  /// the conservative final update, draining, events; false (state restored) if Newton failed and
  /// the step can still shrink.
  ///
  /// The step's bookkeeping is fused into as few phases as possible (each phase ends with a
  /// barrier, and on a shared machine each barrier can wait a time slice for a descheduled
  /// thread): start (energy, coefficients), Newton, final update (with the openness the flood
  /// fill needs), one serial part (flood fill, break-through), drain (with exposure, energies and
  /// the end events' sums), one serial part (books, melt onset, the re-flood), and only when
  /// something drained the exposure and surface-area phases; then the serial end of the step.
  bool step(BlockTeam& team) {
    if (area_stale) midpoint_surface_area(team);
    // build_coefficients reads the neighbours' h, which nothing writes in this phase
    team.for_blocks([&](long bl) {
      double e = 0;
      for_cells(bl, [&](long c, int i, int j, int k) {
        t_start[c] = m[c] > 0 ? temperature(h[c]) : 0.0;
        f_start[c] = liquid(h[c]);
        e += m[c] * vol[c] * h[c];
        hn[c] = h[c];
        build_coefficients(c, i, j, k);
      });
      block_sums[static_cast<std::size_t>(bl)].energy_start = e;
    });
    const double e_before = sum_blocks([](const BlockSums& b) { return b.energy_start; });
    const bool ok = newton(team);
    if (!ok && dt > kMinStep_s) {
      team.for_blocks([&](long bl) {
        for (long c = bl * kBlock; c < block_end(bl); ++c) h[c] = hn[c];
      });
      return false;
    }
    if (!ok && team.leader()) ++stats.unconverged_steps;
    // Conservative final update: each cell's enthalpy from its balance at the final
    // temperatures (t is current: Newton's last iteration set it from h), so that the interior
    // fluxes cancel exactly in the total. heat_rate reads the temperatures only, so each cell
    // may overwrite its own h. Then the cell's openness for the flood fill.
    team.for_blocks([&](long bl) {
      double heat = 0;
      for_cells(bl, [&](long c, int i, int j, int k) {
        if (m[c] > 0) {
          h[c] = hn[c] + dt * heat_rate(c, i, j, k) / (m[c] * vol[c]);
          heat += bq0[c] - bq1[c] * t[c];
        }
        open_now[c] = ice_fraction(c) < 0.5;
      });
      block_sums[static_cast<std::size_t>(bl)].heat = heat;
    });
    const double heat_step = dt * sum_blocks([](const BlockSums& b) { return b.heat; });
    team.serial([&] {
      time = dt == step_remaining ? step_target : time + dt;
      heat_in += heat_step;
      fill_outside();
      detect_break_through();
    });
    // exposure, draining (booked), openness for a re-flood, energies and the end events' sums
    team.for_blocks([&](long bl) {
      BlockSums& b = block_sums[static_cast<std::size_t>(bl)];
      b.drained = b.most_drained = b.removed = b.energy_end = b.drained_m3 = 0;
      b.enclosed = b.wettest = b.ice = b.dtemp = b.dmelt = 0;
      b.most_drained_cell = b.wettest_cell = -1;
      for_cells(bl, [&](long c, int i, int j, int k) {
        exposure(c, i, j, k);
        const double before = m[c];
        drain_cell(c, b);
        b.drained_m3 += (before - m[c]) * vol[c];
        remember_openness(c);
        open_now[c] = ice_fraction(c) < 0.5;
        b.energy_end += m[c] * vol[c] * h[c];
        add_enclosed(c, b);
        b.ice += ice_fraction(c) * vol[c];
        rate[c] = m[c] > 0 ? (temperature(h[c]) - t_start[c]) / dt : 0.0;
        if (m[c] > 0) {
          b.dtemp = std::max(b.dtemp, std::abs(temperature(h[c]) - t_start[c]));
          b.dmelt = std::max(b.dmelt, std::abs(liquid(h[c]) - f_start[c]));
        }
      });
    });
    const double drained_step = sum_blocks([](const BlockSums& b) { return b.drained; });
    team.serial([&] {
      const double drained_before = drained;
      drained += drained_step;
      stats.removed_ice_m3 += sum_blocks([](const BlockSums& b) { return b.removed; });
      double most = 0;
      long most_cell = -1;
      for (const BlockSums& b : block_sums)
        if (b.most_drained_cell >= 0 && b.most_drained > most) {
          most = b.most_drained;
          most_cell = b.most_drained_cell;
        }
      if (!melt_started && most_cell >= 0) {
        melt_started = true;
        events.push_back({"melt_onset", time, centre(most_cell)});
      }
      const double e_end = sum_blocks([](const BlockSums& b) { return b.energy_end; });
      const double err =
          std::abs(e_end - e_before - heat_step + (drained - drained_before)) / reference;
      stats.max_step_energy_error = std::max(stats.max_step_energy_error, err);
      stats.steps++;
      stats.min_step_s = stats.steps == 1 ? dt : std::min(stats.min_step_s, dt);
      stats.max_step_s = std::max(stats.max_step_s, dt);
      if (drained_step > 0) fill_outside();  // the drained cells opened: the next step's outside
      // the mean recession speed, drained volume over the heated area: the next step's area is
      // taken half a step ahead (update_surface_area)
      recession_m_s = 0;
      if (drained_step > 0) {
        const double area = sum_cells(n, [&](long c) { return surface_area[c]; });
        const double drained_m3 = sum_blocks([](const BlockSums& b) { return b.drained_m3; });
        recession_m_s = area > 0 ? drained_m3 / (area * dt) : 0.0;
      }
      area_stale = drained_step > 0 || area_ahead;
    });
    if (drained_step > 0) {
      // exposure as the next step sees it (its surface areas follow at its start)
      team.for_blocks([&](long bl) {
        BlockSums& b = block_sums[static_cast<std::size_t>(bl)];
        b.enclosed = b.wettest = 0;
        b.wettest_cell = -1;
        for_cells(bl, [&](long c, int i, int j, int k) {
          exposure(c, i, j, k);
          add_enclosed(c, b);
        });
      });
    }
    return true;
  }

  // --- openness, draining, events -------------------------------------------------------------
  /// Flood fill from the air at the grid's border through cells less than half ice: `open_now`
  /// (cell less than half ice), `outside_now` (connected), `exposed` = outside or next to it.
  /// The fill itself is serial (on the leader; a breadth-first search over the open cells).
  void flood(BlockTeam& team) {
    team.for_blocks([&](long bl) {
      for (long c = bl * kBlock; c < block_end(bl); ++c) open_now[c] = ice_fraction(c) < 0.5;
    });
    team.serial([&] { fill_outside(); });
    team.for_blocks([&](long bl) { for_cells(bl, [&](auto... a) { exposure(a...); }); });
  }
  /// exposed[c]: outside, or next to a cell outside.
  void exposure(long c, int i, int j, int k) {
    exposed[c] = outside_now[c];
    if (!outside_now[c])
      for_neighbours(c, i, j, k, [&](long nb) { exposed[c] |= outside_now[nb]; });
  }
  /// outside_now from open_now (serial).
  void fill_outside() {
    const long nxy = static_cast<long>(nx) * ny;
    std::fill(outside_now.begin(), outside_now.end(), 0);
    queue.clear();
    auto seed = [&](long c) {
      if (m[c] == 0 && !outside_now[c]) {
        outside_now[c] = 1;
        queue.push_back(c);
      }
    };
    // the border cells: the faces j = 0, ny - 1 and i = nx - 1, and (3D) i = 0, k = 0, nz - 1
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j) {
        const long row = j * static_cast<long>(nx) + k * nxy;
        const bool face = j == 0 || j == ny - 1 || (!axisymmetric && (k == 0 || k == nz - 1));
        if (face) {
          for (int i = 0; i < nx; ++i) seed(row + i);
        } else {
          if (!axisymmetric) seed(row);
          seed(row + nx - 1);
        }
      }
    for (std::size_t head = 0; head < queue.size(); ++head)
      for_neighbours(queue[head], [&](long nb) {
        if (open_now[nb] && !outside_now[nb]) {
          outside_now[nb] = 1;
          queue.push_back(nb);
        }
      });
  }
  /// f(nb) for the face neighbours of cell c (at i, j, k) in a fixed order.
  template <class F>
  void for_neighbours(long c, int i, int j, int k, F&& f) const {
    const long nxy = static_cast<long>(nx) * ny;
    if (i > 0) f(c - 1);
    if (i + 1 < nx) f(c + 1);
    if (j > 0) f(c - nx);
    if (j + 1 < ny) f(c + nx);
    if (k > 0) f(c - nxy);
    if (k + 1 < nz) f(c + nxy);
  }
  template <class F>
  void for_neighbours(long c, F&& f) const {
    const long nxy = static_cast<long>(nx) * ny;
    for_neighbours(c, static_cast<int>(c % nx), static_cast<int>((c / nx) % ny),
                   static_cast<int>(c / nxy), f);
  }
  void remember_openness(long c) {
    enclosed_prev[c] = open_now[c] && !outside_now[c];
    open_prev[c] = open_now[c];
  }
  void classify_openness(BlockTeam& team) {
    flood(team);
    team.for_blocks([&](long bl) {
      for (long c = bl * kBlock; c < block_end(bl); ++c) remember_openness(c);
    });
  }

  /// A former cavity cell now outside: the break-through event, at the first wall cell that
  /// opened this step next to the former cavity (serial, until the first break-through).
  void detect_break_through() {
    if (broke_through) return;
    long first = -1, fallback = -1;
    for (long c = 0; c < n && fallback < 0; ++c)
      if (outside_now[c] && enclosed_prev[c]) fallback = c;
    if (fallback < 0) return;
    for (long c = 0; c < n && first < 0; ++c) {
      if (!outside_now[c] || open_prev[c]) continue;
      bool next_to_cavity = false;
      for_neighbours(c, [&](long nb) { next_to_cavity |= enclosed_prev[nb] != 0; });
      if (next_to_cavity) first = c;
    }
    broke_through = true;
    events.push_back({"break_through", time, centre(first >= 0 ? first : fallback)});
  }

  /// Material | air area per cell, |grad m| V (mirrored at the grid's walls and the axis), with
  /// the share computed in air cells handed to their material neighbours by fraction.
  ///
  /// |grad m| is the mean of two estimates that err in opposite directions on curved surfaces:
  /// Youngs' smoothed gradient (central differences averaged across with weights 1, 2, 1: the
  /// averaging over differently oriented normals shortens the vector) and the plain central
  /// difference (which over-counts the staircase of a tilted surface). On a 3 cm sphere at t = 0
  /// the sums are -1.9 % and +2.0 % of 4 pi R^2 on 1.25 mm cells (3D) and -1.3 % and +1.5 % on
  /// 0.5 mm cells (axisymmetric); their mean is within 0.07 % in both. Both are exact on a face
  /// parallel to the grid. The heated area sets the melt rate directly: Youngs' alone made the 3D
  /// sphere melt about 1 % too slowly against the 1D solver (docs/simulate.md).
  ///
  /// The step's areas (on the leader, before the step): the cells' areas from the fractions,
  /// scaled to the total area half a step ahead (update_surface_area).
  void midpoint_surface_area(BlockTeam& team) {
    const double lead = 0.5 * dt * recession_m_s;
    area_ahead = lead > 0;
    double ratio = 1;
    if (area_ahead) {
      update_surface_area(team, lead);
      ratio = sum_cells(n, [&](long c) { return surface_area[c]; });
    }
    update_surface_area(team);
    if (!area_ahead) return;
    const double now = sum_cells(n, [&](long c) { return surface_area[c]; });
    ratio = now > 0 ? ratio / now : 1.0;
    team.for_blocks([&](long bl) {
      for (long c = bl * kBlock; c < block_end(bl); ++c) surface_area[c] *= ratio;
    });
  }
  /// lead_m > 0: the areas of the fractions with the surface moved lead_m along its normal,
  /// m - lead_m |grad m|. A step holds its areas while the surface recedes, so step() takes
  /// the cells' areas from the fractions as they are, scaled by the ratio of the total area
  /// half a step ahead (lead: the last step's mean recession speed) to the total now. From the
  /// step's start alone, a shrinking body was heated at its past, larger area: an ablating
  /// sphere of radius a ran fast by q dt / (L_v a) relative, first order in the step (0.4-0.7 %
  /// over 600 s with 10 s steps at any cell size; measured 0.078 %/s of step against 0.083
  /// predicted; docs/validation.md, "Ablation excess"). Tried and rejected: each cell's own
  /// melt as its lead (it fed a roughening of the surface at fine cells, +1.5 % at 0.125 mm),
  /// and the moved fractions' areas as they are (the offset spreads the gradient one cell
  /// deeper, into colder cells, where a convective surface drew more heat: the default hollow
  /// sphere broke through 27 s earlier). One ratio for the whole grid: bodies receding at
  /// different relative rates keep a first-order remainder in their difference.
  ///
  /// Three or four phases of the team (each writes only its own cells): the moved fractions
  /// (lead_m > 0 only); the gradient areas; the material cells' shares (with the air neighbours'
  /// areas and the remnant rule below); the areas of the exposed cells (with the shares of their
  /// unexposed neighbours).
  void update_surface_area(BlockTeam& team, double lead_m = 0) {
    m_geo = m.data();  // the fractions as they are: no copy
    if (lead_m > 0) {
      team.for_blocks([&](long bl) {
        for_cells(bl, [&](long c, int i, int j, int k) {
          m_moved[c] = std::max(0.0, m[c] - lead_m * central_gradient(i, j, k));
        });
      });
      m_geo = m_moved.data();
    }
    team.for_blocks([&](long bl) { for_cells(bl, [&](auto... a) { area_gradient(a...); }); });
    team.for_blocks([&](long bl) { for_cells(bl, [&](auto... a) { area_share_of(a...); }); });
    team.for_blocks([&](long bl) { for_cells(bl, [&](auto... a) { area_final(a...); }); });
  }
  /// How much of a handed-on share cell c takes relative to its neighbours: its volume on the
  /// axisymmetric grid (rings grow with the radius), 1 on the uniform 3D grid. By count alone,
  /// a ring next to the axis took as much of a neighbour's area, and so of the surface heat, as
  /// a ring three to five times its size: per volume it melted faster, and a sphere ablating
  /// under a uniform flux grew a dimple at its poles (0.5 mm deep, 4 cells, after 600 s at
  /// 0.125 mm cells), its total area estimate drifting 2.7 % high (docs/validation.md).
  double share_weight(long c) const { return axisymmetric ? vol[c] : 1.0; }
  /// Phase 1: the gradient area of every cell, and for air cells the material around them.
  void area_gradient(long c, int i, int j, int k) {
    area_g[c] = gradient_area(c, i, j, k);
    double sum = 0;
    if (m[c] == 0) for_neighbours(c, i, j, k, [&](long nb) { sum += m[nb] * share_weight(nb); });
    area_w[c] = sum;
  }
  /// Phase 2: a material cell's own share (reads area_g of air cells only, writes it for
  /// material cells only), and what it hands to its exposed neighbours.
  void area_share_of(long c, int i, int j, int k) {
    area_share[c] = 0;
    if (m[c] == 0) {
      surface_area[c] = 0;
      return;
    }
    double a = area_g[c];
    for_neighbours(c, i, j, k, [&](long nb) {
      if (m[nb] == 0 && area_w[nb] > 0) a += area_g[nb] * (m[c] * share_weight(c)) / area_w[nb];
    });
    area_g[c] = remnant_area(c, i, j, k, a);  // now the material cell's own share
    // Only cells open to the outside air take surface heat (their melt drains): a share that
    // the smoothed gradient put one cell deeper goes to its exposed neighbours, evenly (per
    // unit of share_weight: the receiver scales it by its own).
    if (exposed[c] || area_g[c] == 0) return;
    double weights = 0;
    for_neighbours(c, i, j, k, [&](long nb) {
      if (m[nb] > 0 && exposed[nb]) weights += share_weight(nb);
    });
    if (weights > 0) area_share[c] = area_g[c] / weights;
  }
  /// Phase 3: the exposed cells' areas with the shares handed to them.
  void area_final(long c, int i, int j, int k) {
    if (m[c] == 0) return;
    if (!exposed[c]) {
      surface_area[c] = area_share[c] > 0 ? 0.0 : area_g[c];  // no exposed neighbour: keep it
      return;
    }
    double a = area_g[c];
    for_neighbours(c, i, j, k, [&](long nb) {
      if (!exposed[nb]) a += area_share[nb] * share_weight(c);
    });
    surface_area[c] = a;
  }

  /// |grad m| V of cell c (at i, j, k): the mean of Youngs' and the central-difference gradient
  /// (above); the fractions beyond the grid's walls mirror the cells inside.
  double gradient_area(long c, int i, int j, int k) const {
    const bool three = nz > 1;
    const long sy = nx, sz = static_cast<long>(nx) * ny;
    if (i > 0 && i + 1 < nx && j > 0 && j + 1 < ny && (!three || (k > 0 && k + 1 < nz))) {
      auto at = [&](int a, int b, int d) { return m_geo[c + a + sy * b + sz * d]; };
      // Inside the bulk (or the air) every difference is exactly 0, so is the area: the same
      // bits as the formula, at a third of its loads.
      const int kw = three ? 1 : 0;
      bool uniform = true;
      for (int d = -kw; d <= kw && uniform; ++d)
        for (int b = -1; b <= 1 && uniform; ++b)
          for (int a = -1; a <= 1 && uniform; ++a) uniform = at(a, b, d) == m_geo[c];
      return uniform ? 0.0 : gradient_area_at(c, at);
    }
    return gradient_area_at(c, [&](int a, int b, int d) {
      const int ii = std::clamp(i + a, 0, nx - 1), jj = std::clamp(j + b, 0, ny - 1),
                kk = std::clamp(k + d, 0, nz - 1);
      return m_geo[ii + sy * jj + sz * kk];
    });
  }
  /// |grad m| of the fractions themselves, central differences (walls mirrored) [1/m].
  double central_gradient(int i, int j, int k) const {
    const long sy = nx, sz = static_cast<long>(nx) * ny;
    auto at = [&](int a, int b, int d) {
      const int ii = std::clamp(i + a, 0, nx - 1), jj = std::clamp(j + b, 0, ny - 1),
                kk = std::clamp(k + d, 0, nz - 1);
      return m[ii + sy * jj + sz * kk];
    };
    const double cx = at(1, 0, 0) - at(-1, 0, 0), cy = at(0, 1, 0) - at(0, -1, 0),
                 cz = nz > 1 ? at(0, 0, 1) - at(0, 0, -1) : 0.0;
    return std::sqrt(cx * cx + cy * cy + cz * cz) / (2 * s);
  }
  /// The same with at(di, dj, dk) the material fraction of the cell at that offset.
  template <class At>
  double gradient_area_at(long c, At&& at) const {
    const bool three = nz > 1;
    const int kw = three ? 1 : 0;
    // Youngs' gradient ...
    double gx = 0, gy = 0, gz = 0;
    for (int a = -1; a <= 1; ++a)
      for (int b = -kw; b <= kw; ++b) {
        const double w = (2 - std::abs(a)) * (three ? 2 - std::abs(b) : 2);
        gx += w * (at(1, a, b) - at(-1, a, b));
        gy += w * (at(a, 1, b) - at(a, -1, b));
        if (three) gz += w * (at(a, b, 1) - at(a, b, -1));
      }
    const double norm = three ? 16 * 2 * s : 8 * 2 * s;
    const double youngs = std::sqrt(gx * gx + gy * gy + gz * gz) / norm;
    // ... and the plain central differences
    const double cx = at(1, 0, 0) - at(-1, 0, 0), cy = at(0, 1, 0) - at(0, -1, 0),
                 cz = three ? at(0, 0, 1) - at(0, 0, -1) : 0.0;
    const double central = std::sqrt(cx * cx + cy * cy + cz * cz) / (2 * s);
    return 0.5 * (youngs + central) * vol[c];
  }

  /// Remnants thinner than a cell (rods and plates left of a shell's edges, fragments): their
  /// cells are less than half full with no bulk behind them, and |grad m| V, which sees a
  /// smeared surface, gives them a fraction of their true area (a rod of cross-section 0.3 dx^2
  /// has 1.9 dx^2 of surface per cell length, the gradient ~0.6 dx^2), so they lingered for
  /// minutes as sub-cell dust. Such a cell gets at least the area of the most compact body of
  /// its volume: a sphere in 3D, (36 pi)^(1/3) m^(2/3) dx^2, a torus of round cross-section in
  /// (r, y), 2 sqrt(pi m) V / dx; at most 2 V / dx (a plate's two faces).
  double remnant_area(long c, int i, int j, int k, double a) const {
    if (m[c] >= 0.5 || backed_by_bulk(c, i, j, k)) return a;
    const double compact = nz > 1 ? std::cbrt(36 * std::numbers::pi) * std::pow(m[c], 2.0 / 3)
                                  : 2 * std::sqrt(std::numbers::pi * m[c]);
    return std::max(a, std::min(compact, 2.0) * vol[c] / s);
  }

  /// A cell at least half full within two cells along any axis: cell c is part of a resolved
  /// body's (smeared) surface rather than a sub-cell remnant.
  bool backed_by_bulk(long c, int i, int j, int k) const {
    const long nxy = static_cast<long>(nx) * ny;
    for (int d = 1; d <= 2; ++d) {
      if ((i - d >= 0 && m[c - d] >= 0.5) || (i + d < nx && m[c + d] >= 0.5)) return true;
      if ((j - d >= 0 && m[c - d * nx] >= 0.5) || (j + d < ny && m[c + d * nx] >= 0.5)) return true;
      if ((k - d >= 0 && m[c - d * nxy] >= 0.5) || (k + d < nz && m[c + d * nxy] >= 0.5))
        return true;
    }
    return false;
  }

  double ice_volume() const {
    return sum_cells(n, [&](long c) { return ice_fraction(c) * vol[c]; });
  }

  /// The serial end of an accepted step: core_frozen (at the last enclosed liquid's cell),
  /// fully_melted, and the next step size.
  void end_of_step(double step_dt, double saved) {
    const double enclosed = sum_blocks([](const BlockSums& b) { return b.enclosed; });
    const double ice = sum_blocks([](const BlockSums& b) { return b.ice; });
    if (had_enclosed_liquid && !broke_through && !core_frozen && enclosed == 0) {
      core_frozen = true;
      events.push_back({"core_frozen", time, centre(last_liquid_cell)});
    }
    if (enclosed > 0) {  // the lowest-index cell with the most enclosed liquid
      double most = -1;
      for (const BlockSums& b : block_sums)
        if (b.wettest_cell >= 0 && b.wettest > most) {
          most = b.wettest;
          last_liquid_cell = b.wettest_cell;
        }
    }
    if (ice <= kGoneFraction * initial_material) {
      done = true;
      long last = n - 1;
      while (last > 0 && m[last] == 0) --last;
      events.push_back({"fully_melted", time, centre(last)});
    }
    if (p.fixed_step_s > 0) {
      dt_next = p.fixed_step_s;
      return;
    }
    const double dtemp_max = max_blocks([](const BlockSums& b) { return b.dtemp; });
    const double dmelt_max = max_blocks([](const BlockSums& b) { return b.dmelt; });
    double factor = 2.0;
    if (dtemp_max > 0) factor = std::min(factor, 0.9 * p.step_temperature_change_k / dtemp_max);
    if (dmelt_max > 0) factor = std::min(factor, 0.9 * p.step_melt_fraction / dmelt_max);
    factor = std::max(0.3, factor);
    // a step shortened to land on the target keeps the previous size unless it must shrink
    dt_next = step_dt < saved ? std::min(saved, step_dt * factor)
                              : std::min(p.max_step_s, step_dt * factor);
    if (step_dt < saved && factor >= 1) dt_next = saved;
  }
  long last_liquid_cell = 0;

  /// The steps to t_target in one OpenMP parallel region: the leader runs them, the other
  /// threads help with each phase's blocks and sleep while the leader does the serial
  /// bookkeeping (events, the flood fill), instead of spinning in OpenMP's barriers.
  double advance_to(double target) {
    TeamShared shared;
#pragma omp parallel if (n > kParallelCells)
    {
      BlockTeam team(shared, omp_get_thread_num(), block_count());
      if (team.leader()) {
        advance_team(team, target);
        team.finish();
      } else {
        team.serve();
      }
    }
    return time;
  }

  /// Run by the team's leader; the helpers only run the blocks of the phases it posts (posting
  /// a phase publishes everything the leader wrote before).
  void advance_team(BlockTeam& team, double target) {
    while (!done && time < target) {
      const double remaining = target - time;
      double step_dt = std::min(dt_next, remaining);
      // avoid a sliver step before the target
      if (remaining - step_dt < 1e-3 * step_dt) step_dt = remaining;
      const double saved = dt_next;
      if (team.leader()) {
        dt = step_dt;
        step_remaining = remaining;
        step_target = target;
      }
      if (!step(team)) {
        team.serial([&] {
          ++stats.rejected_steps;
          dt_next = std::max(0.5 * step_dt, 0.99 * kMinStep_s);
        });
        continue;
      }
      team.serial([&] { end_of_step(step_dt, saved); });
    }
  }
  double step_remaining = 0, step_target = 0;  ///< for landing exactly on the target time

  GridSnapshot snapshot() const {
    GridSnapshot out;
    out.time_s = time;
    out.liquid_volume_m3 = sum_cells(n, [&](long c) { return m[c] * liquid(h[c]) * vol[c]; });
    out.ice_volume_m3 = ice_volume();
    out.enclosed_liquid_volume_m3 = enclosed_liquid_volume();
    out.enthalpy_j = energy();
    out.heat_in_j = heat_in;
    out.drained_j = drained;
    out.energy_balance_error = std::abs(out.enthalpy_j - e0 - heat_in + drained) / reference;
    return out;
  }

  GridField field() const {
    GridField f;
    f.geometry = p.geometry;
    f.cells = p.cells;
    f.origin_m = p.origin_m;
    f.spacing_m = s;
    f.time_s = time;
    f.temperature_c.resize(static_cast<std::size_t>(n));
    f.ice_fraction.resize(static_cast<std::size_t>(n));
    f.water_fraction.resize(static_cast<std::size_t>(n));
    for (long c = 0; c < n; ++c) {
      // air cells show the temperature of the surrounding air / held surface
      f.temperature_c[c] =
          static_cast<float>(m[c] > 0 ? temperature(h[c]) : p.surface_temperature_c);
      const double liq = liquid(h[c]);
      f.water_fraction[c] = static_cast<float>(m[c] * liq);
      f.ice_fraction[c] = static_cast<float>(std::min(m[c] * (1 - liq), 1.0 - f.water_fraction[c]));
    }
    return f;
  }
};

EnthalpySolver::EnthalpySolver(GridProblem problem)
    : m_impl(std::make_unique<Impl>(std::move(problem))) {}
EnthalpySolver::~EnthalpySolver() = default;
double EnthalpySolver::advance_to(double t_target) {
  return m_impl->advance_to(t_target);
}
double EnthalpySolver::time() const {
  return m_impl->time;
}
bool EnthalpySolver::finished() const {
  return m_impl->done;
}
GridSnapshot EnthalpySolver::snapshot() const {
  return m_impl->snapshot();
}
GridField EnthalpySolver::field() const {
  return m_impl->field();
}
const std::vector<GridEvent>& EnthalpySolver::events() const {
  return m_impl->events;
}
const GridStatistics& EnthalpySolver::statistics() const {
  return m_impl->stats;
}
double EnthalpySolver::reference_energy() const {
  return m_impl->reference;
}
std::vector<double> EnthalpySolver::liquid_fraction() const {
  std::vector<double> out(static_cast<std::size_t>(m_impl->n));
  for (long c = 0; c < m_impl->n; ++c) out[c] = m_impl->m[c] * m_impl->liquid(m_impl->h[c]);
  return out;
}
const std::vector<double>& EnthalpySolver::material_fraction() const {
  return m_impl->m;
}
const std::vector<double>& EnthalpySolver::enthalpy() const {
  return m_impl->h;
}
double EnthalpySolver::cell_volume(int i, int j, int k) const {
  return m_impl->vol[i + static_cast<long>(m_impl->nx) * (j + static_cast<long>(m_impl->ny) * k)];
}

}  // namespace thaw::sim
