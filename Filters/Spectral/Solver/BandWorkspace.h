// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BandWorkspace.h
 * @brief What one shift-invert band is asked for (BandRequest), what it returns (Band) and the
 *        tall matrices it works in, kept from band to band (Workspace).
 *
 * Filled by the two band iterations (BlockLanczos.h, SpectraBand.h) and read by the loop over
 * bands (Bands.h); tested through Testing/Core/TestEigenSolver.cxx (BandSeams, MethodsAgree).
 */
#ifndef spectral_BandWorkspace_h
#define spectral_BandWorkspace_h

#include "Common/Mesh.h"

namespace spectral
{
namespace detail
{
/// The pairs one band looks for: those nearest its shift.
struct BandRequest
{
  /// The shift sigma of L - sigma M.
  double Sigma = 0.0;
  /// nev, the number of pairs nearest the shift: the loop's band at the first attempt, fewer
  /// at a retry (RetryPairs, Bands.h).
  int Pairs = 0;
  /// 0 for the first run at this shift; later runs start elsewhere, with fewer pairs in the
  /// same subspace.
  int Attempt = 0;
  /// The first non-zero eigenvalue, the scale of relative residuals; <= 0 when not yet known.
  double LambdaReference = 0.0;
  /// The spacing of the eigenvalues near the shift; 0 before the first band.
  double MeanGap = 0.0;
  /// The pairs the band's Krylov subspace is sized for: the loop's band, whatever the attempt,
  /// so that a retry holds no more vectors than the first run (the memory estimate counts those,
  /// Solver/Memory.h).
  int SubspacePairs = 0;
  /// The converged pairs the band waits for before it returns (the loop's BandReturnPairs,
  /// Bands.h).
  int ReturnPairs = 0;
};

/// Eigenvalues of one band, sorted ascending; the vectors are the first columns of
/// Workspace::Basis.
struct Band
{
  Vector Values;
};

/**
 * Tall matrices kept from band to band. A fresh n-row matrix costs a page fault and the clearing
 * of a page for every 4 KB it touches first: with a new basis, Ritz vectors and merge products
 * for every band, a tenth of the run time on a 100,000-point mesh.
 */
struct Workspace
{
  DenseMatrix Basis; ///< the Lanczos basis of a band, then the band's vectors in its first columns
  DenseMatrix Image; ///< (L - sigma M) X for Ritz vectors X, or L Y in the band merge

  /// The first `cols` columns of A, resized to `rows` x `cols` only when it is too small.
  static Eigen::Block<DenseMatrix, Eigen::Dynamic, Eigen::Dynamic, true> Columns(DenseMatrix& A,
    Eigen::Index rows,
    Eigen::Index cols)
  {
    if (A.rows() != rows || A.cols() < cols)
    {
      A.resize(rows, cols);
    }
    return A.leftCols(cols);
  }
};
} // namespace detail
} // namespace spectral

#endif
