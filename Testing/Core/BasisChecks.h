// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BasisChecks.h
 * @brief Checks of properties every basis of ComputeBasis (Basis.h) has, shared by the core's
 *        tests of surfaces, volumes and point clouds.
 */
#ifndef spectral_testing_BasisChecks_h
#define spectral_testing_BasisChecks_h

#include "Basis.h"
#include "Checks.h"

#include <string>
#include <vector>

namespace spectral
{
namespace testing
{
/**
 * Zero modes by construction (EigenOptions::ConstantNullSpace): the first `components`
 * eigenvalues are exactly 0 and no other is; each of their harmonics is 1 / sqrt(the mass of its
 * component) on the rows where it is not 0 (its component) and the components are disjoint and
 * cover every row; every other harmonic is M-orthogonal to each of them (1e-12). The mass of a
 * component and h_c^T M h_k = c sum_i m_i h_k(i) come from the lumped mass m (the row sums of
 * M, for the lumped and the consistent mass alike).
 */
inline void CheckZeroModes(const BasisResult& basis, int components, const std::string& name)
{
  const Vector& lambda = basis.Pairs.Eigenvalues;
  const DenseMatrix& H = basis.Pairs.Eigenvectors;
  const Vector& mass = basis.LumpedMass;
  int zeros = 0;
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
  {
    zeros += lambda[k] == 0.0 ? 1 : 0;
  }
  const bool first = zeros == components && (lambda.head(components).array() == 0.0).all();
  Check(basis.Components == components && first,
    name + "one eigenvalue exactly 0 per component, first: " + std::to_string(zeros) + " of " +
      std::to_string(basis.Components));
  if (!first || H.cols() < components)
  {
    return;
  }
  std::vector<int> owner(static_cast<std::size_t>(H.rows()), -1);
  bool disjoint = true;
  double constantError = 0.0;
  double overlap = 0.0;
  for (int c = 0; c < components; ++c)
  {
    double area = 0.0;
    for (Eigen::Index i = 0; i < H.rows(); ++i)
    {
      if (H(i, c) != 0.0)
      {
        disjoint = disjoint && owner[static_cast<std::size_t>(i)] < 0;
        owner[static_cast<std::size_t>(i)] = c;
        area += mass[i];
      }
    }
    const double value = 1.0 / std::sqrt(area);
    Vector weights = Vector::Zero(H.rows());
    for (Eigen::Index i = 0; i < H.rows(); ++i)
    {
      if (H(i, c) != 0.0)
      {
        constantError = std::max(constantError, std::abs(H(i, c) - value) / value);
        weights[i] = value * mass[i];
      }
    }
    for (Eigen::Index k = components; k < H.cols(); ++k)
    {
      overlap = std::max(overlap, std::abs(weights.dot(H.col(k))));
    }
  }
  Check(disjoint && std::count(owner.begin(), owner.end(), -1) == 0,
    name + "the zero modes' supports are disjoint and cover every point");
  CheckBelow(
    constantError, 1e-13, name + "each zero mode is 1/sqrt(its component's mass) on it (relative)");
  CheckBelow(overlap, 1e-12, name + "every other harmonic M-orthogonal to every zero mode");
}
} // namespace testing
} // namespace spectral

#endif
