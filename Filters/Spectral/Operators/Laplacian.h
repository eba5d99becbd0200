// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Laplacian.h
 * @brief The discrete operators of a mesh, whatever its kind, behind one interface.
 *
 * Every kind of mesh (today triangle surfaces, with the extrinsic cotangent or the intrinsic
 * Delaunay Laplacian) is turned into the same DiscreteLaplacian: the stiffness Q, the mass of
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
  /// Cotangent weights of the input triangles (Operators.h).
  Cotangent,
  /// Cotangent weights of the intrinsic Delaunay triangulation (IntrinsicDelaunay.h).
  IntrinsicDelaunay
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
  /// The connected component of each row (one zero eigenvalue each).
  ComponentLabels Components;
  /// Bounding-box diagonal of the used points: the scale of the lowest frequencies.
  double Diameter = 0.0;
  /// What was left out or could not be repaired, one sentence each, for the user.
  std::vector<std::string> Warnings;
};

/**
 * The operators of the part of a prepared mesh that has triangles (see PrepareMesh).
 * \param prepared The output of PrepareMesh: its rows are the operators' rows.
 * \param options Laplacian and mass.
 * \param monitor Cancellation of the intrinsic Delaunay flips; no progress is reported.
 * \throws Cancelled if the monitor says so.
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
