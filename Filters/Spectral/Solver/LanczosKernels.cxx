// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/LanczosKernels.h"
#include "Common/Threads.h"
#include "Solver/BlockProducts.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace spectral
{
namespace detail
{
namespace
{
/// out = X Z for a tall X, rows on BlockThreads threads; out does not overlap X.
void MultiplyInto(Eigen::Ref<DenseMatrix> out,
  const Eigen::Ref<const DenseMatrix>& X,
  const DenseMatrix& Z)
{
  ForEachRowRange(X.rows(),
    BlockThreads(X.rows()),
    [&](int, Eigen::Index first, Eigen::Index count)
    { out.middleRows(first, count).noalias() = X.middleRows(first, count) * Z; });
}

/**
 * Replace the columns `deficient` of W by random vectors M-orthogonal to Basis, to W and to the
 * null vectors of M.Deflation (two passes of classical Gram-Schmidt), M-normalized.
 */
void ReplaceDeficient(DenseMatrix& W,
  const MassMatrix& M,
  const Eigen::Ref<const DenseMatrix>& Basis,
  const std::vector<Eigen::Index>& deficient,
  std::mt19937& generator)
{
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  for (const Eigen::Index i : deficient)
  {
    Vector v(W.rows());
    for (Eigen::Index r = 0; r < v.size(); ++r)
    {
      v[r] = uniform(generator);
    }
    for (int again = 0; again < 2; ++again)
    {
      Eigen::Map<DenseMatrix> column(v.data(), v.size(), 1);
      M.Deflate(column);
      v -= Basis * (Basis.transpose() * (M.Matrix * v));
      v -= W * (W.transpose() * (M.Matrix * v));
    }
    W.col(i) = v / std::sqrt(v.dot(M.Matrix * v));
  }
}
} // namespace

//------------------------------------------------------------------------------
void MultiplyInPlace(Eigen::Ref<DenseMatrix> X, const DenseMatrix& Z, DenseMatrix* gram)
{
  const Eigen::Index chunk = 256;
  const int parts = BlockThreads(X.rows());
  std::vector<DenseMatrix> partial(static_cast<std::size_t>(parts));
  ForEachRowRange(X.rows(),
    parts,
    [&](int part, Eigen::Index first, Eigen::Index count)
    {
      DenseMatrix rows(std::min(chunk, count), Z.cols());
      if (gram)
      {
        partial[static_cast<std::size_t>(part)] = DenseMatrix::Zero(Z.cols(), Z.cols());
      }
      for (Eigen::Index r = first; r < first + count; r += chunk)
      {
        const Eigen::Index h = std::min(chunk, first + count - r);
        rows.topRows(h).noalias() = X.block(r, 0, h, Z.rows()) * Z;
        X.block(r, 0, h, Z.cols()) = rows.topRows(h);
        if (gram)
        {
          partial[static_cast<std::size_t>(part)].noalias() +=
            rows.topRows(h).transpose() * rows.topRows(h);
        }
      }
    });
  if (gram)
  {
    // The partial Gram matrices added in range order: the same sum for any thread count with
    // the same ranges.
    *gram = partial[0];
    for (std::size_t part = 1; part < partial.size(); ++part)
    {
      if (partial[part].size())
      {
        *gram += partial[part];
      }
    }
  }
}

//------------------------------------------------------------------------------
DenseMatrix Project(DenseMatrix& W, const Eigen::Ref<const DenseMatrix>& B, const MassMatrix& M)
{
  DenseMatrix scratch;
  const DenseMatrix C = TransposeProduct(B, M.Times(W, scratch));
  SubtractProduct(W, B, C);
  return C;
}

//------------------------------------------------------------------------------
DenseMatrix MassGram(const DenseMatrix& W, const MassMatrix& M)
{
  DenseMatrix scratch;
  return TransposeProduct(W, M.Times(W, scratch));
}

//------------------------------------------------------------------------------
Vector MassNorms(const DenseMatrix& W, const MassMatrix& M)
{
  if (M.Identity)
  {
    return W.colwise().squaredNorm().transpose();
  }
  return W.cwiseProduct(M.Matrix * W).colwise().sum().transpose();
}

//------------------------------------------------------------------------------
DenseMatrix Orthonormalize(DenseMatrix& W,
  const MassMatrix& M,
  const Eigen::Ref<const DenseMatrix>& Basis,
  double floor,
  std::mt19937& generator,
  DenseMatrix gram,
  Eigen::Ref<DenseMatrix>* out)
{
  const Eigen::Index b = W.cols();
  DenseMatrix R = DenseMatrix::Identity(b, b);
  for (int pass = 0; pass < 2; ++pass)
  {
    DenseMatrix G = gram.size() ? gram : MassGram(W, M);
    gram.resize(0, 0);
    G = 0.5 * (G + G.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<DenseMatrix> decomposition(G);
    const Vector& g = decomposition.eigenvalues();
    const DenseMatrix& U = decomposition.eigenvectors();
    DenseMatrix S = DenseMatrix::Zero(b, b);
    DenseMatrix Rpass = DenseMatrix::Zero(b, b);
    std::vector<Eigen::Index> deficient;
    for (Eigen::Index i = 0; i < b; ++i)
    {
      if (g[i] > floor)
      {
        S.col(i) = U.col(i) / std::sqrt(g[i]);
        Rpass.row(i) = std::sqrt(g[i]) * U.col(i).transpose();
      }
      else
      {
        deficient.push_back(i);
      }
    }
    R = (Rpass * R).eval();
    if (deficient.empty() && pass == 1 && out)
    {
      MultiplyInto(*out, W, S);
      return R;
    }
    MultiplyInPlace(W, S, deficient.empty() && pass == 0 && M.Identity ? &gram : nullptr);
    ReplaceDeficient(W, M, Basis, deficient, generator);
  }
  if (out)
  {
    *out = W;
  }
  return R;
}

//------------------------------------------------------------------------------
Vector RayleighRitz(Eigen::Ref<DenseMatrix> X, Eigen::Ref<DenseMatrix> AX, DenseMatrix* MX)
{
  DenseMatrix S = TransposeProduct(X, AX);
  DenseMatrix G = MX ? TransposeProduct(X, *MX) : TransposeProduct(X, X);
  S = 0.5 * (S + S.transpose()).eval();
  G = 0.5 * (G + G.transpose()).eval();
  Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> pencil(S, G);
  if (pencil.info() != Eigen::Success)
  {
    throw SolverFailure("the Ritz vectors of a band are not linearly independent");
  }
  const DenseMatrix& Z = pencil.eigenvectors();
  MultiplyInPlace(X, Z);
  MultiplyInPlace(AX, Z);
  if (MX)
  {
    MultiplyInPlace(*MX, Z);
  }
  return pencil.eigenvalues();
}

//------------------------------------------------------------------------------
Vector RayleighQuotients(const Eigen::Ref<const DenseMatrix>& X,
  const Eigen::Ref<const DenseMatrix>& AX,
  const Eigen::Ref<const DenseMatrix>& MX)
{
  Vector out(X.cols());
  for (Eigen::Index k = 0; k < X.cols(); ++k)
  {
    out[k] = X.col(k).dot(AX.col(k)) / X.col(k).dot(MX.col(k));
  }
  return out;
}
} // namespace detail
} // namespace spectral
