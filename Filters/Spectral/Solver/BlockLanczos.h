// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BlockLanczos.h
 * @brief One shift-invert band by block Lanczos with thick restarts (LanczosMethod::Block, the
 *        default): the Krylov basis and its reorthogonalization, the Ritz pairs and their
 *        convergence tests, thick restarts, and the verification and refinement of the pairs
 *        a band returns.
 *
 * The dense steps (M-orthonormalization, Rayleigh-Ritz) are in LanczosKernels.h, the true
 * residual test in Verification.h. Used by Bands; tested by Testing/Core/TestEigenSolver.cxx
 * (SphereSpectrum, TorusContract, RefinedBands, Cancellation).
 */
#ifndef spectral_BlockLanczos_h
#define spectral_BlockLanczos_h

#include "Common/Monitor.h"
#include "Solver/BandWorkspace.h"
#include "Solver/EigenSolver.h"
#include "Solver/Factorization.h"
#include "Solver/MassMatrix.h"

namespace spectral
{
namespace detail
{
/// Thrown by a band whose shift lies too close to an eigenvalue: where that eigenvalue lies, and
/// on which side of it the shift was.
struct ShiftTooClose
{
  double Eigenvalue;
  /// +1 where the shift lay above the eigenvalue, -1 below.
  double Side;
};

/**
 * The request.Pairs (nev) eigenpairs nearest request.Sigma by block Lanczos on
 * Op = (L - sigma M)^-1 M in the M inner product, with full block reorthogonalization (the block
 * recurrence, then classical Gram-Schmidt against the whole basis, repeated only where it
 * cancels; matrix-matrix products only) and thick restarts that keep the best Ritz vectors. The
 * projected matrix T = V^T M Op V is assembled from the Gram-Schmidt coefficients. A block of b
 * vectors finds eigenvalues of multiplicity up to b directly. A pair counts as converged when its
 * Ritz estimate is below Tolerance and its residual below ResidualTolerance / 20 (relaxed up to
 * / 2 when the iteration stalls), relative to max(|lambda|, request.LambdaReference)
 * (LambdaReference <= 0: the band's first non-zero eigenvalue). Once the pairs the band must
 * return have settled by their Ritz estimates alone, the band refines them and lets their true
 * residuals and backward errors decide, whatever the residual estimate counts.
 * \param factor factored at request.Sigma.
 * \param monitor polled for cancellation before every block and told the band's progress (its
 *        applications against those a band usually takes, at most 0.95) after every block.
 * \param work the band's vectors, ascending, go into the first columns of work.Basis.
 * \param stats operator applications and seconds are added to it.
 * \throws SolverFailure without convergence; ShiftTooClose (request.MeanGap > 0: the spacing of
 *         the eigenvalues near sigma) when an eigenvalue lies within MeanGap / 40 of sigma.
 */
Band RunBlockBand(const ShiftedFactor& factor,
  const MassMatrix& M,
  const BandRequest& request,
  const EigenOptions& options,
  const Monitor& monitor,
  Workspace& work,
  EigenResult& stats);
} // namespace detail
} // namespace spectral

#endif
