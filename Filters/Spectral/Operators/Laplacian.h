// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Laplacian.h
 * @brief The discrete operators of a mesh, whatever its kind, behind one interface.
 *
 * Every kind of mesh (triangle surfaces, with the extrinsic cotangent or the intrinsic Delaunay
 * Laplacian, and tetrahedral volumes, with the P1 cotangent Laplacian) is turned into the same
 * DiscreteLaplacian: the stiffness Q, the mass of
 * the eigenproblem Q h = lambda M h, the lumped mass that the transform weighs by, the map from
 * the operators' rows to the input's points, and what was left out and why. The solvers
 * (Solver/EigenSolver.h) and the entry point (Basis.h) only see this structure.
 *
 * Used by Basis.cxx and bench/; tested by Testing/Core/TestOperators.cxx (AssembleLaplacian).
 */
#ifndef spectral_Laplacian_h
#define spectral_Laplacian_h

#include "Common/Mesh.h"
#include "Common/Monitor.h"
#include "Operators/Operators.h"

#include <string>
#include <vector>

namespace spectral
{
/// The discretization of the Laplace-Beltrami operator of a triangle mesh.
enum class LaplacianKind
{
  /// Cotangent weights of the input triangles or tetrahedra (Operators.h).
  Cotangent,
  /// Cotangent weights of the intrinsic Delaunay triangulation (IntrinsicDelaunay.h). For
  /// triangles only: a volume uses Cotangent instead, with a warning.
  IntrinsicDelaunay
};

/// The condition the harmonics satisfy on the boundary of the mesh.
enum class BoundaryCondition
{
  /// The natural condition: zero normal derivative. Each connected component has a constant
  /// harmonic of eigenvalue 0.
  Neumann,
  /// The harmonics vanish on the boundary (BoundaryPoints in Operators.h): the boundary points
  /// are eliminated from the operators, so they have zero harmonics and mass, and no
  /// eigenvalue is zero. A mesh without boundary (a closed surface) keeps Neumann, with a
  /// warning.
  Dirichlet
};

/// The mass matrix M of the eigenproblem.
enum class MassKind
{
  /// The diagonal (barycentric) mass.
  Lumped,
  /// The Galerkin mass; its row sums are the lumped mass.
  Consistent
};

/// How a mesh's operators are built.
struct LaplacianOptions
{
  LaplacianKind Laplacian = LaplacianKind::Cotangent;
  MassKind Mass = MassKind::Lumped;
  BoundaryCondition Boundary = BoundaryCondition::Neumann;
};

/// The operators of a mesh: what every solver takes, and what the output needs to map back.
struct DiscreteLaplacian
{
  /// Q, #rows by #rows, symmetric positive semi-definite, Q 1 = 0.
  SparseMatrix Stiffness;
  /// M: Diagonal(LumpedMass) or the consistent mass.
  SparseMatrix Mass;
  /// The lumped mass (intrinsic with the intrinsic Laplacian): the transform's weights.
  Vector LumpedMass;
  /// For each row of the operators, the input point it belongs to.
  std::vector<int> InputPointIds;
  /// The connected component of each row (one zero eigenvalue each with ConstantHarmonics).
  ComponentLabels Components;
  /// Whether the first eigenvalue of each component is the 0 of its constant harmonic: true for
  /// Neumann conditions, false once Dirichlet conditions eliminated boundary points.
  bool ConstantHarmonics = true;
  /// Points eliminated by Dirichlet conditions (not among InputPointIds).
  int BoundaryPoints = 0;
  /// Bounding-box diagonal of the used points: the scale of the lowest frequencies.
  double Diameter = 0.0;
  /// What was left out or could not be repaired, one sentence each, for the user.
  std::vector<std::string> Warnings;
};

/**
 * The operators of the part of a prepared mesh that has cells (see PrepareMesh).
 * \param prepared The output of PrepareMesh: its rows are the operators' rows, except the
 *        boundary points that Dirichlet conditions eliminate.
 * \param options Laplacian, mass and boundary condition.
 * \param monitor Cancellation of the intrinsic Delaunay flips; no progress is reported.
 * \throws Cancelled if the monitor says so.
 * \throws InvalidInput if Dirichlet conditions leave no interior point.
 */
DiscreteLaplacian AssembleLaplacian(const PreparedMesh& prepared,
  const LaplacianOptions& options,
  const Monitor& monitor = Monitor());

/**
 * Sentences for the user about what PrepareMesh (degenerate and duplicated triangles, points
 * no triangle uses) and LeaveOutSmallComponents left out; empty when nothing was.
 */
std::vector<std::string> PreparationWarnings(const PreparedMesh& prepared);
} // namespace spectral

#endif
