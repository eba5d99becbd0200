// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file MassMatrix.h
 * @brief The mass matrix of the pencil (L, M) as the band iterations see it: a sparse matrix,
 *        or the identity once SmallestEigenpairs has scaled a diagonal (lumped) mass away; and
 *        the known null vectors the iterations work M-orthogonally to (deflation).
 *
 * Used by Bands, BlockLanczos, SpectraBand and LanczosKernels; both cases are tested by
 * Testing/Core/TestEigenSolver.cxx (SphereSpectrum: lumped; SphereConsistentMass: consistent;
 * ExactZeroModes: deflation).
 */
#ifndef spectral_MassMatrix_h
#define spectral_MassMatrix_h

#include "Common/Mesh.h"
#include "Solver/BlockProducts.h"

namespace spectral
{
namespace detail
{
/**
 * The mass matrix of the pencil in the products of the block iteration. A positive diagonal mass
 * (the lumped one) is scaled away before the iteration (SmallestEigenpairs): the pencil becomes
 * (D^-1/2 L D^-1/2, I), and Identity skips every product with it.
 */
struct MassMatrix
{
  /// n by n; the sparse identity when Identity is set.
  const SparseMatrix& Matrix;
  bool Identity;
  /**
   * Null vectors of L known in advance (EigenOptions::ConstantNullSpace), M-orthonormal, n by k;
   * null for none. The iterations keep every vector they build M-orthogonal to them (Deflate),
   * so that they look for the other eigenpairs only, in the complement of the null space.
   */
  const DenseMatrix* Deflation = nullptr;

  /// W -= Z (Z^T M W) for the null vectors Z (nothing without them), with the products of
  /// BlockProducts.h, whose sums run in an order that does not depend on where W lies in memory
  /// (Eigen's vectorized reductions start at an aligned address), so that a solve repeats its
  /// result to the last bit.
  void Deflate(Eigen::Ref<DenseMatrix> W) const
  {
    if (!this->Deflation || this->Deflation->cols() == 0)
    {
      return;
    }
    const DenseMatrix& Z = *this->Deflation;
    const DenseMatrix coefficients =
      this->Identity ? TransposeProduct(Z, W) : TransposeProduct(DenseMatrix(this->Matrix * Z), W);
    SubtractProduct(W, Z, coefficients);
  }

  /// M W in `out`; W itself (no copy) for the identity.
  const DenseMatrix& Times(const DenseMatrix& W, DenseMatrix& out) const
  {
    if (this->Identity)
    {
      return W;
    }
    out.noalias() = this->Matrix * W;
    return out;
  }

  /// Not for blocks or expressions: they would bind to a temporary copy, which the identity
  /// case would return.
  template<typename Other>
  const DenseMatrix& Times(const Other& W, DenseMatrix& out) const = delete;
};
} // namespace detail
} // namespace spectral

#endif
