// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Eigenvalues.h
 * @brief The one rule that tells the zero eigenvalues of a Laplacian from the others, and
 *        Weyl's estimate of the k-th eigenvalue.
 *
 * The constant harmonics (one per connected component) have the eigenvalue 0, which a solver
 * returns as round-off of the size of the whole spectrum: a few ulps of its top lambda_max,
 * about 1e-16 lambda_max to 1e-13 lambda_max after the shift-invert iterations, with either
 * sign. The non-constant ones start at lambda_1, which on the meshes the eigensolver accepts
 * (it warns beyond lambda_max / lambda_1 of about 1e8) is at least 1e-8 lambda_max. The
 * threshold ZeroEigenvalueTolerance * scale sits between the two, about two orders of magnitude
 * from each, where scale is the top of the spectrum: lambda_max of the operator, or, where only
 * the mesh is at hand, omega_N^2 with the Nyquist frequency omega_N = pi / (mean edge length)
 * (see NyquistFrequency in Filtering/Transfer.h), which is of the same order.
 *
 * Used by vtkSpectralFilter (slider ranges) and vtkManifoldHarmonicSmoothing (a basis of
 * constant harmonics only); tested by Testing/Core/TestTransfer.cxx.
 */
#ifndef spectral_Eigenvalues_h
#define spectral_Eigenvalues_h

#include "Common/Constants.h"

#include <cmath>

namespace spectral
{
/// Eigenvalues at most this fraction of the top of the spectrum count as zero.
constexpr double ZeroEigenvalueTolerance = 1e-10;

/**
 * Whether lambda is one of the zero eigenvalues of the constant harmonics.
 * \param lambda An eigenvalue of L h = lambda M h (negative round-off counts as zero).
 * \param scale The top of the spectrum: lambda_max, or omega_N^2 of the mesh; >= 0. With scale
 *        0 (no triangle of finite size) only lambda <= 0 is zero.
 * \return lambda <= ZeroEigenvalueTolerance * scale. A NaN is not a zero eigenvalue (and not a
 *         valid one either: callers that need finite values check them).
 */
inline bool IsZeroEigenvalue(double lambda, double scale)
{
  return lambda <= ZeroEigenvalueTolerance * scale;
}

/**
 * Weyl's law for the k-th eigenvalue of the Laplace-Beltrami operator (Neumann or Dirichlet
 * alike): the number of eigenvalues below lambda grows as A lambda / (4 pi) on a surface of
 * area A and as V lambda^(3/2) / (6 pi^2) in a volume V, so lambda_k ~ 4 pi k / A, or
 * (6 pi^2 k / V)^(2/3). An estimate for placing shifts and intervals, not a bound.
 * \param measure The area (dimension 2) or the volume (dimension 3), > 0.
 */
inline double WeylEigenvalue(double k, double measure, int dimension)
{
  return dimension == 3 ? std::pow(6.0 * Pi * Pi * k / measure, 2.0 / 3.0) : 4.0 * Pi * k / measure;
}
} // namespace spectral

#endif
