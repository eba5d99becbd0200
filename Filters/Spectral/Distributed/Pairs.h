// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Pairs.h
 * @brief The eigenpairs of the distributed pencil: one slice of the spectrum by Krylov-Schur
 *        spectrum slicing, the figures of each pair on distributed vectors (the core's
 *        definitions, Verification.h), and the scatter of a pair's values to the rows of every
 *        process's points.
 */
#ifndef spectral_Distributed_Pairs_h
#define spectral_Distributed_Pairs_h

#include "Distributed/Petsc.h"

#include "Common/Mesh.h"

#include <functional>
#include <utility>
#include <vector>

namespace spectral
{
namespace distributed
{
/// The eigenpairs of one interval, ascending (eigenvalue, SLEPc's index).
struct Slice
{
  std::vector<std::pair<double, PetscInt>> Order;
  /// Eigenvalues in the interval by the inertia at its ends, and the shifts used.
  PetscInt Count = 0;
  PetscInt Shifts = 0;
};

/// What SolveSlice passes to SLEPc.
struct SliceSettings
{
  /// Krylov-Schur's convergence tolerance and iteration limit.
  double Tolerance = 0.0;
  int MaxIterations = 0;
  /// SLEPc's npart: sub-intervals solved at once by groups of processes.
  int Partitions = 1;
};

/**
 * Every eigenpair of [lower, upper] by Krylov-Schur spectrum slicing (shift-and-invert on MUMPS
 * Cholesky factorizations, the options of the Session), in `eps`. \throws std::runtime_error
 * when the number of pairs differs from the inertia count of the interval. Collective.
 */
Slice SolveSlice(OwnedEPS& eps, Mat Q, Mat D, double lower, double upper, const SliceSettings& settings);

/// The figures of one pair before its relative residual is known (it needs every eigenvalue).
struct PairError
{
  /// The D^-1-weighted norm of the residual Q x - lambda D x.
  double ResidualNorm = 0.0;
  /// The componentwise backward error (Verification.h, ScaledBackwardError).
  double Backward = 0.0;
};

/// The checks of eigenpairs of (Q, D) on distributed vectors (collective).
class PairChecks
{
public:
  PairChecks(Mat Q, Mat D);

  /// Scales x to unit D-norm, stores D x (owned rows) in dx and measures the pair.
  PairError NormalizeAndCheck(Vec x, double lambda, double* dx);

  /// trace(Q) / total mass: the floor of the spectrum's scale for the relative residual.
  double TraceOverMass = 0.0;
  /// Gershgorin's bound on the largest eigenvalue, max_i sum_j |Q_ij| / D_i, over all processes.
  double GershgorinTop = 0.0;

private:
  Mat Q;
  Mat D;
  OwnedMat AbsQ;
  std::vector<double> RowSum;
  OwnedVec Qx;
  OwnedVec Dx;
  OwnedVec AbsX;
  OwnedVec Scale;
  OwnedVec AbsDx;
};

/// Copies the values of a distributed vector (owned rows) to the piece's points that use them,
/// seam copies included (from their owners, by a PETSc scatter).
class RowWriter
{
public:
  /// `layout`: any vector of the operators' row layout; `global`: the global number of each
  /// used point; `rows`: its row in the piece.
  RowWriter(Vec layout, const std::vector<PetscInt>& global, const std::vector<int>& rows);

  /// Calls store(row, value) for every used point (collective).
  void Write(Vec values, const std::function<void(Eigen::Index, double)>& store);

private:
  const std::vector<int>& Rows;
  OwnedVec Local;
  OwnedScatter Scatter;
};

/**
 * H^T Y for the first `columns` harmonics H already written in `rows` (row-major, m values a
 * point), read at the rows `ownedRows` (one per row of Y).
 */
DenseMatrix WrittenTimes(const double* rows,
  int m,
  int columns,
  const std::vector<Eigen::Index>& ownedRows,
  const Eigen::Ref<const DenseMatrix>& Y);
} // namespace distributed
} // namespace spectral

#endif
