// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file IntrinsicDelaunay.h
 * @brief The intrinsic Delaunay Laplacian: cotan operators of an intrinsic Delaunay triangulation.
 *
 * The surface is kept as it is (same points, same metric); only its triangulation changes. Edges
 * are flipped intrinsically, on edge lengths alone, until every interior edge is locally
 * Delaunay (the two angles opposite it sum to at most pi, i.e. cot a + cot b >= 0). The cotan
 * stiffness of that triangulation has non-negative edge weights on interior edges, so it
 * satisfies a maximum principle, and it does not degrade on obtuse or needle triangles the way
 * the extrinsic cotan Laplacian does.
 *
 * References: A. I. Bobenko and B. A. Springborn, "A Discrete Laplace-Beltrami Operator for
 * Simplicial Surfaces", Discrete & Computational Geometry 38, 2007 (intrinsic Delaunay
 * triangulations and their Laplacian); N. Sharp and K. Crane, "A Laplacian for Nonmanifold
 * Triangle Meshes", Computer Graphics Forum 39(5), 2020 (robust flipping on real-world meshes).
 *
 * Non-manifold edges (three or more triangles) and edges between two triangles that cannot be
 * oriented consistently are never flipped: they stay as they are and their cotangent weights
 * may remain negative. Triangles that are oriented inconsistently across a manifold edge are
 * re-oriented internally; orientation plays no role in the operators.
 *
 * Used by vtkManifoldHarmonicBasis (Laplacian = INTRINSIC_DELAUNAY); tested by
 * Testing/Core/TestIntrinsicDelaunay.cxx.
 */
#ifndef spectral_IntrinsicDelaunay_h
#define spectral_IntrinsicDelaunay_h

#include "Common/Mesh.h"
#include "Common/Monitor.h"

namespace spectral
{
/// #F by 3 edge lengths; entry (f, c) is the length of the side from corner c to corner c+1.
using EdgeLengths = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// An intrinsic triangulation of the points of a mesh: triangles with edge lengths, no positions.
struct IntrinsicTriangulation
{
  /// Number of points (the same points as the extrinsic mesh).
  int NumberOfPoints = 0;
  /// #F by 3 point indices. Two triangles may share more than one edge after flips.
  Triangles Faces;
  /// #F by 3 lengths, see EdgeLengths.
  EdgeLengths Lengths;
  /// Number of edge flips performed.
  int Flips = 0;
  /// Edges left out of flipping: non-manifold edges (three or more triangles, counted once
  /// each) and manifold edges across which the orientation cannot be made consistent.
  int UnflippableEdges = 0;
  /// Interior edges still not locally Delaunay when the flip budget (see below) ran out.
  int NonDelaunayEdges = 0;
};

/**
 * The intrinsic Delaunay triangulation of a mesh, by edge flips on edge lengths.
 *
 * Each non locally Delaunay interior edge (cot a + cot b < -1e-10) is flipped: the two
 * triangles are laid out in the plane from their lengths and the other diagonal of the quad
 * becomes the edge. Flipping stops when all edges are Delaunay, or after 50 #F + 1000 flips
 * (a guard against rounding cycles; NonDelaunayEdges then counts what was left).
 *
 * \param mesh Triangles of non-zero area (e.g. PrepareMesh(...).Mesh). Degenerate triangles are
 *        tolerated: their edges are not flipped and they contribute nothing to the operators.
 * \param monitor Polled for cancellation every few thousand flips.
 * \return The flipped triangulation (same number of triangles and points).
 * \throws Cancelled if monitor.Cancelled returned true.
 */
IntrinsicTriangulation IntrinsicDelaunay(const TriangleMesh& mesh,
  const Monitor& monitor = Monitor());

/**
 * The intrinsic triangulation of a mesh without any flip (the extrinsic triangulation's edge
 * lengths). Its operators equal CotanStiffness, LumpedMass and ConsistentMass of the mesh.
 */
IntrinsicTriangulation IntrinsicTriangulationOf(const TriangleMesh& mesh);

/**
 * Cotan stiffness of an intrinsic triangulation (#V by #V, sparse, symmetric, positive
 * semi-definite, Q 1 = 0), with the definition of CotanStiffness. Cotangents come from edge
 * lengths: cot of the angle opposite side a is (b^2 + c^2 - a^2) / (4 area), the area from
 * Kahan's stable form of Heron's formula. Degenerate triangles contribute nothing.
 */
SparseMatrix IntrinsicCotanStiffness(const IntrinsicTriangulation& T);

/**
 * Lumped mass of an intrinsic triangulation: a third of the area of each intrinsic triangle to
 * each of its corners (length #V). Flips preserve the total area but move mass between points,
 * so this is the mass that matches IntrinsicCotanStiffness (Sharp and Crane use it too).
 */
Vector IntrinsicLumpedMass(const IntrinsicTriangulation& T);

/// Consistent (Galerkin) mass of the intrinsic triangles; same pattern as the stiffness.
SparseMatrix IntrinsicConsistentMass(const IntrinsicTriangulation& T);
} // namespace spectral

#endif
