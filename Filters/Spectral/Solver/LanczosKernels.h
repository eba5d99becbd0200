// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LanczosKernels.h
 * @brief Dense steps on tall blocks of vectors in the M inner product: projection,
 *        M-orthonormalization, Rayleigh-Ritz, and the in-place products they rotate bases with.
 *
 * The products with the whole basis go through BlockProducts.h; these kernels add the
 * M inner product (MassMatrix.h) and keep the number of n-row temporaries low.
 *
 * Used by BlockLanczos (every kernel) and Bands (MultiplyInPlace in the merge of bands); tested
 * through Testing/Core/TestEigenSolver.cxx (SphereSpectrum: identity mass, SphereConsistentMass:
 * sparse mass, BandSeams: merges), which checks the M-orthonormality of every result.
 */
#ifndef spectral_LanczosKernels_h
#define spectral_LanczosKernels_h

#include "Common/Mesh.h"
#include "Solver/MassMatrix.h"

#include <random>

namespace spectral
{
namespace detail
{
/**
 * X.leftCols(Z.cols()) = X.leftCols(Z.rows()) Z in place (Z.cols() <= Z.rows()), a few hundred
 * rows at a time through a small buffer: rotating or compressing a tall basis needs no second
 * n-row matrix. With `gram`, also its Gram matrix Y^T Y of the result Y, summed while the rows
 * are in cache (no second pass over Y).
 */
void MultiplyInPlace(Eigen::Ref<DenseMatrix> X, const DenseMatrix& Z, DenseMatrix* gram = nullptr);

/// W -= B (B^T M W) for a tall n-row B; returns B^T M W.
DenseMatrix Project(DenseMatrix& W, const Eigen::Ref<const DenseMatrix>& B, const MassMatrix& M);

/// The Gram matrix W^T M W.
DenseMatrix MassGram(const DenseMatrix& W, const MassMatrix& M);

/// The squared M-norm of every column of W.
Vector MassNorms(const DenseMatrix& W, const MassMatrix& M);

/**
 * M-orthonormalize the columns of W (two passes of SVQB: eigen-decomposition of the Gram matrix)
 * and return R with W_in = W_out R. Directions whose norm fell below `floor` (the block is nearly
 * inside the span of Basis) are replaced by random vectors M-orthogonal to Basis, to the other
 * columns and to the null vectors of M.Deflation; their rows of R are zero.
 * \param gram W^T M W if the caller has it, else empty.
 * \param out where the result goes: W itself (null), or other columns (then W is left as
 *        scratch). With the identity mass the second pass's Gram matrix is summed during the
 *        first pass's product and the second product writes `out` directly: W is read three
 *        times instead of five.
 */
DenseMatrix Orthonormalize(DenseMatrix& W,
  const MassMatrix& M,
  const Eigen::Ref<const DenseMatrix>& Basis,
  double floor,
  std::mt19937& generator,
  DenseMatrix gram = DenseMatrix(),
  Eigen::Ref<DenseMatrix>* out = nullptr);

/**
 * Rayleigh-Ritz on the pencil (L - sigma M, M) within the span of the columns of X, given
 * AX = (L - sigma M) X and MX = M X (null for the identity M): rotates X, AX and MX in place to
 * the Ritz vectors (M-orthonormal) and returns the Ritz values lambda - sigma: the Rayleigh
 * quotients of the pencil itself, where the Ritz values of the Lanczos projection T carry the
 * rounding of every solve and Gram-Schmidt coefficient that built it.
 * \throws SolverFailure if the columns of X are not linearly independent.
 */
Vector RayleighRitz(Eigen::Ref<DenseMatrix> X, Eigen::Ref<DenseMatrix> AX, DenseMatrix* MX);

/**
 * The Rayleigh quotient x^T A x / x^T M x of every column x of X, given AX = A X and MX = M X.
 */
Vector RayleighQuotients(const Eigen::Ref<const DenseMatrix>& X,
  const Eigen::Ref<const DenseMatrix>& AX,
  const Eigen::Ref<const DenseMatrix>& MX);
} // namespace detail
} // namespace spectral

#endif
