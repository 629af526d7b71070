#pragma once
/// \file
/// \brief Area (2-D) and volume (3-D) of a sampled region.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mcws/core/cancel_check.h"

namespace mcws {

/// \brief A triangle surface: vertices [length unit] and triangles as vertex indices, each
/// counter-clockwise seen from outside (its normal, (b - a) x (c - a), points out).
struct TriangleSurface {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// \brief Result of delaunayMeasure().
struct RegionMeasure {
  double measure{0.0};               ///< corrected area [unit^2] or volume [unit^3]
  double uncorrected{0.0};           ///< the kept simplices' total, before the edge correction
  std::size_t points{0};             ///< distinct points
  std::size_t triangulated{0};       ///< of those, the points triangulated (MeasureOptions::shell)
  std::size_t boundary_vertices{0};  ///< vertices between kept and dropped simplices
  std::size_t outside{0};            ///< boundary vertices outside the region of the other points
  double alpha_factor{0.0};
  /// With MeasureOptions::surface (3-D): the facets between kept and dropped tetrahedra, each
  /// oriented away from its kept one, so a closed surface that encloses `uncorrected`. Vertices
  /// in the order of the distinct input positions, triangles sorted: the same for any thread
  /// count.
  TriangleSurface surface;
  /// Whether repairing the cavities and the pinches of the kept region (within a few rounds) made
  /// `surface` a closed 2-manifold.
  bool surface_is_manifold{false};
};

/// \brief Area or volume of the region a cloud samples, from its Delaunay triangulation (CGAL).
///
/// A triangle (2-D) or tetrahedron (3-D) belongs to the region when its circumradius is at most
/// `alpha_factor` times the local spacing at its sparsest vertex; the local spacing at a point is
/// its distance to the k-th nearest neighbour (k = 8) scaled to the mean spacing of a uniform
/// cloud. Kept simplices sum to A_N, which misses a thin band along the edge. Efron's identity
/// for uniform samples (Efron 1965; Ripley and Rasson 1977, "Finding the edge of a Poisson
/// forest") says the missing share equals the chance that one more sample falls outside. Leave
/// one out estimates it: V, the number of points that lie outside the region built from all the
/// others (for each boundary vertex, from the Delaunay triangulation of its neighbours, which is
/// what fills its star when it is removed; see LeaveOneOut), over N. The result is A_N / (1 - V /
/// N); for a convex hull V is exactly its vertex count. The correction assumes the density is
/// uniform near the edge, as for the validation shapes; a cloud much sparser along its edge than
/// inside (a projected ball, joint-space samples near the workspace's tips) comes out low, and
/// refining the boundary is the remedy. By default only the points an empty ball of alpha radius
/// may touch are triangulated, with the same result (MeasureOptions::shell).
/// \param points the region's points; for a planar region x and y hold the plane's coordinates
///   and z is ignored (dimensions = 2).
/// \param dimensions 2 (area) or 3 (volume).
/// \param alpha_factor the circumradius limit in local spacings (> 0; 3 keeps every interior
///   simplex of a uniform cloud of up to 10^8 points and bridges no gap wider than 6 spacings).
/// \throws mcws::Error for fewer than dimensions + 1 points, all points on a line (2-D) or a
///   plane (3-D), no simplex within the alpha limit, more than half the points outside the region
///   of the others (too few points to correct for the edge), or a bad alpha factor.
RegionMeasure delaunayMeasure(const pcl::PointCloud<pcl::PointXYZ>& points, int dimensions,
                              double alpha_factor = 3.0);

/// \brief How the edge correction finds the boundary vertices outside the region of the others.
enum class LeaveOneOut {
  /// From each vertex's star: the Delaunay triangulation of its neighbours, which is what fills
  /// the hole when the vertex is removed; read-only on the big triangulation, on all threads.
  kStar,
  /// Remove each vertex from the triangulation, locate its point, put it back (one thread).
  kRemoveAndReinsert,
};

/// \brief Options of delaunayMeasure().
struct MeasureOptions {
  double alpha_factor{3.0};
  /// False: no leave-one-out step; measure = uncorrected (for refined clouds, whose samples lie on
  /// the edge itself: see mcws_refine).
  bool edge_correction{true};
  /// How the leave-one-out count is computed; both give the same count for points in general
  /// position (ties between cospherical simplices may be broken differently).
  LeaveOneOut leave_one_out{LeaveOneOut::kStar};
  /// Worker threads (OpenMP for the neighbour search and the edge correction, TBB for CGAL's
  /// parallel 3-D triangulation, which also stops at the core count); 0: OpenMP's default (all
  /// cores unless OMP_NUM_THREADS). The result does not depend on it. TBB's limit is process-wide
  /// while the call runs (concurrent calls share the smallest). With more than one, the shell's
  /// (MeasureOptions::shell) search tree of its left-out points is built on a thread of its own
  /// while the shell is triangulated.
  int threads{0};
  /// Triangulate only the points that an empty ball of alpha radius may touch (exposedPoints():
  /// a shell a few spacings deep along the region's edges, about 14 % of a 10^6-point ball, 3 % of
  /// a disk) instead of every point. A simplex the alpha test drops has only such vertices, so it
  /// is a simplex of the shell's triangulation too; the shell's other simplices, those that fill
  /// in for the left-out points, are all kept. Same kept total (to the rounding of the per-simplex
  /// sum, about 1e-12 of it), boundary vertices and leave-one-out count as triangulating every
  /// point, in a fraction of the time and memory. With `surface`, the stars of the surface's
  /// vertices are completed as the repairs go (the points in their simplices' circumspheres
  /// inserted), so every cell the surface and its repairs look at is the whole triangulation's:
  /// the same surface. Not with LeaveOneOut::kRemoveAndReinsert, which triangulates every point.
  bool shell{true};
  /// 3-D: also return the boundary surface of the kept tetrahedra (RegionMeasure::surface).
  bool surface{false};
  /// Called as each phase starts ("local spacing", "triangulation", "alpha test", "edge
  /// correction").
  std::function<void(const std::string&)> phase;
  /// Called on the calling thread as each phase starts (after `phase`) and every few
  /// milliseconds of work within the phases (CancelCheck): the local spacing's neighbour searches,
  /// the exposed points' passes, the insertion (beyond 65536 points then done in pieces sorted
  /// along a Hilbert curve: the same triangulation), the alpha test (and the shell's completion,
  /// round by round), the edge correction's stars and the surface repair. What it throws ends the
  /// call. It changes no number of the result.
  CancelCheck cancel_check;
};

/// \brief delaunayMeasure() with options.
RegionMeasure delaunayMeasure(const pcl::PointCloud<pcl::PointXYZ>& points, int dimensions,
                              const MeasureOptions& options);

/// \brief Result of delaunayMeasureSubset(): the whole cloud's region and a subset's, measured
/// the same way.
struct SubsetMeasure {
  /// The whole cloud's: as delaunayMeasure() with every point triangulated, its `measure` written
  /// as `uncorrected + outside * unit_share` (the same value, to rounding).
  RegionMeasure all;
  double measure{0.0};      ///< the subset's area [unit^2] or volume [unit^3]; <= all.measure
  double uncorrected{0.0};  ///< the subset's part of the whole cloud's kept simplices
  std::size_t points{0};    ///< distinct positions holding a subset point
  /// The whole cloud's outside points counted for the subset, each weighted by the subset's
  /// share of the kept simplices around it (0..1): at most all.outside.
  double outside{0.0};
  /// The share of the region one point stands for in the edge correction: all.measure /
  /// all.points [unit^2 or unit^3].
  double unit_share{0.0};
};

/// \brief Area or volume of the region a subset of a cloud samples (the collision-free points of
/// a cloud sampled with collision checking), measured within the whole cloud's triangulation so
/// that it can never exceed the whole cloud's measure.
///
/// Measured on its own, a subset's region can come out larger than the whole cloud's (by 0.1 %
/// for an arm whose collisions thin its interior): the subset is sparser, so its local spacing and
/// with it the alpha limit are wider (bridging more of the concave parts), and its edge
/// correction, V / N from its own sparser edge, is larger; the two estimates carry independent
/// errors of that size. Here both come from one triangulation, the whole cloud's, with its local
/// spacing and alpha limit. A kept simplex counts for the subset whole when all its vertices are
/// subset points or its centroid lies in the subset's region, else the share of its vertices that
/// are subset points (it straddles the subset's edge). The subset's region, for that test: the
/// Delaunay simplices of the subset's points and the whole cloud's boundary vertices next to one
/// (in a kept simplex with a subset point) that pass the alpha test at those points' own local
/// spacing (with the boundary vertices, a subset thinner
/// than the whole, as where colliding samples are mixed among free ones, reaches the whole's edge
/// rather than stopping a spacing of its own short of it). The edge correction counts each of the
/// whole cloud's outside points (its leave-one-out count V) weighted by the subset's share of the
/// kept simplices around it, each standing for all.measure / all.points. Every term is at most the
/// whole cloud's, so measure <= all.measure by construction. Where the subset's edge runs inside
/// the whole cloud (a region reached only in collision), the band along it is counted by the
/// straddling simplices' shares only.
/// \param in_subset one flag per point of `points`; a position with copies is in the subset when
///   any copy is.
/// \param options as delaunayMeasure()'s; `shell`, `surface` and `leave_one_out` are ignored
///   (every point is triangulated, leave-one-out from the star).
/// \throws mcws::Error as delaunayMeasure() for the whole cloud, for a flag count that is not the
///   point count, and for a subset of fewer than 9 distinct positions or all in a plane (a line).
SubsetMeasure delaunayMeasureSubset(const pcl::PointCloud<pcl::PointXYZ>& points,
                                    const std::vector<char>& in_subset, int dimensions,
                                    const MeasureOptions& options);

/// \brief Result of columnArea().
struct ColumnArea {
  double area{0.0};            ///< [unit^2]
  double width{0.0};           ///< column width L used [unit]
  double gap{0.0};             ///< crossing gap used [unit]
  std::size_t columns{0};      ///< columns holding boundary points
  std::size_t odd_columns{0};  ///< columns whose crossings had to be completed (see below)
};

/// \brief The rectangle method of Yin, Wang & Yu 2010 (section 5, eqs. (2) to (4)): the plane is
/// cut into columns of width L along x; in column i the boundary crossings y_i1 < y_i2 < ... pair
/// up and S = L sum_i sum_j (y_i,2j - y_i,2j-1).
///
/// Taken literally, every boundary point is a "crossing" and pairing neighbours measures the
/// thickness of the boundary band, not the region. Here the boundary points of a column are first
/// grouped into crossings: sorted by y, a new crossing starts where consecutive points are more
/// than `gap` apart; a crossing's y is its points' mean. A column with an odd number of crossings
/// (where the boundary runs steeply, top and bottom merge) splits its tallest crossing into its
/// lowest and highest point.
/// \param boundary boundary points, x and y being the plane's coordinates.
/// \param width L [unit]; 0: the x extent over sqrt(number of boundary points). Narrow columns
///   (a few times the boundary points' spacing) miss sides; this keeps several points per crossing.
/// \param gap [unit]; 0: three times L.
/// \throws mcws::Error for fewer than 3 points or a negative width or gap.
ColumnArea columnArea(const pcl::PointCloud<pcl::PointXYZ>& boundary, double width = 0.0,
                      double gap = 0.0);

}  // namespace mcws
