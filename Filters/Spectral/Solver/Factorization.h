// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Factorization.h
 * @brief The factorization of L - sigma M behind every shift-invert band, and the inertia it
 *        gives: the number of eigenvalues below sigma (Sylvester's law of inertia).
 *
 * ShiftedFactor wraps the two FactorizationMethods: SupernodalLDLT (SupernodalLDLT.h) on
 * CHOLMOD's analysis, or CHOLMOD's simplicial LDL^T. It also defines CountEigenvaluesBelow,
 * declared in EigenSolver.h.
 *
 * Used by Bands, BlockLanczos and SpectraBand; tested by Testing/Core/TestEigenSolver.cxx
 * (InertiaCounts, MethodsAgree) and Testing/Core/TestSupernodalLDLT.cxx.
 */
#ifndef spectral_Factorization_h
#define spectral_Factorization_h

#include "Common/Mesh.h"
#include "Solver/EigenSolver.h"

#include <memory>

namespace spectral
{
class SupernodalLDLT;

namespace detail
{
class SimplicialFactor;

/**
 * The factorization of L - sigma M for a sequence of shifts. The pattern of L + M is analysed
 * once (fill-reducing ordering, symbolic factor); each shift reuses that analysis. The pivots
 * give the inertia of L - sigma M: the number of eigenvalues below sigma.
 */
class ShiftedFactor
{
public:
  /// Analyse the pattern of L + M; L and M must outlive this object.
  ShiftedFactor(const SparseMatrix& L, const SparseMatrix& M, FactorizationMethod method);
  ~ShiftedFactor();
  ShiftedFactor(const ShiftedFactor&) = delete;
  ShiftedFactor& operator=(const ShiftedFactor&) = delete;

  /// Factor L - sigma M. Returns false if a pivot is zero or not finite.
  bool Factor(double sigma);

  /// Number of negative pivots of the last factorization: eigenvalues below its shift.
  int NegativePivots() const;

  /// L - sigma M of the last factorization.
  const SparseMatrix& ShiftedMatrix() const { return this->Shifted; }

  /// X = (L - sigma M)^-1 B for a block of right-hand sides.
  DenseMatrix SolveBlock(const Eigen::Ref<const DenseMatrix>& B) const;

private:
  const SparseMatrix& StiffnessMatrix;
  const SparseMatrix& MassMatrix;
  SparseMatrix Shifted;
  std::unique_ptr<SupernodalLDLT> Supernodal;
  std::unique_ptr<SimplicialFactor> Simplicial;
};
} // namespace detail
} // namespace spectral

#endif
