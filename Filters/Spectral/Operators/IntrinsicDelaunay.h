// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file IntrinsicDelaunay.h
 * @brief The robust intrinsic Delaunay Laplacian of N. Sharp and K. Crane (2020).
 *
 * The surface is kept as it is (same points, same metric); only its triangulation changes.
 * Edges are flipped intrinsically, on edge lengths alone, until every edge is locally Delaunay
 * (the two angles opposite it sum to at most pi, i.e. cot a + cot b >= 0). The cotan stiffness
 * of that triangulation has non-negative edge weights, so it satisfies a maximum principle, and
 * it does not degrade on obtuse or needle triangles the way the extrinsic cotan Laplacian does.
 *
 * Two steps make it work on any triangle soup, as in Sharp and Crane's paper:
 * - the tufted cover: every triangle is taken twice, once in each orientation, and the copies
 *   around each edge are glued cyclically (TuftedCover). The cover is a closed oriented surface
 *   even where the input has boundaries, non-manifold edges (three or more triangles) or
 *   inconsistent orientation, so every edge can be flipped. Its operators, halved (Weight), are
 *   the input's: on a mesh that is already intrinsic Delaunay they equal the cotan operators.
 *   Copies of one triangle in the input (the soup of the point-cloud Laplacian, PointCloud.h)
 *   take turns with the other triangles around each edge, so that a copy is glued to another
 *   triangle rather than folded onto its twin where the input allows it: a fold is an edge whose
 *   two opposite angles are the same angle, flipped whenever that angle is obtuse, and flips
 *   through folds lower the Dirichlet energy below that of the surface (eigenvalues about 2%
 *   low on a random sphere cloud, 0.5% with the turns).
 * - intrinsic mollification: the smallest delta is added to every edge length that makes each
 *   triangle satisfy the triangle inequality with a margin of MollificationFactor times the mean
 *   edge length (Mollify), so near-degenerate triangles get finite cotangents.
 *
 * References: A. I. Bobenko and B. A. Springborn, "A Discrete Laplace-Beltrami Operator for
 * Simplicial Surfaces", Discrete & Computational Geometry 38, 2007 (intrinsic Delaunay
 * triangulations and their Laplacian); N. Sharp and K. Crane, "A Laplacian for Nonmanifold
 * Triangle Meshes", Computer Graphics Forum 39(5), 2020 (tufted cover, mollification).
 *
 * Used by Operators/Laplacian.cxx (LaplacianKind::IntrinsicDelaunay); tested by
 * Testing/Core/TestIntrinsicDelaunay.cxx.
 */
#ifndef spectral_IntrinsicDelaunay_h
#define spectral_IntrinsicDelaunay_h

#include "Common/Mesh.h"
#include "Common/Monitor.h"

#include <string>
#include <vector>

namespace spectral
{
/// #F by 3 edge lengths; entry (f, c) is the length of the side from corner c to corner c+1.
using EdgeLengths = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// The margin of the triangle inequality that Mollify ensures, relative to the mean edge length
/// (Sharp and Crane's default).
constexpr double MollificationFactor = 1e-5;

/// An intrinsic triangulation of the points of a mesh: triangles with edge lengths, no positions.
struct IntrinsicTriangulation
{
  /// Number of points (the same points as the extrinsic mesh).
  int NumberOfPoints = 0;
  /// #F by 3 point indices. Two triangles may share more than one edge after flips, and an
  /// edge may join a point to itself.
  Triangles Faces;
  /// #F by 3 lengths, see EdgeLengths.
  EdgeLengths Lengths;
  /// The factor of every triangle's contribution to the operators: 1/2 for a tufted cover,
  /// which holds each triangle twice.
  double Weight = 1.0;
  /// The length added to every edge by Mollify (0 when every triangle had its margin).
  double Mollification = 0.0;
  /// Number of edge flips performed.
  int Flips = 0;
  /// Edges still not locally Delaunay when the flip budget (see below) ran out.
  int NonDelaunayEdges = 0;
};

/**
 * The intrinsic Delaunay triangulation of the mollified tufted cover of a mesh, by edge flips
 * on edge lengths.
 *
 * Each non locally Delaunay edge (cot a + cot b < -1e-10) is flipped: the two triangles are
 * laid out in the plane from their lengths and the other diagonal of the quad becomes the edge.
 * Flipping stops when all edges are Delaunay, or after 50 #F + 1000 flips (a guard against
 * rounding cycles; NonDelaunayEdges then counts what was left).
 *
 * \param mesh Any triangles (e.g. PrepareMesh(...).Mesh); degenerate ones get the margin of
 *        the mollification.
 * \param monitor Polled for cancellation every few thousand flips.
 * \return The flipped triangulation (same number of triangles and points).
 * \throws Cancelled if monitor.Cancelled returned true.
 */
IntrinsicTriangulation IntrinsicDelaunay(const TriangleMesh& mesh,
  const Monitor& monitor = Monitor());

/**
 * The sentences for the user about an intrinsic triangulation: the edges that the flip budget
 * left non-Delaunay (their cotangent weights may be negative); empty when there are none.
 */
std::vector<std::string> IntrinsicDelaunayWarnings(const IntrinsicTriangulation& T);

/**
 * The tufted cover of a mesh: its triangles [0, F) and the same triangles reversed [F, 2F)
 * (face F + f is (a, c, b) for face f = (a, b, c)), with Weight 1/2. Without flips its operators
 * equal those of the mesh.
 */
IntrinsicTriangulation TuftedCover(const TriangleMesh& mesh);

/**
 * Intrinsic mollification: add to every length the smallest delta >= 0 for which every
 * triangle satisfies l_a + l_b >= l_c + epsilon, epsilon = factor times the mean length.
 * \return delta.
 */
double Mollify(EdgeLengths& lengths, double factor);

/**
 * The intrinsic triangulation of a mesh without any flip (the extrinsic triangulation's edge
 * lengths). Its operators equal CotanStiffness, LumpedMass and ConsistentMass of the mesh.
 */
IntrinsicTriangulation IntrinsicTriangulationOf(const TriangleMesh& mesh);

/**
 * Cotan stiffness of an intrinsic triangulation, times its Weight (#V by #V, sparse, symmetric,
 * positive semi-definite, Q 1 = 0), with the definition of CotanStiffness. Cotangents come from
 * edge lengths: cot of the angle opposite side a is (b^2 + c^2 - a^2) / (4 area), the area from
 * Kahan's stable form of Heron's formula. Degenerate triangles contribute nothing.
 */
SparseMatrix IntrinsicCotanStiffness(const IntrinsicTriangulation& T);

/**
 * Lumped mass of an intrinsic triangulation: Weight times a third of the area of each intrinsic
 * triangle to each of its corners (length #V). Flips preserve the total area but move mass between
 * points, so this is the mass that matches IntrinsicCotanStiffness (Sharp and Crane use it too).
 */
Vector IntrinsicLumpedMass(const IntrinsicTriangulation& T);

/// Consistent (Galerkin) mass of the intrinsic triangles (times Weight); same pattern as the
/// stiffness.
SparseMatrix IntrinsicConsistentMass(const IntrinsicTriangulation& T);
} // namespace spectral

#endif
