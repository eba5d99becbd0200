// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Operators.h
 * @brief Discrete Laplace-Beltrami operators of a triangle mesh: cotan stiffness and mass.
 *
 * The generalized eigenproblem L h = lambda M h of these matrices defines the manifold harmonics
 * (B. Vallet and B. Levy, "Spectral Geometry Processing with Manifold Harmonics", Computer Graphics
 * Forum 27(2), 2008). Natural (Neumann) boundary conditions hold on open boundaries.
 *
 * Used by vtkManifoldHarmonicBasis; tested by Testing/Core/TestOperators.cxx.
 */
#ifndef spectral_Operators_h
#define spectral_Operators_h

#include "Common/Mesh.h"

#include <vector>

namespace spectral
{
/// The part of a mesh that the operators are built on, and how it maps to the input.
struct PreparedMesh
{
  /// Triangles of non-zero area, on the points they use, renumbered 0..#used-1.
  TriangleMesh Mesh;
  /// For each point of Mesh, its index in the input mesh.
  std::vector<int> InputPointIds;
  /// Input triangles left out because their area is numerically zero.
  int DegenerateTriangles = 0;
  /// Input triangles left out because an earlier one has the same three points (either
  /// orientation): counted twice they would double the local stiffness and mass.
  int DuplicateTriangles = 0;
  /// Input points that no remaining triangle uses (their harmonics are zero).
  int UnusedPoints = 0;
  /// Connected components left out by LeaveOutSmallComponents, and their points (which have
  /// zero harmonics, as unused points have).
  int SmallComponents = 0;
  int SmallComponentPoints = 0;
};

/// Largest coordinate magnitude the operators accept: squared areas (edge lengths to the fourth
/// power) stay finite below it.
constexpr double MaxCoordinate = 1e75;

/**
 * The one check of a point's coordinates, for every kind of input.
 * \throws InvalidInput if point `id` has a non-finite coordinate or one of magnitude above
 *         MaxCoordinate.
 */
void CheckCoordinates(const Points& points, Eigen::Index id);

/**
 * Keep the triangles with non-zero area, once each, and the points they use.
 *
 * A triangle is degenerate when twice its area is below 1e-12 times its longest edge squared
 * (zero-area triangles, repeated points, collinear corners). Degenerate triangles carry no
 * stiffness and no mass, so they are left out rather than turned into infinite cotangents.
 *
 * \param input Points and triangles; indices must lie in [0, #V).
 * \return The compact mesh with the map back to input point ids.
 * \throws InvalidInput for an index out of range, or a coordinate that CheckCoordinates refuses
 *         on a used point.
 */
PreparedMesh PrepareMesh(const TriangleMesh& input);

/**
 * Leave out the connected components of fewer than `minimumPoints` points: their triangles are
 * dropped and their points get zero harmonics and mass, like unused points (SmallComponents and
 * SmallComponentPoints count them).
 * \param prepared The output of PrepareMesh.
 * \param minimumPoints Components of at least this many points stay; 0 or 1 keeps all.
 */
PreparedMesh LeaveOutSmallComponents(const PreparedMesh& prepared, int minimumPoints);

/**
 * Cotangent stiffness matrix Q (#V by #V, sparse, symmetric, positive semi-definite).
 *
 * Q_ij = -(cot a_ij + cot b_ij) / 2 for an edge ij with opposite angles a_ij and b_ij
 * (one angle on a boundary edge), Q_ii = -sum_j Q_ij, so Q 1 = 0. Cotangents come from edge
 * vectors (cot = u.v / |u x v|); degenerate triangles contribute nothing. The diagonal is stored
 * even where it is zero, so every Q has the pattern of the mesh graph plus the diagonal.
 */
SparseMatrix CotanStiffness(const TriangleMesh& mesh);

/// Lumped (barycentric) mass: D_ii = sum of |t|/3 over the triangles t around point i. Length #V.
Vector LumpedMass(const TriangleMesh& mesh);

/**
 * Consistent (Galerkin) mass matrix B (#V by #V, sparse, symmetric positive definite on used
 * points): B_ij = sum |t|/12 over triangles t with edge ij, B_ii = sum |t|/6 over t around i.
 * Its row sums equal LumpedMass.
 */
SparseMatrix ConsistentMass(const TriangleMesh& mesh);

/**
 * A sparse symmetric operator assembled from per-triangle contributions, shared by the extrinsic
 * operators here and the intrinsic ones of IntrinsicDelaunay.h. Every diagonal entry is stored,
 * also where it stays zero, so all operators of a mesh have the pattern of its graph plus the
 * diagonal.
 */
class TriangleAssembly
{
public:
  /// n unknowns; room for `perTriangle` entries of each of `triangles` triangles.
  TriangleAssembly(Eigen::Index n, Eigen::Index triangles, int perTriangle);
  /// Edge weight w between points i and j: -w at (i, j) and (j, i), +w at (i, i) and (j, j).
  void AddEdgeWeight(int i, int j, double w);
  /// Galerkin mass of a triangle of the given area: area/6 on its diagonal, area/12 off it.
  void AddMassBlock(int a, int b, int c, double area);
  /// The assembled matrix (duplicates summed), compressed.
  SparseMatrix Matrix() const;

private:
  Eigen::Index Size;
  std::vector<Eigen::Triplet<double>> Triplets;
};

/// The diagonal matrix diag(d) in sparse form.
SparseMatrix Diagonal(const Vector& d);

/// The diagonal of the bounding box of the points; 0 for none.
double BoundingBoxDiagonal(const Points& points);

/// Total area of the triangles.
double SurfaceArea(const TriangleMesh& mesh);

/// The connected component of each point (points joined by triangle edges).
struct ComponentLabels
{
  /// For each point, its component in [0, Count), numbered in the order of their first points.
  std::vector<int> Label;
  /// Number of components; isolated points count as components of their own.
  int Count = 0;
};

/// Label the connected components of a mesh.
ComponentLabels LabelComponents(const TriangleMesh& mesh);

/// Number of connected components (points joined by triangle edges; isolated points count too).
int ConnectedComponents(const TriangleMesh& mesh);

/// Mean edge length over all triangle edges (each interior edge counted twice). 0 for no triangles.
double MeanEdgeLength(const TriangleMesh& mesh);
} // namespace spectral

#endif
