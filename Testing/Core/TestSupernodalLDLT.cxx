// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Properties of the supernodal LDL^T factorization (Filters/Spectral/Solver/SupernodalLDLT.h): solves
// agree with the matrix and with Eigen's own simplicial LDL^T, the pivots count the eigenvalues
// below a shift (checked against a dense eigensolver), zero pivots are reported.
#include "Checks.h"
#include "Meshes.h"
#include "Operators/Operators.h"
#include "Solver/SupernodalLDLT.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include <string>

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
    int negative = 0;
    for (Eigen::Index k = 0; k < reference.vectorD().size(); ++k)
    {
      negative += reference.vectorD()[k] < 0.0 ? 1 : 0;
    }
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

const Case Cases[] = {
  { "SolvesAgree", SolvesAgree },
  { "InertiaMatchesDense", InertiaMatchesDense },
  { "ZeroPivotReported", ZeroPivotReported },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
