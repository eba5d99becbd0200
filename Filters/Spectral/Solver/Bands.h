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
 * Block size and return (BandBlockColumns, BandReturnPairs; BandRequest::ReturnPairs). A band's
 * block Lanczos iteration (BlockLanczos.h) applies the operator to blocks of 8 vectors, and returns
 * once 4/5 of its pairs have converged in the single band, 9/10 in bands of 100. Small blocks raise
 * the degree of the Krylov polynomial per application: the single band of 135 pairs at m = 100
 * converges in one fill of its 421-vector basis (416 applications, no restart) where blocks of 16
 * took 576 applications and a restart, 19 to 35% less time on the 10K- and 100K-point tori. A band
 * of 100 with blocks of 8 reaches 4/5 of its pairs so early that it returns too few (8 bands
 * instead of 6 at m = 500); waiting for 9/10 took fewer applications than blocks of 12 at 4/5 in
 * every case measured (6 bands at m = 500), while in the single band it would cost a restart
 * (bench/README, "Block size").
 *
 * Shifts. The first shift is -1 / area (below the first non-zero eigenvalue of most shapes); each
 * later shift is placed from the eigenvalue density of the band before (Weyl's law), 3/8 of a
 * band's width above what is complete. A band trusts only its pairs strictly inside the interval
 * its pairs span around the shift; where two bands overlap, their vectors are merged by a
 * Rayleigh-Ritz step on the joint span (Merge). After each band the inertia of L - sigma M
 * (Factorization.h) must equal the number of accepted eigenvalues below sigma; otherwise what
 * is not proven is dropped and the band is retried (at most three times). A retry (a band that
 * stalled or an inertia count that disagreed) starts from another vector and asks for fewer
 * pairs in the same Krylov subspace (RetryPairs: 2 nev / (attempt + 2)), so that it holds no more
 * vectors than the first run, which the memory plan counts (Memory.h).
 *
 * Pairs that start higher (EigenOptions::StartIndex > 0): the eigenvalues below StartValue
 * count as found (their number is the caller's inertia proof), the first shift lies above
 * StartValue by 3/8 of a band's width (the density from Weyl's law, StartIndex / StartValue),
 * and a band's pairs below StartValue are not trusted.
 *
 * Known null vectors (MassMatrix::Deflation, EigenOptions::ConstantNullSpace): the bands work in
 * their M-orthogonal complement. With StartIndex 0 they are the first accepted pairs, which no
 * merge changes, counted by the inertia proofs at their Rayleigh quotient (0 up to the rounding
 * of L: where an inertia count of L as rounded sees them) and returned with eigenvalue 0.
 *
 * Without the eigenvectors (EigenOptions::KeepEigenvectors false): once more than two bands'
 * worth of accepted vectors are kept, those one band below what is proven are verified and
 * dropped (retired), at a gap of the spectrum, never inside a multiple eigenvalue. A later band
 * that reaches below the retired ones counts its pairs there in the inertia proof but does not
 * merge them: their values are already accepted.
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

#include <functional>

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

/// The vectors in each block of a band's block Lanczos iteration (the block policy above).
constexpr int BandBlockColumns = 8;

/// The converged pairs a band waits for before it returns, for a solve of m pairs in bands of
/// nev (PairsPerBand) and an attempt that asks for `pairs` (RetryPairs): 4/5 of them in the
/// single band (nev = SingleBandSize(m)), 9/10 in the others (the block policy above).
int BandReturnPairs(int m, int nev, int pairs);

/// The pairs a band of `pairs` asks for at retry `attempt` (0: the first run): 2 pairs /
/// (attempt + 2), at least 1, in the subspace of the first run (BandRequest::SubspacePairs).
int RetryPairs(int pairs, int attempt);

/**
 * What a solve that does not keep its eigenvectors does with the pairs it lets go: verify them
 * (CheckSomeResiduals) on the caller's pencil. Called with the pairs' values, their vectors in
 * the loop's pencil (the loop's own columns, not a copy), the index of the first, and the result
 * whose figures it raises.
 */
using RetirePairs = std::function<void(const Vector& values,
  const Eigen::Ref<const DenseMatrix>& vectors,
  int first,
  EigenResult&)>;

/**
 * The band-by-band shift-invert Lanczos iteration (see EigenSolver.h and the band policy above)
 * on the pencil (L, M).
 * \param area the surface area: the sum of the entries of the mass matrix before any scaling.
 * \param retire Without options.KeepEigenvectors: receives every returned pair (and possibly
 *        some beyond them) before its vector is dropped.
 * \return the options.NumberOfEigenpairs smallest pairs at or above options.StartValue,
 *         ascending, M-orthonormal (signs not normalized, MaxResidual not set), or their
 *         eigenvalues alone without options.KeepEigenvectors (MaxResidual set by `retire`).
 * \throws SolverFailure, Cancelled as SmallestEigenpairs.
 */
EigenResult BandEigenpairs(const SparseMatrix& L,
  const MassMatrix& M,
  double area,
  const EigenOptions& options,
  const Monitor& monitor,
  const RetirePairs& retire = RetirePairs());
} // namespace detail
} // namespace spectral

#endif
