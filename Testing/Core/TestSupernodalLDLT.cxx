// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Properties of the supernodal LDL^T factorization (Filters/Spectral/Solver/SupernodalLDLT.h):
// solves agree with the matrix and with Eigen's own simplicial LDL^T, the pivots count the
// eigenvalues below a shift (checked against a dense eigensolver), zero pivots are reported; on
// several threads the factor is bitwise that of one thread, and failures are reported alike;
// a volume's wide supernodes (factored a panel at a time) do the same.
#include "Checks.h"
#include "Meshes.h"
#include "Operators/Operators.h"
#include "Solver/SupernodalLDLT.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include <limits>
#include <string>
#include <vector>

using namespace spectral;
using namespace spectral::testing;

namespace
{
/// A fixed pseudo-random block of right-hand sides (the same on every run).
DenseMatrix RightHandSides(Eigen::Index n, Eigen::Index count)
{
  DenseMatrix B(n, count);
  for (Eigen::Index j = 0; j < count; ++j)
  {
    for (Eigen::Index i = 0; i < n; ++i)
    {
      B(i, j) = std::sin(0.37 * static_cast<double>(i + 1) * static_cast<double>(j + 2));
    }
  }
  return B;
}

/// How far a solve on several threads may lie from the one-thread solve of the same factor,
/// relative: they sum the updates of the separators' rows in another order, and the shifted
/// (indefinite) matrices magnify rounding by their condition.
constexpr double SolveAgreement = 1e-10;

/// The negative pivots of Eigen's simplicial LDL^T: the reference inertia.
int NegativePivots(const Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower>& reference)
{
  return static_cast<int>((reference.vectorD().array() < 0.0).count());
}

/// Two disjoint meshes (several components) of about 6,000 points with the lumped mass.
struct Pencil
{
  SparseMatrix L;
  SparseMatrix M;
};

Pencil TorusAndSphere()
{
  const TriangleMesh mesh = Join(Torus(2.0, 0.7, 64, 32), Translated(Icosphere(4), 5.0));
  return { CotanStiffness(mesh), Diagonal(LumpedMass(mesh)) };
}

//------------------------------------------------------------------------------
void SolvesAgree()
{
  const Pencil p = TorusAndSphere();
  SupernodalLDLT factor(SparseMatrix(p.L + p.M));
  Check(factor.Supernodes() > 1 && factor.Supernodes() < p.L.rows(),
    "supernodes: " + std::to_string(factor.Supernodes()) + " for " +
      std::to_string(p.L.rows()) + " columns");
  for (const double sigma : { -0.05, 3.7, 41.3 })
  {
    const SparseMatrix A = p.L - sigma * p.M;
    Check(factor.Factorize(A), "factorized at shift " + std::to_string(sigma));
    Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> reference(A);
    Check(reference.info() == Eigen::Success, "Eigen's simplicial LDL^T at the same shift");
    for (const Eigen::Index count : { 1, 7, 16, 24, 40 })
    {
      const DenseMatrix B = RightHandSides(A.rows(), count);
      const DenseMatrix X = factor.Solve(B);
      const DenseMatrix Y = reference.solve(B);
      const std::string name = "shift " + std::to_string(sigma) + ", " +
        std::to_string(count) + " right-hand sides";
      CheckBelow((A * X - B).norm() / B.norm(), 1e-9, name + ": |A X - B| / |B|");
      CheckBelow((X - Y).norm() / Y.norm(), 1e-8, name + ": |X - X_Eigen| / |X_Eigen|");
    }
    const int negative = NegativePivots(reference);
    Check(factor.NegativePivots() == negative,
      "shift " + std::to_string(sigma) + ": negative pivots " +
        std::to_string(factor.NegativePivots()) + ", Eigen's LDL^T " + std::to_string(negative));
  }
}

//------------------------------------------------------------------------------
void InertiaMatchesDense()
{
  const TriangleMesh mesh = Icosphere(3);
  const SparseMatrix L = CotanStiffness(mesh);
  const SparseMatrix M = Diagonal(LumpedMass(mesh));
  const DenseMatrix Ld(L);
  const DenseMatrix Md(M);
  Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> dense(Ld, Md);
  const Vector& lambda = dense.eigenvalues();
  SupernodalLDLT factor(SparseMatrix(L + M));
  for (const int k : { 1, 4, 9, 60, 200, 500 })
  {
    // Midway between two distinct eigenvalues.
    int j = k;
    while (lambda[j] - lambda[j - 1] < 1e-6 * lambda[j])
    {
      ++j;
    }
    const double sigma = 0.5 * (lambda[j - 1] + lambda[j]);
    const bool factored = factor.Factorize(L - sigma * M);
    Check(factored && factor.NegativePivots() == j,
      "shift " + std::to_string(sigma) + ": negative pivots " +
        std::to_string(factor.NegativePivots()) + ", dense eigenvalues below " +
        std::to_string(j));
  }
}

//------------------------------------------------------------------------------
void ZeroPivotReported()
{
  // A diagonal matrix with an exact zero: every elimination order meets the zero pivot.
  SparseMatrix A(5, 5);
  for (int i = 0; i < 5; ++i)
  {
    A.insert(i, i) = (i == 2) ? 0.0 : 1.0 + i;
  }
  A.makeCompressed();
  SparseMatrix pattern = A;
  pattern.coeffRef(2, 2) = 1.0;
  SupernodalLDLT factor(pattern);
  Check(!factor.Factorize(A), "a zero pivot makes Factorize return false");
  Check(factor.Factorize(pattern), "the same pattern with a non-zero pivot factors");
}

//------------------------------------------------------------------------------
/// A noisy torus of about 20,000 points: its elimination tree has many independent subtrees.
Pencil LargeTorus()
{
  const TriangleMesh mesh = NoisyTorusOfSize(20000, 0.02);
  return { CotanStiffness(mesh), Diagonal(LumpedMass(mesh)) };
}

//------------------------------------------------------------------------------
void ThreadsMatchOneThread()
{
  // Factor on 1, 2, 4 and 8 threads (more than the cores: the schedule, not the speed, is under
  // test), positive definite and shifted into the spectrum (indefinite). A factor made on T
  // threads and solved on one must equal the one-thread factor's solve exactly (the same
  // factor bit for bit); solving on T threads may round differently (kernel widths, and the
  // updates of the separators' rows summed thread by thread), within what the conditioning of
  // the indefinite matrix makes of rounding (up to 1.2e-12 relative measured here, 2.6e-12 on
  // the ball of WideSupernodes: SolveAgreement).
  const Pencil p = LargeTorus();
  Check(p.L.rows() >= 20000, "mesh of " + std::to_string(p.L.rows()) + " points");
  SupernodalLDLT factor(SparseMatrix(p.L + p.M));
  const DenseMatrix B = RightHandSides(p.L.rows(), 37);
  for (const double sigma : { -0.05, 45.0 })
  {
    const SparseMatrix A = p.L - sigma * p.M;
    const std::string shift = "shift " + std::to_string(sigma);
    factor.SetThreads(1);
    Check(factor.Factorize(A), shift + ": factorized on 1 thread");
    const int negative = factor.NegativePivots();
    Check((sigma < 0.0) == (negative == 0),
      shift + ": " + std::to_string(negative) + " negative pivots");
    const DenseMatrix X1 = factor.Solve(B);
    CheckBelow((A * X1 - B).norm() / B.norm(), 1e-9, shift + ": |A X - B| / |B| on 1 thread");
    for (const int threads : { 2, 4, 8 })
    {
      const std::string on = shift + " on " + std::to_string(threads) + " threads";
      factor.SetThreads(threads);
      Check(factor.Factorize(A), on + ": factorized");
      Check(factor.NegativePivots() == negative,
        on + ": negative pivots " + std::to_string(factor.NegativePivots()) + ", 1 thread " +
          std::to_string(negative));
      const DenseMatrix X = factor.Solve(B);
      CheckBelow((X - X1).norm() / X1.norm(), SolveAgreement, on + ": solve vs 1 thread, relative");
      for (const Eigen::Index count : { 1, 5, 12 })
      {
        const DenseMatrix Xc = factor.Solve(B.leftCols(count));
        CheckBelow((Xc - X1.leftCols(count)).norm() / X1.leftCols(count).norm(),
          SolveAgreement,
          on + ", " + std::to_string(count) + " right-hand sides: vs 1 thread");
      }
      factor.SetThreads(1);
      CheckBelow((factor.Solve(B) - X1).cwiseAbs().maxCoeff(),
        0.0,
        on + ": the factor is bitwise that of 1 thread (both solved on 1)");
    }
  }
}

//------------------------------------------------------------------------------
void WideSupernodes()
{
  // A tetrahedral ball: its top separators are planes of hundreds of points, factored a panel
  // of columns at a time (FactorPanel). Its solves agree with Eigen's simplicial LDL^T, its
  // pivots count as Eigen's do, every number of threads gives the one-thread factor bit for bit
  // and solves on its subtrees as on one thread, and a NaN at the centre (a top separator) is
  // reported.
  const TriangleMesh ball = TetrahedralBall(18);
  const SparseMatrix L = CotanStiffness(ball);
  const SparseMatrix M = Diagonal(LumpedMass(ball));
  SupernodalLDLT factor(SparseMatrix(L + M));
  Check(factor.WidestSupernode() > 200,
    "the widest supernode has " + std::to_string(factor.WidestSupernode()) + " columns");
  const DenseMatrix B = RightHandSides(L.rows(), 13);
  for (const double sigma : { -0.05, 60.0, 250.0 })
  {
    const SparseMatrix A = L - sigma * M;
    const std::string shift = "ball, shift " + std::to_string(sigma);
    Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> reference(A);
    Check(reference.info() == Eigen::Success, shift + ": Eigen's simplicial LDL^T");
    const int negative = NegativePivots(reference);
    Check((sigma > 0.0) == (negative > 0), shift + ": " + std::to_string(negative) + " below");
    const DenseMatrix Y = reference.solve(B);
    DenseMatrix X1;
    for (const int threads : { 1, 2, 4, 8 })
    {
      const std::string on = shift + " on " + std::to_string(threads) + " threads";
      factor.SetThreads(threads);
      Check(factor.Factorize(A), on + ": factorized");
      Check(factor.NegativePivots() == negative,
        on + ": negative pivots " + std::to_string(factor.NegativePivots()) + ", Eigen's " +
          std::to_string(negative));
      // Up to 4 threads the tree splits evenly with 38% of the factor above the subtrees; 8
      // shares of this small ball leave about half above them (51% here), where the plan gives
      // way to splitting the columns: either is right there.
      Check(factor.SolveThreads() == threads || (threads > 4 && factor.SolveThreads() == 1),
        on + ": the solve shares subtrees among " + std::to_string(factor.SolveThreads()));
      const DenseMatrix Xt = factor.Solve(B);
      CheckBelow((A * Xt - B).norm() / B.norm(), 1e-9, on + ": |A X - B| / |B|");
      CheckBelow((Xt - Y).norm() / Y.norm(), 1e-8, on + ": |X - X_Eigen| / |X_Eigen|");
      factor.SetThreads(1);
      const DenseMatrix X = factor.Solve(B);
      if (threads == 1)
      {
        X1 = X;
      }
      CheckBelow((X - X1).cwiseAbs().maxCoeff(), 0.0, on + ": bitwise the factor of 1 thread");
      CheckBelow((Xt - X1).norm() / X1.norm(), SolveAgreement, on + ": solved on them vs 1 thread");
    }
  }
  // The point nearest the centre.
  Eigen::Index centre = 0;
  ball.Vertices.rowwise().squaredNorm().minCoeff(&centre);
  SparseMatrix nan = L + M;
  nan.coeffRef(centre, centre) = std::numeric_limits<double>::quiet_NaN();
  for (const int threads : { 1, 2 })
  {
    factor.SetThreads(threads);
    Check(!factor.Factorize(nan),
      "ball, NaN at the centre on " + std::to_string(threads) + " threads: false");
  }
}

//------------------------------------------------------------------------------
void ThreadsReportFailures()
{
  // A zero pivot on an isolated point (a component of its own: a subtree of the elimination
  // tree that any thread may take) and a NaN inside the mesh: Factorize returns false on every
  // number of threads, and the next factorization of a good matrix succeeds.
  const Pencil p = LargeTorus();
  const Eigen::Index n = p.L.rows();
  std::vector<Eigen::Triplet<double>> entries;
  const SparseMatrix A = p.L + p.M;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
  {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
    {
      entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
    }
  }
  entries.emplace_back(static_cast<int>(n), static_cast<int>(n), 1.0);
  SparseMatrix good(n + 1, n + 1);
  good.setFromTriplets(entries.begin(), entries.end());
  SparseMatrix zero = good;
  zero.coeffRef(n, n) = 0.0;
  SparseMatrix nan = good;
  nan.coeffRef(n / 2, n / 2) = std::numeric_limits<double>::quiet_NaN();
  SupernodalLDLT factor(good);
  for (const int threads : { 1, 2, 4, 8 })
  {
    const std::string on = " on " + std::to_string(threads) + " threads";
    factor.SetThreads(threads);
    Check(!factor.Factorize(zero), "zero pivot of an isolated point" + on + ": false");
    Check(factor.Factorize(good), "then the good matrix" + on + ": factorized");
    Check(factor.NegativePivots() == 0, "then the good matrix" + on + ": no negative pivot");
    Check(!factor.Factorize(nan), "NaN inside the mesh" + on + ": false");
    Check(factor.Factorize(good), "then the good matrix again" + on + ": factorized");
  }
}

const Case Cases[] = {
  { "SolvesAgree", SolvesAgree },
  { "InertiaMatchesDense", InertiaMatchesDense },
  { "ZeroPivotReported", ZeroPivotReported },
  { "ThreadsMatchOneThread", ThreadsMatchOneThread },
  { "ThreadsReportFailures", ThreadsReportFailures },
  { "WideSupernodes", WideSupernodes },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
