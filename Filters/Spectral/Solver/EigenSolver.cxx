// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
//
// SmallestEigenpairs: checks its input, then takes the dense path (small problems) or the
// band-by-band shift-invert iteration, whose parts live in files of their own:
//
//   Bands.{h,cxx}           the band policy, the shifts, the merging of bands, inertia proofs
//   BlockLanczos.{h,cxx}    one band by block Lanczos with thick restarts (default)
//   SpectraBand.{h,cxx}     one band by Spectra's implicitly restarted Lanczos
//   LanczosKernels.{h,cxx}  M-orthonormalization, Rayleigh-Ritz, in-place block products
//   Factorization.{h,cxx}   the LDL^T factorizations of L - sigma M, inertia counts
//   Verification.{h,cxx}    residual tests of bands and of the result
//
// This file also scales a diagonal mass away before the iteration and normalizes the signs.
#include "Solver/EigenSolver.h"
#include "Common/Threads.h"
#include "Solver/Bands.h"
#include "Solver/BlockProducts.h"
#include "Solver/Diagnostics.h"
#include "Solver/MassMatrix.h"
#include "Solver/Verification.h"

#include <Eigen/Dense>

#include <cmath>
#include <string>

namespace spectral
{
namespace
{
using detail::Clock;
using detail::SecondsSince;

/// Whether M is diagonal with positive finite entries (a lumped mass).
bool IsPositiveDiagonal(const SparseMatrix& M)
{
  Eigen::Index diagonal = 0;
  for (Eigen::Index j = 0; j < M.outerSize(); ++j)
  {
    for (SparseMatrix::InnerIterator it(M, j); it; ++it)
    {
      if (it.row() != it.col())
      {
        if (it.value() != 0.0)
        {
          return false;
        }
      }
      else if (it.value() > 0.0 && std::isfinite(it.value()))
      {
        ++diagonal;
      }
      else
      {
        return false;
      }
    }
  }
  return diagonal == M.rows();
}

/// Phi <- diag(scaling) Phi, a row range per thread.
void ScaleRows(DenseMatrix& Phi, const Vector& scaling)
{
  ForEachRowRange(Phi.rows(),
    BlockThreads(Phi.rows()),
    [&](int, Eigen::Index first, Eigen::Index count)
    {
      for (Eigen::Index k = 0; k < Phi.cols(); ++k)
      {
        Phi.col(k).segment(first, count).array() *= scaling.segment(first, count).array();
      }
    });
}

/// Make the entry of largest magnitude of every column positive.
void NormalizeSigns(DenseMatrix& Phi)
{
  for (Eigen::Index k = 0; k < Phi.cols(); ++k)
  {
    Eigen::Index row = 0;
    Phi.col(k).cwiseAbs().maxCoeff(&row);
    if (Phi(row, k) < 0.0)
    {
      Phi.col(k) *= -1.0;
    }
  }
}

/// All eigenpairs of the dense pencil, then the m smallest from index `first`.
EigenResult DenseEigenpairs(const SparseMatrix& L, const SparseMatrix& M, int first, int m)
{
  const DenseMatrix Ld(L);
  const DenseMatrix Md(M);
  Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> solver(Ld, Md);
  if (solver.info() != Eigen::Success)
  {
    throw SolverFailure("the dense generalized eigensolver failed (is the mass matrix positive "
                        "definite?)");
  }
  EigenResult result;
  result.Eigenvalues = solver.eigenvalues().segment(first, m);
  result.Eigenvectors = solver.eigenvectors().middleCols(first, m);
  return result;
}

/// The dense path: problems of at most DenseThreshold unknowns, or with m > n / 3.
EigenResult SolveDensely(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  const Monitor& monitor)
{
  const Eigen::Index n = L.rows();
  const int m = options.NumberOfEigenpairs;
  if (n > 20000)
  {
    throw InvalidInput("asking for " + std::to_string(options.StartIndex + m) + " eigenpairs of " +
      std::to_string(n) + " unknowns needs a dense solve; ask for at most n/3");
  }
  monitor.ThrowIfCancelled();
  const Clock::time_point start = Clock::now();
  EigenResult result = DenseEigenpairs(L, M, options.StartIndex, m);
  result.Seconds.RayleighRitz = SecondsSince(start);
  return result;
}

/// The band-by-band iteration (Bands.h), on the standard problem when M is a lumped mass.
EigenResult SolveByBands(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  const Monitor& monitor)
{
  const Eigen::Index n = L.rows();
  const double area = M.sum();
  if (!IsPositiveDiagonal(M))
  {
    const detail::RetirePairs retire =
      [&](const Vector& values, const DenseMatrix& vectors, int first, EigenResult& result)
    { detail::CheckSomeResiduals(L, M, options, values, vectors, first, result); };
    return detail::BandEigenpairs(
      L, detail::MassMatrix{ M, false }, area, options, monitor, retire);
  }
  // Q h = lambda D h with a diagonal D is the standard problem S y = lambda y with
  // S = D^-1/2 Q D^-1/2 and y = D^1/2 h: the same eigenvalues, the same inertia of every
  // shifted matrix (a congruence), and the D inner product of the iteration becomes the
  // Euclidean one, which saves a sparse product with D for every product of the iteration.
  const Vector scaling = M.diagonal().cwiseSqrt().cwiseInverse();
  const SparseMatrix S = scaling.asDiagonal() * L * scaling.asDiagonal();
  SparseMatrix identity(n, n);
  identity.setIdentity();
  // Pairs let go without options.KeepEigenvectors are verified as harmonics h = D^-1/2 y, on
  // the caller's pencil, as the final check verifies the pairs that are kept.
  const detail::RetirePairs retire =
    [&](const Vector& values, const DenseMatrix& vectors, int first, EigenResult& result)
  {
    DenseMatrix harmonics = vectors;
    ScaleRows(harmonics, scaling);
    detail::CheckSomeResiduals(L, M, options, values, harmonics, first, result);
  };
  EigenResult result =
    detail::BandEigenpairs(S, detail::MassMatrix{ identity, true }, area, options, monitor, retire);
  ScaleRows(result.Eigenvectors, scaling);
  return result;
}
} // namespace

//------------------------------------------------------------------------------
EigenResult SmallestEigenpairs(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  const Monitor& monitor)
{
  // Every part of the solve that is asked for 0 threads uses options.Threads.
  const ScopedThreadLimit threads(options.Threads);
  const Eigen::Index n = L.rows();
  const int m = options.NumberOfEigenpairs;
  if (L.cols() != n || M.rows() != n || M.cols() != n)
  {
    throw InvalidInput("the stiffness and mass matrices must be square and of the same size");
  }
  if (options.StartIndex < 0 || (options.StartIndex > 0 && !(options.StartValue > 0.0)))
  {
    throw InvalidInput("the pairs must start at a positive StartValue with StartIndex >= 0");
  }
  const Eigen::Index wanted = static_cast<Eigen::Index>(options.StartIndex) + m;
  if (m < 1 || wanted > n)
  {
    throw InvalidInput("cannot compute " + std::to_string(m) + " eigenpairs from index " +
      std::to_string(options.StartIndex) + " of a problem with " + std::to_string(n) +
      " unknowns: ask for 1 to " + std::to_string(n - options.StartIndex));
  }
  monitor.Report(0.0);
  const bool dense = n <= options.DenseThreshold || 3 * wanted > n;
  EigenResult result =
    dense ? SolveDensely(L, M, options, monitor) : SolveByBands(L, M, options, monitor);
  if (dense || options.KeepEigenvectors)
  {
    NormalizeSigns(result.Eigenvectors);
    detail::CheckResiduals(L, M, options, result);
  }
  if (!options.KeepEigenvectors)
  {
    // The band path verified its pairs as it let them go.
    result.Eigenvectors.resize(0, 0);
  }
  monitor.Report(1.0);
  return result;
}
} // namespace spectral
