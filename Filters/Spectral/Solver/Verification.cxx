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
#include <vector>

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
/// Eight columns of a block, one row of them (BlockProducts.h): one AVX-512 register.
constexpr int BlockWidth = 8;
using BlockRow = Row<BlockWidth>;
using BlockRows = Rows<BlockWidth>;

/**
 * out[i] += sum_k A(i, k) x[k] and, with absOut, absOut[i] += sum_k |A(i, k)| |x[k]|, for the
 * rows x[k] of up to 8 columns, in one pass over a compressed column-major A (any pattern: each
 * column k adds its entries times the row x[k], the order in which Eigen's sparse-dense product
 * adds them). Eigen's product handles one column of x at a time and reads A once for each,
 * twice more for |A| |x|: the final check of 500 pairs on the 100,045-point torus took 1.0 s.
 */
void AddSparseProduct(const SparseMatrix& A, const BlockRows& x, BlockRows& out, BlockRows* absOut)
{
  const int* start = A.outerIndexPtr();
  const int* index = A.innerIndexPtr();
  const double* value = A.valuePtr();
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
  {
    const BlockRow& xk = x[static_cast<std::size_t>(k)];
    const BlockRow absXk = xk.cwiseAbs();
    for (int p = start[k]; p < start[k + 1]; ++p)
    {
      const std::size_t i = static_cast<std::size_t>(index[p]);
      out[i] += value[p] * xk;
      if (absOut)
      {
        (*absOut)[i] += std::abs(value[p]) * absXk;
      }
    }
  }
}

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
  // AddSparseProduct reads compressed storage; the solver's matrices are.
  const auto compressed = [](const SparseMatrix& S)
  {
    SparseMatrix copy = S;
    copy.makeCompressed();
    return copy;
  };
  const SparseMatrix copyL = L.isCompressed() ? SparseMatrix() : compressed(L);
  const SparseMatrix copyM = M.isCompressed() ? SparseMatrix() : compressed(M);
  const SparseMatrix& A = L.isCompressed() ? L : copyL;
  const SparseMatrix& B = M.isCompressed() ? M : copyM;
  // A block of 8 columns at a time: the residuals of all m pairs at once would take twice the
  // memory of the basis. The threads take a range of columns each, each with its own blocks
  // (five n x 8 blocks: 320 bytes a row, where blocks of 32 took 13 MB of a
  // 10,000-point streamed solve's 61 MB estimate); no more threads than one per 128 columns
  // (their blocks then hold at most a third of the basis's memory), but two from 64 columns on
  // (at 100 harmonics on the 10,000-point torus of the benchmark the check took 0.033 s on one
  // thread, 0.020 s on two).
  PairFigures out;
  out.Relative.resize(lambda.size());
  out.Backward.resize(backward ? lambda.size() : 0);
  constexpr Eigen::Index block = BlockWidth;
  const int parts = static_cast<int>(std::max<Eigen::Index>(1,
    std::min<Eigen::Index>(BlockThreads(Phi.rows()),
      std::max<Eigen::Index>(lambda.size() / 128, std::min<Eigen::Index>(2, lambda.size() / 32)))));
  const std::size_t n = static_cast<std::size_t>(Phi.rows());
  ForEachRowRange(lambda.size(),
    parts,
    [&](int, Eigen::Index begin, Eigen::Index columns)
    {
      BlockRows X(n);
      BlockRows LX(n);
      BlockRows MX(n);
      BlockRows absLX(backward ? n : 0);
      BlockRows absMX(backward ? n : 0);
      // Column-major n x 8 views of blocks no longer needed once the products are done: the
      // residuals in X's storage, |L| |x| and |M| |x| in LX's and MX's.
      const auto columnsOf = [n](BlockRows& rows, Eigen::Index count)
      { return Eigen::Map<DenseMatrix>(rows.data()->data(), static_cast<Eigen::Index>(n), count); };
      for (Eigen::Index first = begin; first < begin + columns; first += block)
      {
        const Eigen::Index count = std::min(block, begin + columns - first);
        std::fill(X.begin(), X.end(), BlockRow::Zero());
        CopyIn<BlockWidth>(Phi.middleCols(first, count), X.data());
        std::fill(LX.begin(), LX.end(), BlockRow::Zero());
        std::fill(MX.begin(), MX.end(), BlockRow::Zero());
        std::fill(absLX.begin(), absLX.end(), BlockRow::Zero());
        std::fill(absMX.begin(), absMX.end(), BlockRow::Zero());
        AddSparseProduct(A, X, LX, backward ? &absLX : nullptr);
        AddSparseProduct(B, X, MX, backward ? &absMX : nullptr);
        BlockRow lanes = BlockRow::Zero();
        lanes.head(count) = lambda.segment(first, count);
        for (std::size_t i = 0; i < n; ++i)
        {
          LX[i] -= lanes.cwiseProduct(MX[i]);
        }
        auto R = columnsOf(X, count);
        CopyOut<BlockWidth>(LX.data(), R);
        auto absLx = columnsOf(LX, count);
        auto absMx = columnsOf(MX, count);
        if (backward)
        {
          CopyOut<BlockWidth>(absLX.data(), absLx);
          CopyOut<BlockWidth>(absMX.data(), absMx);
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
              ComponentwiseBackwardError(R.col(j), absLx.col(j), absMx.col(j), lambda[k]);
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
