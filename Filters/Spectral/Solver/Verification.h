// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Verification.h
 * @brief The residual checks of eigenpairs: the true residuals that decide which Ritz pairs a
 *        band keeps (Verify), and the final check of the returned pairs (CheckResiduals).
 *
 * Also defines the public measures declared in EigenSolver.h: RelativeResiduals and
 * OrthonormalityError. Both checks measure residuals in the D^-1 norm (D the row sums of M),
 * relative to max(|lambda|, a reference eigenvalue): see RelativeResiduals. Which figures are
 * good enough is decided by Acceptance.h.
 *
 * Used by BlockLanczos (Verify) and SmallestEigenpairs (CheckResiduals); tested by
 * Testing/Core/TestEigenSolver.cxx (TorusContract, RefinedBands; every case through CheckPairs).
 */
#ifndef spectral_Verification_h
#define spectral_Verification_h

#include "Common/Mesh.h"
#include "Solver/Acceptance.h"
#include "Solver/EigenSolver.h"

#include <string>
#include <vector>

namespace spectral
{
/**
 * The reference eigenvalue of relative residuals: the smallest non-zero |lambda_k| of the pairs
 * (IsZeroEigenvalue against the largest), at least 1e-6 traceRatio.
 * \param traceRatio trace(L) / sum(M): the operator's scale.
 */
double ResidualReference(const Vector& lambda, double traceRatio);

namespace detail
{
/**
 * What the componentwise backward errors of Ritz pairs X need besides their residuals: |L|,
 * |M| (null for the identity) and X, from which |L| |x| and |M| |x| are formed one column at a
 * time, for the pairs whose residual alone does not pass (an n-row vector each, where whole
 * n x k matrices of them doubled a band's memory), and the tolerance
 * (EigenOptions::BackwardErrorTolerance). A null AbsL leaves the backward error out.
 */
struct BackwardScale
{
  const SparseMatrix* AbsL = nullptr;
  const SparseMatrix* AbsM = nullptr;
  const Eigen::Ref<const DenseMatrix>* X = nullptr;
  double Tolerance = 0.0;
};

/**
 * The floor of the denominators of BackwardErrors, relative to their largest: where a harmonic
 * and its neighbours vanish (its nodal lines, a flat grid's symmetry lines), |L| |h| is itself
 * round-off, and the pair is measured against the scale of the whole vector instead.
 */
constexpr double BackwardErrorFloor = 1e-6;

/**
 * max_i |r_i| / max(scale_i, BackwardErrorFloor largest), the componentwise backward error of a
 * residual r against the denominators `scale` = |L| |x| + |lambda| |M| |x|, whose largest over
 * the whole vector is `largest` (over all processes, for a distributed vector's rows).
 */
double ScaledBackwardError(const Eigen::Ref<const Vector>& r,
  const Eigen::Ref<const Vector>& scale,
  double largest);

/// The componentwise backward error of column k given its residual r (see BackwardErrors).
double ComponentwiseBackwardError(const Eigen::Ref<const Vector>& r,
  const Eigen::Ref<const Vector>& absLx,
  const Eigen::Ref<const Vector>& absMx,
  double lambda);

/**
 * Check the true residuals of Ritz pairs (x_k, sigma + shifted_k), given AX = (L - sigma M) X and
 * MX = M X: sets `nearest` to the pairs ordered by distance from the shift and returns how many
 * of the first of them have a relative residual (D^-1 norm, relative to
 * max(|lambda|, reference)) within `tolerance`, or a componentwise backward error within
 * backward.Tolerance.
 */
int Verify(const Eigen::Ref<const DenseMatrix>& AX,
  const Eigen::Ref<const DenseMatrix>& MX,
  const Vector& shifted,
  const Vector& inverseMass,
  double sigma,
  double reference,
  double tolerance,
  std::vector<Eigen::Index>& nearest,
  const BackwardScale& backward);

/// The two measures of a set of eigenpairs, one entry per pair.
struct PairFigures
{
  /// RelativeResiduals.
  Vector Relative;
  /// BackwardErrors; empty unless asked for.
  Vector Backward;
};

/**
 * RelativeResiduals and, if `backward`, BackwardErrors of the pairs in one pass over them (each
 * block of residuals is formed once for both).
 */
PairFigures ResidualFigures(const SparseMatrix& L,
  const SparseMatrix& M,
  const Vector& lambda,
  const DenseMatrix& Phi,
  bool backward);

/**
 * The final check of SmallestEigenpairs: sets result.MaxResidual and result.MaxBackwardError to
 * the largest of RelativeResiduals and BackwardErrors of the returned pairs and adds its time to
 * result.Seconds.Verification.
 * \throws SolverFailure if a pair exceeds both options.ResidualTolerance and
 *         options.BackwardErrorTolerance.
 */
void CheckResiduals(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  EigenResult& result);

/**
 * The same check on some of the pairs: raises result.MaxResidual and result.MaxBackwardError to
 * the figures of the pairs (lambda, Phi), whose first is pair `first` of the result (for the
 * message), and adds its time to result.Seconds.Verification. How a solve that does not keep
 * its eigenvectors verifies its pairs before it lets them go, a block at a time.
 * \throws SolverFailure as CheckResiduals.
 */
void CheckSomeResiduals(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  const Vector& lambda,
  const DenseMatrix& Phi,
  int first,
  EigenResult& result);
} // namespace detail
} // namespace spectral

#endif
