// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Problem.h
 * @brief The problem stage of a basis computation: from a mesh and options to the operators to
 *        solve, in units of the mesh's size, with the number of harmonics, before any eigensolve.
 *
 * Checks the request (InvalidInput), keeps the usable part of the mesh (PrepareMesh,
 * LeaveOutSmallComponents) or takes a point cloud whole, assembles the chosen operators
 * (triangles, tetrahedra, intrinsic Delaunay, clouds; Dirichlet conditions eliminate the boundary
 * rows) in units of UnitScale of the used points' diameter, clamps the number of harmonics to the
 * usable points (ClampHarmonics, with a warning) and checks the memory. ComputeBasis (Basis.h)
 * runs it, then the core's engine; the distributed engine (Distributed/Solve.h) runs its
 * distributed counterparts and shares its rules: UnitScale, ClampHarmonics.
 */
#ifndef spectral_Problem_h
#define spectral_Problem_h

#include "Basis.h"

#include <string>
#include <utility>

namespace spectral
{
/// The operators to solve and what the solve needs to know of them.
struct Problem
{
  /// The usable part of a surface or volume mesh in units of Scale (empty for a point cloud):
  /// kept for the whole solve, as the operators are (the solver's buffers then lie where they
  /// always did, and its rounding, which follows their alignment, does not move).
  PreparedMesh Prepared;
  /// The operators in units of Scale, with the map back to the input points.
  DiscreteLaplacian Operators;
  /// The unit of length (UnitScale): eigenvalues scale back as 1 / Scale^2.
  double Scale = 1.0;
  /// 3 for a volume (tetrahedra), 2 otherwise: the mass scales back as Scale^Dimension.
  int Dimension = 2;
  /// m after the clamps; 0 with a frequency window (its inertia count decides).
  int Harmonics = 0;
  /// The band size the memory plan chose (CheckMemory): EigenOptions::BandSize of the solve.
  int BandSize = 0;
  /// Whether a frequency window is asked for, and its ends as eigenvalues in the operators'
  /// units ((omega Scale)^2).
  bool Window = false;
  std::pair<double, double> WindowEigenvalues = { 0.0, 0.0 };
};

/**
 * The number of harmonics to compute: `requested`, at most `usable` (the points that `what`, e.g.
 * "triangles use"); `warning` is set when it clamps, empty otherwise.
 * \throws InvalidInput if requested < 1.
 */
int ClampHarmonics(int requested, long long usable, const std::string& what, std::string& warning);

/**
 * The frequency window [lower, upper) as eigenvalues in units of `scale` ((omega scale)^2): the one
 * rule of both engines. \throws InvalidInput unless 0 <= lower < upper < infinity.
 */
std::pair<double, double> WindowEigenvalues(double lower, double upper, double scale);

/// The error of a frequency window [lower, upper) that holds no eigenvalue (`below` lie below it).
std::string EmptyWindow(double lower, double upper, int below);

/**
 * The memory plan (PlanBasisMemory or PlanStreamedMemory, Solver/Memory.h) for m harmonics on
 * `used` of the mesh's points against what is available (BasisOptions::MemoryLimit, or the
 * system's): the band size to run with, smaller than the automatic one where that makes the solve
 * fit (a warning says so).
 *
 * \return the band size for EigenOptions::BandSize (options.Solver.BandSize when unchanged).
 * \throws InsufficientMemory when not even the smallest planned band fits.
 */
int CheckMemory(const TriangleMesh& mesh,
  Eigen::Index used,
  int m,
  const BasisOptions& options,
  const Monitor& monitor,
  BasisResult& result);

/**
 * The problem stage of ComputeBasis (see the file documentation). Warnings go to the monitor and
 * into result.Warnings; result.BoundaryPoints, Components and ConstantHarmonics are set.
 * \throws as ComputeBasis, before its eigensolve.
 */
Problem PrepareProblem(const TriangleMesh& mesh,
  const BasisOptions& options,
  const Monitor& monitor,
  BasisResult& result);

/// The warning of a request for m harmonics on a surface or volume of `components` > 1 connected
/// components with m <= components: every harmonic is constant on one component, and what a
/// spectral filter can still do with them. The one text of both engines.
std::string NoMoreHarmonicsThanComponents(int m, int components);

/// The warnings about the components of the problem for m harmonics (with natural conditions):
/// their zero eigenvalues, welding seams, and a request for no more harmonics than components.
void ReportComponentsOf(const Problem& problem, int m, const Monitor& monitor, BasisResult& result);

/// Passes the warnings on to the monitor and keeps them in the result.
void Report(const std::vector<std::string>& warnings, const Monitor& monitor, BasisResult& result);
} // namespace spectral

#endif
