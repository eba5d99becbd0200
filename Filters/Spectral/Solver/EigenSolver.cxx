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
//   Acceptance.{h,cxx}      accept / relax / fail, the sign rule, the Gram check
//
// This file also scales a diagonal mass away before the iteration and normalizes the signs
// (Acceptance.h, NormalizeSigns).
#include "Solver/EigenSolver.h"
#include "Common/Threads.h"
#include "Solver/Acceptance.h"
#include "Solver/Bands.h"
#include "Solver/BlockProducts.h"
#include "Solver/Diagnostics.h"
#include "Solver/MassMatrix.h"
#include "Solver/Memory.h"
#include "Solver/Verification.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

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

/**
 * The shift c of InvertedEigenpairs: the smallest positive L_ii / M_ii, of the order of the
 * lowest eigenvalues of a debris component (at its regular corners) and of the top of a
 * regular mesh's spectrum; the trace ratio, or 1, where there is none.
 */
double InvertedShift(const SparseMatrix& L, const SparseMatrix& M)
{
  const Vector l = L.diagonal();
  const Vector d = M.diagonal();
  double shift = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < l.size(); ++i)
  {
    if (d[i] > 0.0 && l[i] > 0.0 && std::isfinite(l[i] / d[i]))
    {
      shift = std::min(shift, l[i] / d[i]);
    }
  }
  if (!std::isfinite(shift))
  {
    shift = d.sum() > 0.0 ? l.sum() / d.sum() : 0.0;
  }
  return shift > 0.0 && std::isfinite(shift) ? shift : 1.0;
}

/**
 * Pairs first .. first + m - 1 of the pencil solved inverted, M x = mu (L + c M) x:
 * lambda = 1/mu - c, h = x / sqrt(mu) (then h^T M h = mu x^T (L + c M) x = 1). False where
 * L + c M is not numerically positive definite. mu is known to eps / c, so lambda to about
 * eps (lambda + c)^2 / c: eps c below c, a relative eps lambda / c above.
 */
bool InvertedEigenpairs(const DenseMatrix& Ld,
  const DenseMatrix& Md,
  double shift,
  int first,
  int m,
  EigenResult& result)
{
  const Eigen::Index n = Ld.rows();
  const DenseMatrix shifted = Ld + shift * Md;
  Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> inverted(Md, shifted);
  if (inverted.info() != Eigen::Success || !(inverted.eigenvalues()[n - first - m] > 0.0))
  {
    return false;
  }
  result.Eigenvalues.resize(m);
  result.Eigenvectors.resize(n, m);
  for (int k = 0; k < m; ++k)
  {
    // Ascending lambda is descending mu.
    const Eigen::Index j = n - 1 - first - k;
    const double mu = inverted.eigenvalues()[j];
    result.Eigenvalues[k] = 1.0 / mu - shift;
    result.Eigenvectors.col(k) = inverted.eigenvectors().col(j) / std::sqrt(mu);
  }
  return true;
}

/**
 * Pairs first .. first + m - 1 of the plain pencil L h = lambda M h, its rows permuted by
 * `permutation` (identity: as given) and put back. False where M is not numerically positive
 * definite.
 */
bool PlainEigenpairs(const DenseMatrix& Ld,
  const DenseMatrix& Md,
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>& permutation,
  int first,
  int m,
  EigenResult& result)
{
  Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> solver(
    permutation * Ld * permutation.transpose(), permutation * Md * permutation.transpose());
  if (solver.info() != Eigen::Success)
  {
    return false;
  }
  result.Eigenvalues = solver.eigenvalues().segment(first, m);
  result.Eigenvectors = permutation.transpose() * solver.eigenvectors().middleCols(first, m);
  return true;
}

/// The permutation that puts the rows in decreasing order of L_ii / M_ii.
Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> DecreasingRatio(const SparseMatrix& L,
  const SparseMatrix& M)
{
  const Vector ratio = L.diagonal().cwiseQuotient(M.diagonal());
  std::vector<int> order(static_cast<std::size_t>(ratio.size()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(
    order.begin(), order.end(), [&ratio](int a, int b) { return ratio[a] > ratio[b]; });
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation(ratio.size());
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    permutation.indices()[order[k]] = static_cast<int>(k);
  }
  return permutation;
}

/**
 * All eigenpairs of the dense pencil, then the m smallest from index `first`.
 *
 * A dense solver's eigenvalues carry an absolute error of about eps lambda_max, and on a
 * graded pencil more, depending on the order of the points: debris of a range scan holding a
 * near-coincident point (a triangle split 1-to-3 at 1e-8 of its size from a corner, alone:
 * eigenvalues spanning 1e17) came out with its smallest pairs wrong, even negative (backward
 * errors up to 0.9). Where a pair of the plain pencil misses `tolerance` (its componentwise
 * backward error, as the final check measures it), the pencil is also solved inverted
 * (InvertedEigenpairs, c = InvertedShift), which gets the smallest pairs of such debris to
 * round-off, and plain with its rows in decreasing order of L_ii / M_ii (a graded matrix is
 * reduced to tridiagonal form the more accurately the larger entries come first), which gets
 * its largest ones; each pair is taken from the solve with the smallest backward error.
 * Mixed, the pairs must stay ascending and M-orthonormal to `tolerance`; otherwise the solve
 * with the smallest worst error is kept.
 */
EigenResult DenseEigenpairs(const SparseMatrix& L,
  const SparseMatrix& M,
  int first,
  int m,
  double tolerance)
{
  const DenseMatrix Ld(L);
  const DenseMatrix Md(M);
  const Eigen::Index n = Ld.rows();
  std::vector<EigenResult> solves(1);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> identity(n);
  identity.setIdentity();
  if (!PlainEigenpairs(Ld, Md, identity, first, m, solves[0]))
  {
    throw SolverFailure("the dense generalized eigensolver failed (is the mass matrix positive "
                        "definite?)");
  }
  std::vector<Vector> errors = { BackwardErrors(
    L, M, solves[0].Eigenvalues, solves[0].Eigenvectors) };
  if (errors[0].maxCoeff() <= tolerance)
  {
    return solves[0];
  }
  EigenResult other;
  if (InvertedEigenpairs(Ld, Md, InvertedShift(L, M), first, m, other))
  {
    solves.push_back(other);
  }
  if (PlainEigenpairs(Ld, Md, DecreasingRatio(L, M), first, m, other))
  {
    solves.push_back(other);
  }
  std::size_t best = 0;
  for (std::size_t s = 1; s < solves.size(); ++s)
  {
    errors.push_back(BackwardErrors(L, M, solves[s].Eigenvalues, solves[s].Eigenvectors));
    best = errors[s].maxCoeff() < errors[best].maxCoeff() ? s : best;
  }
  EigenResult mixed = solves[0];
  bool ascending = true;
  for (int k = 0; k < m; ++k)
  {
    std::size_t from = 0;
    for (std::size_t s = 1; s < solves.size(); ++s)
    {
      from = errors[s][k] < errors[from][k] ? s : from;
    }
    mixed.Eigenvalues[k] = solves[from].Eigenvalues[k];
    mixed.Eigenvectors.col(k) = solves[from].Eigenvectors.col(k);
    ascending = ascending && (k == 0 || mixed.Eigenvalues[k] >= mixed.Eigenvalues[k - 1]);
  }
  if (ascending && OrthonormalityError(mixed.Eigenvectors, M) <= tolerance)
  {
    return mixed;
  }
  return solves[best];
}

/// The constant null vector of L (EigenOptions::ConstantNullSpace), M-normalized: 1 / sqrt(1^T M
/// 1).
Vector ConstantNullVector(const SparseMatrix& M)
{
  return Vector::Constant(M.rows(), 1.0 / std::sqrt(SumOfEntries(M)));
}

/**
 * The pairs of the pencil restricted to the M-orthogonal complement of z: (0, z), then the
 * m - 1 smallest of the complement.
 *
 * The complement {h : w^T h = 0}, w = M z, has the basis C of the columns e_i - (w_i / w_p) e_p,
 * i != p, with p the point of smallest sum_j |L_pj| / w_p (a large mass and small weights of
 * either sign, the most regular point): C^T L C and C^T M C add to each row i w_i / w_p times
 * row p, so the rows of tiny mass and huge weights (a scan's near-coincident points) stay
 * graded, and the dense solve (with its fallbacks for graded pencils) keeps much of its
 * accuracy on them. The pairs are h = C x.
 */
EigenResult ComplementEigenpairs(const SparseMatrix& L,
  const SparseMatrix& M,
  const Vector& z,
  int m,
  double tolerance)
{
  const Eigen::Index n = L.rows();
  const Vector w = M * z;
  const Vector weights = L.cwiseAbs() * Vector::Ones(n);
  Eigen::Index p = 0;
  (weights.array() / w.array()).minCoeff(&p);
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index i = 0, column = 0; i < n; ++i)
  {
    if (i != p)
    {
      entries.emplace_back(i, column, 1.0);
      entries.emplace_back(p, column++, -w[i] / w[p]);
    }
  }
  SparseMatrix C(n, n - 1);
  C.setFromTriplets(entries.begin(), entries.end());
  const SparseMatrix Lc = SparseMatrix(C.transpose() * L * C).pruned();
  const SparseMatrix Mc = SparseMatrix(C.transpose() * M * C).pruned();
  const EigenResult complement = DenseEigenpairs(Lc, Mc, 0, m - 1, tolerance);
  EigenResult result;
  result.Eigenvalues.resize(m);
  result.Eigenvalues << 0.0, complement.Eigenvalues;
  result.Eigenvectors.resize(n, m);
  result.Eigenvectors << z, C * complement.Eigenvectors;
  return result;
}

/**
 * DenseEigenpairs with the constant null vector z deflated: the m smallest pairs, (0, z) first,
 * then the m - 1 smallest of the pencil in the M-orthogonal complement of z.
 *
 * The dense solve computes every pair, so the complement is the span of the pairs but the
 * lowest, whose eigenvector v_0 differs from z by the rounding of L (L z = 0 but for the
 * rounding of its row sums): the m - 1 pairs above it, each made M-orthogonal to z (h - z z^T M h,
 * normalized), are the complement's pairs up to ||z - v_0||_M, with the accuracy the dense solve
 * and its fallbacks for graded pencils had on them. Where that costs a pair its backward error
 * (a scan's debris, whose rounded operators move v_0 far from z), the pencil restricted to the
 * complement is solved instead (ComplementEigenpairs), and the set with the smaller worst
 * backward error is kept; the final check measures it.
 */
EigenResult DeflatedDenseEigenpairs(const SparseMatrix& L,
  const SparseMatrix& M,
  int m,
  const EigenOptions& options)
{
  const Vector z = ConstantNullVector(M);
  EigenResult projected = DenseEigenpairs(L, M, 0, m, options.BackwardErrorTolerance);
  projected.Eigenvalues[0] = 0.0;
  projected.Eigenvectors.col(0) = z;
  if (m == 1)
  {
    return projected;
  }
  // One product of BlockProducts.h for all the columns: sums in an order that does not depend
  // on where the vectors lie in memory, so the solve repeats its result to the last bit.
  auto others = projected.Eigenvectors.rightCols(m - 1);
  SubtractProduct(others, z, TransposeProduct(M * z, others));
  const DenseMatrix massOthers = M * others;
  for (int k = 0; k < m - 1; ++k)
  {
    others.col(k) /= std::sqrt(TransposeProduct(others.col(k), massOthers.col(k))(0, 0));
  }
  const double worst =
    BackwardErrors(L, M, projected.Eigenvalues, projected.Eigenvectors).maxCoeff();
  if (worst <= options.BackwardErrorTolerance)
  {
    return projected;
  }
  EigenResult restricted = ComplementEigenpairs(L, M, z, m, options.BackwardErrorTolerance);
  const double other =
    BackwardErrors(L, M, restricted.Eigenvalues, restricted.Eigenvectors).maxCoeff();
  return other < worst ? restricted : projected;
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
  EigenResult result = options.ConstantNullSpace && options.StartIndex == 0
    ? DeflatedDenseEigenpairs(L, M, m, options)
    : DenseEigenpairs(L, M, options.StartIndex, m, options.BackwardErrorTolerance);
  result.Seconds.RayleighRitz = SecondsSince(start);
  return result;
}

/**
 * EigenOptions::Deliver of the pairs (values, harmonics) whose first is pair `first`: those of
 * index < m, with the constant null pair exact and the signs of the returned result.
 */
void Deliver(const SparseMatrix& M,
  const EigenOptions& options,
  const Vector& values,
  DenseMatrix harmonics,
  int first)
{
  const int count =
    std::min<int>(static_cast<int>(values.size()), options.NumberOfEigenpairs - first);
  if (!options.Deliver || count <= 0)
  {
    return;
  }
  Vector lambda = values.head(count);
  if (harmonics.cols() > count)
  {
    harmonics.conservativeResize(Eigen::NoChange, count);
  }
  if (first == 0 && options.ConstantNullSpace && options.StartIndex == 0)
  {
    lambda[0] = 0.0;
    harmonics.col(0) = ConstantNullVector(M);
  }
  NormalizeSigns(harmonics);
  options.Deliver(first, lambda, harmonics);
}

/**
 * What a solve without KeepEigenvectors does with the pairs it lets go (detail::RetirePairs):
 * verifies them as harmonics of the caller's pencil, as the final check verifies kept pairs,
 * and delivers them (EigenOptions::Deliver), StreamedBlockColumns at a time (Memory.h), so that
 * the harmonics of a whole retired block (up to three bands) are never copied at once.
 * `scaling` (empty: none) turns the loop's vectors into harmonics, h = diag(scaling) y.
 */
void RetireInColumns(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  const Vector& scaling,
  const Vector& values,
  const Eigen::Ref<const DenseMatrix>& vectors,
  int first,
  EigenResult& result)
{
  for (Eigen::Index start = 0; start < values.size(); start += StreamedBlockColumns)
  {
    const Eigen::Index count = std::min<Eigen::Index>(StreamedBlockColumns, values.size() - start);
    DenseMatrix harmonics = vectors.middleCols(start, count);
    if (scaling.size() > 0)
    {
      ScaleRows(harmonics, scaling);
    }
    const Vector part = values.segment(start, count);
    const int index = first + static_cast<int>(start);
    detail::CheckSomeResiduals(L, M, options, part, harmonics, index, result);
    Deliver(M, options, part, std::move(harmonics), index);
  }
}

/// The band-by-band iteration (Bands.h), on the standard problem when M is a lumped mass.
EigenResult SolveByBands(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  const Monitor& monitor)
{
  const Eigen::Index n = L.rows();
  const double area = SumOfEntries(M);
  // The null vector in the iteration's pencil (EigenOptions::ConstantNullSpace): the bands work
  // in its M-orthogonal complement.
  DenseMatrix nulls;
  if (options.ConstantNullSpace)
  {
    nulls = ConstantNullVector(M);
  }
  const DenseMatrix* deflation = options.ConstantNullSpace ? &nulls : nullptr;
  if (!IsPositiveDiagonal(M))
  {
    const detail::RetirePairs retire = [&](const Vector& values,
                                         const Eigen::Ref<const DenseMatrix>& vectors,
                                         int first,
                                         EigenResult& result)
    { RetireInColumns(L, M, options, Vector(), values, vectors, first, result); };
    return detail::BandEigenpairs(
      L, detail::MassMatrix{ M, false, deflation }, area, options, monitor, retire);
  }
  // Q h = lambda D h with a diagonal D is the standard problem S y = lambda y with
  // S = D^-1/2 Q D^-1/2 and y = D^1/2 h: the same eigenvalues, the same inertia of every
  // shifted matrix (a congruence), and the D inner product of the iteration becomes the
  // Euclidean one, which saves a sparse product with D for every product of the iteration.
  const Vector scaling = M.diagonal().cwiseSqrt().cwiseInverse();
  const SparseMatrix S = scaling.asDiagonal() * L * scaling.asDiagonal();
  if (deflation)
  {
    // y = D^1/2 h: the constant becomes D^1/2 1 / sqrt(1^T D 1).
    nulls = M.diagonal().cwiseSqrt() / std::sqrt(area);
  }
  SparseMatrix identity(n, n);
  identity.setIdentity();
  // Pairs let go without options.KeepEigenvectors are verified as harmonics h = D^-1/2 y, on
  // the caller's pencil, as the final check verifies the pairs that are kept.
  const detail::RetirePairs retire = [&](const Vector& values,
                                       const Eigen::Ref<const DenseMatrix>& vectors,
                                       int first,
                                       EigenResult& result)
  { RetireInColumns(L, M, options, scaling, values, vectors, first, result); };
  EigenResult result = detail::BandEigenpairs(
    S, detail::MassMatrix{ identity, true, deflation }, area, options, monitor, retire);
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
  if (options.ConstantNullSpace && options.StartIndex == 0)
  {
    // The null pair exactly, whatever the rounding of a scaling left in its vector.
    result.Eigenvalues[0] = 0.0;
    if (result.Eigenvectors.cols() > 0)
    {
      result.Eigenvectors.col(0) = ConstantNullVector(M);
    }
  }
  if (dense || options.KeepEigenvectors)
  {
    NormalizeSigns(result.Eigenvectors);
    detail::CheckResiduals(L, M, options, result);
  }
  if (!options.KeepEigenvectors)
  {
    if (dense)
    {
      Deliver(M, options, result.Eigenvalues, std::move(result.Eigenvectors), 0);
    }
    // The band path verified its pairs as it let them go.
    result.Eigenvectors.resize(0, 0);
  }
  result.ResidualTolerance = options.ResidualTolerance;
  monitor.Report(1.0);
  return result;
}
} // namespace spectral
