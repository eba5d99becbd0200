// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointCloud.h
 * @brief The Laplacian of a point cloud: local Delaunay triangles of each point's neighbours,
 *        assembled on their tufted cover (N. Sharp and K. Crane, 2020).
 *
 * A cloud sampled from a surface has no triangles, but each point and its k nearest neighbours
 * see a piece of the surface that is nearly flat. For each point:
 * 1. its k nearest neighbours (NearestNeighbors.h), without those farther from it than
 *    NeighborReach times their own k-th neighbour distance: a far outlier is nobody's neighbour,
 *    and a far cluster is a component of its own;
 * 2. the plane of the neighbourhood (principal component analysis: the normal is the direction
 *    of least variance of the point and its neighbours), onto which the neighbours are
 *    projected, relative to the point;
 * 3. the triangles of the point's 1-ring in the 2-D Delaunay triangulation of the projected
 *    neighbourhood (LocalDelaunayRing). Only these triangles are kept, so the whole Delaunay
 *    triangulation is not needed: the 1-ring of the point is the dual of its Voronoi cell, which
 *    is the intersection of the half-planes nearer to it than to each neighbour. Clipping a
 *    polygon by these half-planes has no special cases: duplicates and collinear or cocircular
 *    neighbours only change which (equally Delaunay) triangles come out, never the validity.
 *    Triangles whose circumradius exceeds MaxCircumradiusFactor times the neighbourhood radius
 *    are left out: they are slivers along the convex hull of a finite neighbourhood, not
 *    triangles of the surface (at a boundary of the surface, or at the edge of a neighbourhood).
 *
 * The union of these triangles, with their edge lengths in 3-D, is a non-manifold triangle soup
 * in which most triangles appear three times, once from each corner's neighbourhood. Its
 * intrinsic Delaunay Laplacian (IntrinsicDelaunay.h: tufted cover, mollification, flips) with
 * every contribution divided by 3 is the cloud's Laplacian. The division makes the lumped mass
 * sum to the area of the sampled surface (the area of the soup counted once per triangle,
 * whatever its copies): the harmonics are D-orthonormal as on a mesh of that surface, and the
 * eigenvalues approximate those of the surface. Triangles that fewer than three neighbourhoods
 * agree on weigh 1/3 or 2/3 (Sharp and Crane's construction). Measured in the tests: on 10,000
 * random points of the unit sphere the mass sums to 4 pi within 0.2% and the eigenvalues of
 * l <= 4 are within 0.7% of l(l+1); on 10,000 random points of the unit square the mass sums
 * to 0.985 (the outline of random samples lies inside the square) and the first ten Neumann
 * eigenvalues are within 1.2%.
 *
 * Reference: N. Sharp and K. Crane, "A Laplacian for Nonmanifold Triangle Meshes", Computer
 * Graphics Forum 39(5), 2020, section 5 (point clouds).
 *
 * Used by bench/ManifoldHarmonicsBench.cxx (--cloud); tested by Testing/Core/TestPointCloud.cxx.
 */
#ifndef spectral_PointCloud_h
#define spectral_PointCloud_h

#include "Common/Defaults.h"
#include "Common/Mesh.h"
#include "Common/Monitor.h"
#include "Operators/Laplacian.h"

#include <array>
#include <vector>

namespace spectral
{
/// Points closer than this fraction of the bounding-box diagonal to an earlier point are
/// duplicates of it: left out, with a warning.
constexpr double PointCloudDuplicateTolerance = 1e-12;

/// A neighbour j of point i is used only if |p_i - p_j| <= NeighborReach r_j, where r_j is the
/// distance from j to its own k-th nearest neighbour: points much farther than the spacing of
/// the cloud around them are not part of its surface there.
constexpr double NeighborReach = 3.0;

/// Local triangles whose circumradius exceeds this factor times the largest projected
/// neighbour distance are left out (hull slivers; see the file documentation).
constexpr double MaxCircumradiusFactor = 2.0;

/// How the Laplacian of a point cloud is built.
struct PointCloudOptions
{
  /// k, the neighbours of each point (besides itself) that are triangulated; >= 2, clamped with
  /// a warning to the number of other distinct points.
  int NumberOfNeighbors = DefaultNumberOfNeighbors;
  /**
   * Lumped: the diagonal mass, a third of each intrinsic triangle's area to each corner (after
   * the division by 3 of the triple counting). Consistent: the Galerkin mass of the same
   * intrinsic triangles, divided by 3 too; its row sums are the lumped mass.
   */
  MassKind Mass = MassKind::Lumped;
};

/**
 * The Laplacian of a point cloud (see the file documentation), in the same structure as the
 * operators of a mesh (AssembleLaplacian), so that the eigensolvers take it unchanged.
 *
 * The operators have a row for each distinct point that lies in a local triangle, in the order
 * of the input (InputPointIds). The other points get no row (zero harmonics and mass), each
 * kind with a sentence in Warnings: duplicates, and points in no triangle (alone far from the
 * rest, or with neighbours on a line). Clusters far apart are separate components (Components).
 *
 * Points on a plane give a flat patch with natural (Neumann) boundary conditions on its
 * boundary, the convex-ish outline of the samples.
 *
 * \param points #V by 3 coordinates.
 * \param options k and the mass.
 * \param monitor Stage receives "Neighbors", "Local triangulations", "Intrinsic Delaunay" (the
 *        tufted cover and its flips) and "Operators" (stiffness and mass) as each step begins;
 *        Progress goes from 0 to 1 over the four; Cancelled is polled in the first three.
 *        Callbacks are called from the calling thread only (the steps run on the threads of
 *        ResolveThreads(0), Common/Threads.h). No warning is passed to it: they are in the
 *        result's Warnings, as with AssembleLaplacian.
 * \return Stiffness Q (symmetric, Q 1 = 0, off-diagonal entries <= 0 up to the flip tolerance),
 *         Mass, LumpedMass (sum: the area of the sampled surface), InputPointIds, Components,
 *         Diameter (of the points with rows) and Warnings.
 * \throws InvalidInput for fewer than 3 points or 3 distinct points, NumberOfNeighbors < 2, a
 *         non-finite coordinate or one of magnitude above MaxCoordinate (Operators.h), or a
 *         cloud in which no point has neighbours spanning a plane (all on a line).
 * \throws Cancelled if the monitor says so.
 */
DiscreteLaplacian PointCloudLaplacian(const Points& points,
  const PointCloudOptions& options,
  const Monitor& monitor = Monitor());

/**
 * The 1-ring of the origin in the Delaunay triangulation of the origin and the given 2-D
 * points: the triangles (0, a, b), as pairs (a, b) of indices into `neighbors` in
 * counter-clockwise order around the origin, whose circumradius is at most `maxCircumradius`.
 * Points at distance <= `tiny` from the origin are ignored (projected duplicates). A pair of
 * consecutive ring points with no triangle between them is a gap of the ring (the origin is on
 * the convex hull there).
 */
std::vector<std::array<int, 2>> LocalDelaunayRing(const std::vector<Eigen::Vector2d>& neighbors,
  double maxCircumradius,
  double tiny);

/// The neighbours of each point whose distances stand for its edges in the Nyquist frequency of
/// a cloud: 6, the mean valence of a triangulated surface.
constexpr int NyquistNeighbors = 6;

/**
 * The edge sums behind the Nyquist frequency of a point cloud, NyquistFrequency(sums[0],
 * sums[1]) (Filtering/Transfer.h): the distances from each point to its NyquistNeighbors
 * nearest others (its edges in a triangulation of the cloud), summed, and their number. Points
 * with a non-finite coordinate are left out; {0, 0} for fewer than two points.
 */
std::vector<double> CloudEdgeSums(const Points& points);
} // namespace spectral

#endif
