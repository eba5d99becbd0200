// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Bands.h
 * @brief The bands of the shift-invert iteration: how many pairs each band asks for (the band
 *        policy).
 *
 * Band policy. A band asks for the nev eigenpairs nearest its shift, with
 *
 *   nev = min(EffectiveBandSize(m, BandSize), SingleBandSize(m), n / 2).
 *
 * When EigenOptions::BandSize is 0 (automatic), EffectiveBandSize chooses one band of
 * SingleBandSize(m) = m + m / 4 + 10 pairs while that is at most 160 (m <= 120), else bands of
 * 100 pairs. A band size set by hand is used as is (but never above SingleBandSize(m)).
 *
 * Used by SmallestEigenpairs (EigenSolver.cxx) and by EstimateBasisMemory (Memory.h); tested by
 * Testing/Core/TestMemory.cxx (EstimateFormula: the automatic band sizes).
 */
#ifndef spectral_Bands_h
#define spectral_Bands_h

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
} // namespace spectral

#endif
