// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/Verification.h"
#include "Common/Eigenvalues.h"
#include "Common/Threads.h"
#include "Solver/BlockProducts.h"
#include "Solver/Diagnostics.h"

#include <limits>
#include <sstream>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace spectral
{
//------------------------------------------------------------------------------
double ResidualReference(const Vector& lambda, double traceRatio)
{
  const double top = lambda.size() ? lambda.cwiseAbs().maxCoeff() : 0.0;
  double reference = top;
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
  {
    if (!IsZeroEigenvalue(std::abs(lambda[k]), top))
    {
      reference = std::min(reference, std::abs(lambda[k]));
    }
  }
  // Without a non-zero eigenvalue among the pairs (m = 1, or only the constants of components),
  // fall back to a small fraction of the operator's scale, the ratio of the traces.
  return std::max(reference, 1e-6 * traceRatio);
}

namespace detail
{
namespace
{
//------------------------------------------------------------------------------
// The componentwise backward error of pair k of a BackwardScale, given its residual r.
double BackwardErrorOfColumn(const Vector& r,
  const BackwardScale& backward,
  Eigen::Index k,
  double lambda)
{
  const Vector absX = backward.X->col(k).cwiseAbs();
  const Vector absLx = *backward.AbsL * absX;
  return backward.AbsM ? ComponentwiseBackwardError(r, absLx, *backward.AbsM * absX, lambda)
                       : ComponentwiseBackwardError(r, absLx, absX, lambda);
}
} // namespace

//------------------------------------------------------------------------------
int Verify(const Eigen::Ref<const DenseMatrix>& AX,
  const Eigen::Ref<const DenseMatrix>& MX,
  const Vector& shifted,
  const Vector& inverseMass,
  double sigma,
  double reference,
  double tolerance,
  std::vector<Eigen::Index>& nearest,
  const BackwardScale& backward)
{
  const Eigen::Index count = shifted.size();
  nearest.resize(static_cast<std::size_t>(count));
  for (Eigen::Index i = 0; i < count; ++i)
  {
    nearest[static_cast<std::size_t>(i)] = i;
  }
  std::sort(nearest.begin(),
    nearest.end(),
    [&shifted](Eigen::Index a, Eigen::Index c)
    { return std::abs(shifted[a]) < std::abs(shifted[c]); });
  int verified = 0;
  while (verified < count)
  {
    const Eigen::Index k = nearest[static_cast<std::size_t>(verified)];
    const double lambda = sigma + shifted[k];
    const Vector r = AX.col(k) - shifted[k] * MX.col(k);
    const double residual = std::sqrt(r.cwiseAbs2().dot(inverseMass));
    if (residual > tolerance * std::max(std::abs(lambda), reference) &&
      !(backward.AbsL && BackwardErrorOfColumn(r, backward, k, lambda) <= backward.Tolerance))
    {
      break;
    }
    ++verified;
  }
  return verified;
}

//------------------------------------------------------------------------------
double ScaledBackwardError(const Eigen::Ref<const Vector>& r,
  const Eigen::Ref<const Vector>& scale,
  double largest)
{
  const double floor = BackwardErrorFloor * largest;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < r.size(); ++i)
  {
    const double error = std::abs(r[i]);
    if (error > 0.0)
    {
      const double denominator = std::max(scale[i], floor);
      worst = std::max(
        worst, denominator > 0.0 ? error / denominator : std::numeric_limits<double>::infinity());
    }
  }
  return worst;
}

//------------------------------------------------------------------------------
double ComponentwiseBackwardError(const Eigen::Ref<const Vector>& r,
  const Eigen::Ref<const Vector>& absLx,
  const Eigen::Ref<const Vector>& absMx,
  double lambda)
{
  const Vector scale = absLx + std::abs(lambda) * absMx;
  return ScaledBackwardError(r, scale, scale.size() ? scale.maxCoeff() : 0.0);
}

//------------------------------------------------------------------------------
void CheckResiduals(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  EigenResult& result)
{
  result.MaxResidual = 0.0;
  result.MaxBackwardError = 0.0;
  CheckSomeResiduals(L, M, options, result.Eigenvalues, result.Eigenvectors, 0, result);
}

//------------------------------------------------------------------------------
void CheckSomeResiduals(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  const Vector& lambda,
  const DenseMatrix& Phi,
  int first,
  EigenResult& result)
{
  const Clock::time_point start = Clock::now();
  const PairFigures figures = ResidualFigures(L, M, lambda, Phi, true);
  const Vector& residuals = figures.Relative;
  const Vector& backward = figures.Backward;
  if (residuals.size() > 0)
  {
    result.MaxResidual = std::max(result.MaxResidual, residuals.maxCoeff());
    result.MaxBackwardError = std::max(result.MaxBackwardError, backward.maxCoeff());
  }
  result.Seconds.Verification += SecondsSince(start);
  const PairTolerances tolerances = { options.ResidualTolerance, options.BackwardErrorTolerance };
  const int k = FirstFailingPair(residuals, backward, tolerances);
  if (k >= 0)
  {
    throw SolverFailure(
      PairFailure(first + k, lambda[k], residuals[k], backward[k], tolerances), first + k);
  }
}

//------------------------------------------------------------------------------
PairFigures ResidualFigures(const SparseMatrix& L,
  const SparseMatrix& M,
  const Vector& lambda,
  const DenseMatrix& Phi,
  bool backward)
{
  const Vector rowSums = M * Vector::Ones(M.cols());
  const Vector inverseMass = rowSums.cwiseInverse();
  const double reference =
    ResidualReference(lambda, L.diagonal().sum() / std::max(rowSums.sum(), 1e-300));
  const SparseMatrix absL = backward ? SparseMatrix(L.cwiseAbs()) : SparseMatrix();
  const SparseMatrix absM = backward ? SparseMatrix(M.cwiseAbs()) : SparseMatrix();
  // A block of columns at a time: the residuals of all m pairs at once would take twice the
  // memory of the basis. The threads take a range of columns each (the sparse products are
  // single-threaded), each with its own blocks (five n x 8 matrices: 320 bytes a row, where
  // blocks of 32 took 13 MB of a 10,000-point streamed solve's 61 MB estimate); no more threads
  // than one per 128 columns (their blocks then hold at most a third of the basis's memory), but
  // two from 64 columns on (at 100 harmonics on the 10,000-point torus of the benchmark the check
  // took 0.033 s on one thread, 0.020 s on two).
  PairFigures out;
  out.Relative.resize(lambda.size());
  out.Backward.resize(backward ? lambda.size() : 0);
  const Eigen::Index block = 8;
  const int parts = static_cast<int>(std::max<Eigen::Index>(1,
    std::min<Eigen::Index>(BlockThreads(Phi.rows()),
      std::max<Eigen::Index>(lambda.size() / 128, std::min<Eigen::Index>(2, lambda.size() / 32)))));
  ForEachRowRange(lambda.size(),
    parts,
    [&](int, Eigen::Index begin, Eigen::Index columns)
    {
      DenseMatrix R(Phi.rows(), std::min(block, columns));
      DenseMatrix MPhi(Phi.rows(), R.cols());
      DenseMatrix absLX;
      DenseMatrix absMX;
      for (Eigen::Index first = begin; first < begin + columns; first += block)
      {
        const Eigen::Index count = std::min(block, begin + columns - first);
        const auto part = Phi.middleCols(first, count);
        R.leftCols(count).noalias() = L * part;
        MPhi.leftCols(count).noalias() = M * part;
        R.leftCols(count) -= MPhi.leftCols(count) * lambda.segment(first, count).asDiagonal();
        if (backward)
        {
          const DenseMatrix absPart = part.cwiseAbs();
          absLX.noalias() = absL * absPart;
          absMX.noalias() = absM * absPart;
        }
        for (Eigen::Index j = 0; j < count; ++j)
        {
          const Eigen::Index k = first + j;
          const double norm = std::sqrt(R.col(j).cwiseAbs2().dot(inverseMass));
          out.Relative[k] =
            norm / std::max({ std::abs(lambda[k]), reference, std::numeric_limits<double>::min() });
          if (backward)
          {
            out.Backward[k] =
              ComponentwiseBackwardError(R.col(j), absLX.col(j), absMX.col(j), lambda[k]);
          }
        }
      }
    });
  return out;
}
} // namespace detail

//------------------------------------------------------------------------------
Vector RelativeResiduals(const SparseMatrix& L,
  const SparseMatrix& M,
  const Vector& lambda,
  const DenseMatrix& Phi)
{
  return detail::ResidualFigures(L, M, lambda, Phi, false).Relative;
}

//------------------------------------------------------------------------------
Vector BackwardErrors(const SparseMatrix& L,
  const SparseMatrix& M,
  const Vector& lambda,
  const DenseMatrix& Phi)
{
  return detail::ResidualFigures(L, M, lambda, Phi, true).Backward;
}

//------------------------------------------------------------------------------
double OrthonormalityError(const DenseMatrix& Phi, const SparseMatrix& M)
{
  // M Phi a block of columns at a time, not a second copy of the basis.
  DenseMatrix G(Phi.cols(), Phi.cols());
  const Eigen::Index block = 64;
  for (Eigen::Index first = 0; first < Phi.cols(); first += block)
  {
    const Eigen::Index count = std::min(block, Phi.cols() - first);
    G.middleCols(first, count).noalias() = Phi.transpose() * (M * Phi.middleCols(first, count));
  }
  return GramError(G);
}
} // namespace spectral
