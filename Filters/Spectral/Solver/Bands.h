// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Bands.h
 * @brief The bands of the shift-invert iteration: how many pairs each band asks for (the band
 *        policy), where the shifts go, how bands are merged at their seams, and the loop over
 *        bands with its inertia proofs and rollbacks.
 *
 * Band policy. A band asks for the nev eigenpairs nearest its shift, with
 *
 *   nev = PairsPerBand(m, BandSize, n)
 *       = min(EffectiveBandSize(m, BandSize), SingleBandSize(m), n / 2).
 *
 * When EigenOptions::BandSize is 0 (automatic), EffectiveBandSize chooses one band of
 * SingleBandSize(m) = m + m / 4 + 10 pairs while that is at most 160 (m <= 120), else bands of
 * 100 pairs. A band size set by hand is used as is (but never above SingleBandSize(m)).
 *
 * Shifts. The first shift is -1 / area (below the first non-zero eigenvalue of most shapes); each
 * later shift is placed from the eigenvalue density of the band before (Weyl's law), 3/8 of a
 * band's width above what is complete. A band trusts only its pairs strictly inside the interval
 * its pairs span around the shift; where two bands overlap, their vectors are merged by a
 * Rayleigh-Ritz step on the joint span (Merge). After each band the inertia of L - sigma M
 * (Factorization.h) must equal the number of accepted eigenvalues below sigma; otherwise what
 * is not proven is dropped and the band is retried (at most three times).
 *
 * Used by SmallestEigenpairs (EigenSolver.h) and by EstimateBasisMemory (Memory.h);
 * tested by Testing/Core/TestEigenSolver.cxx (BandSeams, RefinedBands, DisjointComponents) and
 * Testing/Core/TestMemory.cxx (EstimateFormula: the automatic band sizes).
 */
#ifndef spectral_Bands_h
#define spectral_Bands_h

#include "Common/Mesh.h"
#include "Common/Monitor.h"
#include "Solver/EigenSolver.h"

namespace spectral
{
/**
 * The pairs a single band asks for when it must return all m: m + m / 4 + 10 (its edges are
 * left to the final inertia check). No band asks for more.
 */
int SingleBandSize(int m);

/**
 * The band size of the eigensolver: `bandSize` if > 0, else the automatic choice of the band
 * policy above.
 * \param m Number of eigenpairs (harmonics).
 * \param bandSize The requested band size (EigenOptions::BandSize); > 0 is returned as is.
 */
int EffectiveBandSize(int m, int bandSize);

namespace detail
{
struct MassMatrix;

/// nev, the pairs each band asks for: min(EffectiveBandSize(m, bandSize), SingleBandSize(m), n/2).
int PairsPerBand(int m, int bandSize, Eigen::Index n);

/**
 * The band-by-band shift-invert Lanczos iteration (see EigenSolver.h and the band policy above)
 * on the pencil (L, M).
 * \param area the surface area: the sum of the entries of the mass matrix before any scaling.
 * \return the options.NumberOfEigenpairs smallest pairs, ascending, M-orthonormal (signs not
 *         normalized, MaxResidual not set).
 * \throws SolverFailure, Cancelled as SmallestEigenpairs.
 */
EigenResult BandEigenpairs(const SparseMatrix& L,
  const MassMatrix& M,
  double area,
  const EigenOptions& options,
  const Monitor& monitor);
} // namespace detail
} // namespace spectral

#endif
