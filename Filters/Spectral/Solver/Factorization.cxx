// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/Factorization.h"
#include "Solver/Diagnostics.h"
#include "Solver/SupernodalLDLT.h"

#include <Eigen/CholmodSupport>

#include <cmath>

namespace spectral
{
namespace detail
{
/**
 * CHOLMOD's simplicial LDL^T (FactorizationMethod::Simplicial): one column at a time, the
 * reference that the supernodal factorization is tested against.
 */
class SimplicialFactor : public Eigen::CholmodSimplicialLDLT<SparseMatrix, Eigen::Lower>
{
public:
  explicit SimplicialFactor(const SparseMatrix& pattern) { this->analyzePattern(pattern); }
  SimplicialFactor(const SimplicialFactor&) = delete;
  SimplicialFactor& operator=(const SimplicialFactor&) = delete;

  /// Factor A. Returns false if a pivot is zero or not finite.
  bool Factorize(const SparseMatrix& A)
  {
    this->factorize(A);
    if (this->info() != Eigen::Success)
    {
      return false;
    }
    const cholmod_factor* f = this->m_cholmodFactor;
    const int* p = static_cast<const int*>(f->p);
    const double* x = static_cast<const double*>(f->x);
    this->Negative = 0;
    for (std::size_t j = 0; j < f->n; ++j)
    {
      const double pivot = x[p[j]];
      if (!std::isfinite(pivot) || pivot == 0.0)
      {
        return false;
      }
      this->Negative += (pivot < 0.0) ? 1 : 0;
    }
    return true;
  }

  /// Number of negative pivots of the last factorization.
  int NegativePivots() const { return this->Negative; }

  /// X = A^-1 B with Eigen's solve on CHOLMOD's factor.
  DenseMatrix SolveBlock(const Eigen::Ref<const DenseMatrix>& B) const { return this->solve(B); }

private:
  int Negative = 0;
};

//------------------------------------------------------------------------------
ShiftedFactor::ShiftedFactor(const SparseMatrix& L,
  const SparseMatrix& M,
  FactorizationMethod method)
  : StiffnessMatrix(L)
  , MassMatrix(M)
{
  const SparseMatrix pattern = L + M;
  if (method == FactorizationMethod::Simplicial)
  {
    this->Simplicial.reset(new SimplicialFactor(pattern));
  }
  else
  {
    this->Supernodal.reset(new SupernodalLDLT(pattern));
  }
}

//------------------------------------------------------------------------------
ShiftedFactor::~ShiftedFactor() = default;

//------------------------------------------------------------------------------
bool ShiftedFactor::Factor(double sigma)
{
  this->Shifted = this->StiffnessMatrix - sigma * this->MassMatrix;
  return this->Supernodal ? this->Supernodal->Factorize(this->Shifted)
                          : this->Simplicial->Factorize(this->Shifted);
}

//------------------------------------------------------------------------------
int ShiftedFactor::NegativePivots() const
{
  return this->Supernodal ? this->Supernodal->NegativePivots() : this->Simplicial->NegativePivots();
}

//------------------------------------------------------------------------------
DenseMatrix ShiftedFactor::SolveBlock(const Eigen::Ref<const DenseMatrix>& B) const
{
  return this->Supernodal ? this->Supernodal->Solve(B) : this->Simplicial->SolveBlock(B);
}
} // namespace detail

//------------------------------------------------------------------------------
int CountEigenvaluesBelow(const SparseMatrix& L, const SparseMatrix& M, double sigma)
{
  detail::ShiftedFactor factor(L, M, FactorizationMethod::Supernodal);
  if (!factor.Factor(sigma))
  {
    throw SolverFailure(
      "the LDL^T factorization of L - sigma M failed at shift " + detail::Str(sigma));
  }
  return factor.NegativePivots();
}
} // namespace spectral
