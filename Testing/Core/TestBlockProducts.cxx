// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Properties of the narrow block products (Filters/Spectral/Solver/BlockProducts.h): they equal the
// general products B^T A and A - B C for every width, for bases that are the leading columns of a
// larger matrix, on one thread and on two; projecting a block out of an orthonormal basis
// leaves it orthogonal to the basis; the symmetric sparse product equals Eigen's; and 2, 4 and 8
// threads give the results of one.
#include "Checks.h"
#include "Common/Threads.h"
#include "Solver/BlockProducts.h"

#include <Eigen/Dense>

#include <Eigen/Sparse>

#include <cmath>
#include <string>
#include <vector>

using namespace spectral;
using namespace spectral::testing;

namespace
{
/// A fixed pseudo-random n x count matrix (the same on every run).
DenseMatrix Fixed(Eigen::Index n, Eigen::Index count, double seed)
{
  DenseMatrix A(n, count);
  for (Eigen::Index j = 0; j < count; ++j)
  {
    for (Eigen::Index i = 0; i < n; ++i)
    {
      A(i, j) = std::sin(seed * static_cast<double>(i + 1) + 0.71 * static_cast<double>(j + 1));
    }
  }
  return A;
}

//------------------------------------------------------------------------------
void MatchGeneralProducts()
{
  // Row counts below and above the two-thread threshold (8192) and across several chunks of
  // 2048 rows; basis widths below the kernels' threshold (96 columns, general product) and above
  // it with remainders for every grouping of columns (103 = 12 x 8 + 4 + 2 + 1, 134 = 16 x 8 + 4
  // + 2); block widths 1 to 16 (padded to 4, 8 or 16) and 20 (general product).
  for (const Eigen::Index n : { Eigen::Index(37), Eigen::Index(9001), Eigen::Index(20011) })
  {
    const DenseMatrix storage = Fixed(n, 140, 0.37);
    for (const Eigen::Index K : { Eigen::Index(7), Eigen::Index(103), Eigen::Index(134) })
    {
      const auto B = storage.leftCols(K);
      double worstProduct = 0.0;
      double worstUpdate = 0.0;
      for (const Eigen::Index w : { 1, 3, 4, 5, 8, 11, 12, 13, 16, 20 })
      {
        const DenseMatrix A = Fixed(n, w, 0.53);
        const DenseMatrix expected = B.transpose() * A;
        const DenseMatrix C = TransposeProduct(B, A);
        const double scale = static_cast<double>(n);
        worstProduct = std::max(worstProduct, (C - expected).cwiseAbs().maxCoeff() / scale);

        const DenseMatrix coefficients = Fixed(K, w, 0.19);
        DenseMatrix updated = A;
        SubtractProduct(updated, B, coefficients);
        const DenseMatrix reference = A - B * coefficients;
        worstUpdate = std::max(worstUpdate,
          (updated - reference).cwiseAbs().maxCoeff() / (1.0 + static_cast<double>(K)));
      }
      const std::string shape = "n = " + std::to_string(n) + ", K = " + std::to_string(K);
      CheckBelow(worstProduct, 1e-14, shape + ": B^T A, max entry difference / n");
      CheckBelow(worstUpdate, 1e-14, shape + ": A - B C, max entry difference / (K + 1)");
    }
  }
}

//------------------------------------------------------------------------------
void ProjectionOrthogonal()
{
  // Q orthonormal (Householder QR); A - Q (Q^T A) must be orthogonal to Q, and applying the
  // projection again must change it only by rounding.
  const Eigen::Index n = 30001;
  const Eigen::Index K = 97;
  const DenseMatrix Q = Eigen::HouseholderQR<DenseMatrix>(Fixed(n, K, 0.29)).householderQ() *
    DenseMatrix::Identity(n, K);
  DenseMatrix A = Fixed(n, 12, 0.61);
  const double before = A.norm();
  const double largest = A.cwiseAbs().maxCoeff();
  SubtractProduct(A, Q, TransposeProduct(Q, A));
  const double left = (Q.transpose() * A).cwiseAbs().maxCoeff();
  CheckBelow(left, 1e-12 * largest, "max |Q^T (A - Q Q^T A)|");
  const DenseMatrix once = A;
  SubtractProduct(A, Q, TransposeProduct(Q, A));
  CheckBelow((A - once).cwiseAbs().maxCoeff(), 1e-12 * largest, "the projection is idempotent");
  Check(A.norm() > 0.5 * before, "the block keeps most of its norm (it is not inside span(Q))");
}

//------------------------------------------------------------------------------
/// A fixed symmetric n x n sparse matrix with both triangles stored: a ring of neighbours at
/// distances 1, 7 and 97 (so that rows reach far-apart rows) and a diagonal.
SparseMatrix SymmetricPattern(Eigen::Index n)
{
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index i = 0; i < n; ++i)
  {
    entries.emplace_back(static_cast<int>(i), static_cast<int>(i), 6.0 + std::sin(0.3 * i));
    for (const Eigen::Index d : { Eigen::Index(1), Eigen::Index(7), Eigen::Index(97) })
    {
      const Eigen::Index j = (i + d) % n;
      const double v = -0.5 - 0.4 * std::cos(0.7 * static_cast<double>(i + j));
      entries.emplace_back(static_cast<int>(i), static_cast<int>(j), v);
      entries.emplace_back(static_cast<int>(j), static_cast<int>(i), v);
    }
  }
  SparseMatrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

//------------------------------------------------------------------------------
void SymmetricProductMatches()
{
  // One thread (n < 8192) and two; column counts below the kernel's 8, at 8 and across several
  // blocks of 16 with a remainder; X and the result as middle columns of wider matrices (their
  // strides); and an uncompressed A (Eigen's product).
  for (const Eigen::Index n : { Eigen::Index(5003), Eigen::Index(20011) })
  {
    SparseMatrix A = SymmetricPattern(n);
    Check(SparseMatrix(A - SparseMatrix(A.transpose())).norm() == 0.0,
      "n = " + std::to_string(n) + ": the test matrix is symmetric");
    const DenseMatrix storage = Fixed(n, 45, 0.43);
    double worst = 0.0;
    for (const Eigen::Index k : { 3, 8, 12, 16, 17, 40 })
    {
      const auto X = storage.middleCols(2, k);
      DenseMatrix wide = DenseMatrix::Constant(n, k + 3, 7.0);
      auto out = wide.middleCols(1, k);
      SymmetricSparseProduct(A, X, out);
      const DenseMatrix expected = A * X;
      worst =
        std::max(worst, (out - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff());
      Check(wide.col(0).cwiseEqual(7.0).all() && wide.rightCols(2).cwiseEqual(7.0).all(),
        "n = " + std::to_string(n) + ", k = " + std::to_string(k) +
          ": the columns beside the result are untouched");
    }
    CheckBelow(worst, 1e-15, "n = " + std::to_string(n) + ": max |A X - Eigen's A X| / max |A X|");
    A.uncompress();
    DenseMatrix out(n, 12);
    SymmetricSparseProduct(A, storage.leftCols(12), out);
    CheckBelow((out - A * storage.leftCols(12)).cwiseAbs().maxCoeff(),
      0.0,
      "n = " + std::to_string(n) + ": uncompressed A");
  }
}

//------------------------------------------------------------------------------
void ThreadsMatchOneThread()
{
  // The thread-count rule (Common/Threads.h): explicit counts as asked (at most one a row), 0 is
  // one thread below 8192 rows and every core for tall enough products.
  Check(BlockThreads(100) == 1, "automatic: 1 thread for 100 rows");
  Check(BlockThreads(100, 8) == 8, "8 threads asked: 8");
  Check(BlockThreads(5, 8) == 5, "at most one thread a row");
  const Eigen::Index tall = Eigen::Index(4096) * 4096;
  Check(BlockThreads(tall) == ResolveThreads(0),
    "automatic on " + std::to_string(tall) + " rows: every core (" +
      std::to_string(ResolveThreads(0)) + ")");
  Check(ResolveThreads(0) >= 1 && ResolveThreads(3) == 3, "ResolveThreads");

  // Each product on 2, 4 and 8 threads (more than the cores: correctness, not speed) against
  // one thread: row counts that split unevenly, kernel widths 4, 8 and 16 and the general
  // product (K = 7, w = 20), relative to the largest entry.
  const auto relative = [](const DenseMatrix& X, const DenseMatrix& Y)
  { return (X - Y).cwiseAbs().maxCoeff() / Y.cwiseAbs().maxCoeff(); };
  for (const Eigen::Index n : { Eigen::Index(9001), Eigen::Index(20011) })
  {
    const DenseMatrix storage = Fixed(n, 140, 0.37);
    const SparseMatrix S = SymmetricPattern(n);
    const DenseMatrix X = Fixed(n, 40, 0.43);
    DenseMatrix sparse1(n, X.cols());
    SymmetricSparseProduct(S, X, sparse1, 1);
    for (const Eigen::Index K : { Eigen::Index(7), Eigen::Index(134) })
    {
      const auto B = storage.leftCols(K);
      for (const Eigen::Index w : { 3, 8, 12, 20 })
      {
        const DenseMatrix A = Fixed(n, w, 0.53);
        const DenseMatrix coefficients = Fixed(K, w, 0.19);
        const DenseMatrix C1 = TransposeProduct(B, A, 1);
        DenseMatrix updated1 = A;
        SubtractProduct(updated1, B, coefficients, 1);
        for (const int threads : { 2, 4, 8 })
        {
          const std::string shape = "n = " + std::to_string(n) + ", K = " + std::to_string(K) +
            ", w = " + std::to_string(w) + " on " + std::to_string(threads) + " threads";
          CheckBelow(
            relative(TransposeProduct(B, A, threads), C1), 1e-12, shape + ": B^T A vs 1 thread");
          DenseMatrix updated = A;
          SubtractProduct(updated, B, coefficients, threads);
          CheckBelow(relative(updated, updated1), 1e-12, shape + ": A - B C vs 1 thread");
        }
      }
    }
    for (const int threads : { 2, 4, 8 })
    {
      DenseMatrix out(n, X.cols());
      SymmetricSparseProduct(S, X, out, threads);
      CheckBelow(relative(out, sparse1),
        1e-12,
        "n = " + std::to_string(n) + " on " + std::to_string(threads) +
          " threads: A X vs 1 thread");
    }
  }
}

const Case Cases[] = {
  { "MatchGeneralProducts", MatchGeneralProducts },
  { "ProjectionOrthogonal", ProjectionOrthogonal },
  { "SymmetricProductMatches", SymmetricProductMatches },
  { "ThreadsMatchOneThread", ThreadsMatchOneThread },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
