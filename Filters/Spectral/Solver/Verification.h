// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Verification.h
 * @brief The residual checks of eigenpairs: the true residuals that decide which Ritz pairs a
 *        band keeps (Verify), and the final check of the returned pairs (CheckResiduals).
 *
 * Also defines the public measures declared in EigenSolver.h: RelativeResiduals and
 * OrthonormalityError. Both checks measure residuals in the D^-1 norm (D the row sums of M),
 * relative to max(|lambda|, a reference eigenvalue): see RelativeResiduals.
 *
 * Used by BlockLanczos (Verify) and SmallestEigenpairs (CheckResiduals); tested by
 * Testing/Core/TestEigenSolver.cxx (TorusContract, RefinedBands; every case through CheckPairs).
 */
#ifndef spectral_Verification_h
#define spectral_Verification_h

#include "Common/Mesh.h"
#include "Solver/EigenSolver.h"

#include <vector>

namespace spectral
{
namespace detail
{
/**
 * Check the true residuals of Ritz pairs (x_k, sigma + shifted_k), given AX = (L - sigma M) X and
 * MX = M X: sets `nearest` to the pairs ordered by distance from the shift and returns how many
 * of the first of them have a relative residual (D^-1 norm, relative to
 * max(|lambda|, reference)) within `tolerance`.
 */
int Verify(const Eigen::Ref<const DenseMatrix>& AX,
  const Eigen::Ref<const DenseMatrix>& MX,
  const Vector& shifted,
  const Vector& inverseMass,
  double sigma,
  double reference,
  double tolerance,
  std::vector<Eigen::Index>& nearest);

/**
 * The final check of SmallestEigenpairs: sets result.MaxResidual to the largest of
 * RelativeResiduals(L, M, result.Eigenvalues, result.Eigenvectors) and adds its time to
 * result.Seconds.Verification.
 * \throws SolverFailure if it exceeds `tolerance` (EigenOptions::ResidualTolerance).
 */
void CheckResiduals(const SparseMatrix& L,
  const SparseMatrix& M,
  double tolerance,
  EigenResult& result);
} // namespace detail
} // namespace spectral

#endif
