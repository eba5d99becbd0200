// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Memory.h
 * @brief How much memory a basis computation needs, and how much the machine has available.
 *
 * vtkManifoldHarmonicBasis checks, before it assembles anything, that the basis it is asked for
 * fits in memory, and fails with a message saying what to change if it does not, rather than
 * being killed by the system halfway through a long solve.
 *
 * The estimate (bytes) for n points (nUsed of them used by triangles) and m harmonics is
 *
 *     n m b                     the output basis, b = 8 (double) or 4 (float) bytes a value
 *   + nUsed m 8                 the solver's eigenvector block (always double); a spectrum
 *                               alone (no eigenvectors kept, EigenOptions::KeepEigenvectors)
 *                               needs nUsed min(m, 3 k) 8: the vectors its seams still need
 *   + nUsed (9 k / 2 + 100) 8   the Lanczos workspace of a band of k pairs: its Krylov basis
 *                               (3 k and three blocks; a retry of the band asks for fewer pairs
 *                               in the same basis, RetryPairs in Bands.h), the images of its
 *                               Ritz vectors and of the joint span of a merge (up to 3 k / 2),
 *                               block products, and the mesh and sparse operators (about 50
 *                               values a point)
 *   + nUsed 80 12               the sparse LDL^T factor: about 80 non-zeros a row (a surface
 *                               mesh's fill-in under a nested-dissection ordering), 12 bytes each
 *                               (an 8-byte value and a 4-byte row index); a volume's factor
 *                               fills far more, and more with its size: 11 nUsed^(1/3) a row
 *                               (401 measured on the 50,653-point tetrahedral ball of
 *                               `bench/ManifoldHarmonicsBench --volume --case 50000:200`)
 *   + 16 MiB                    the process's own: the BLAS's buffers and the threads' stacks
 *                               that a solve touches first
 *
 * with k = EffectiveBandSize(m, bandSize), the eigensolver's band size (the band policy is
 * documented once, in Bands.h; a band size set by hand above SingleBandSize(m) makes the
 * estimate high, since no band asks for more).
 * It is an estimate, not a bound (the fill-in of the factor depends on the mesh), meant to stay
 * above what a solve takes: a streamed smoothing of a 10,142-point sphere with 800 harmonics
 * (TestManifoldHarmonicSmoothing.MemoryLimitStreams, heaptrack) held a Krylov basis of 3.3 k
 * columns, the images of 1.3 k, the seams' 3 k and two delivery blocks, and its factor 3.5 MB
 * (the estimate's 10 MB: a sphere fills less than 80 a row).
 *
 * A streamed basis (BasisSink, Basis.h) keeps no output basis and runs the solver as for a
 * spectrum alone; its Basis term is instead the blocks in delivery, 2 n min(m,
 * StreamedBlockColumns) 8 (the solver verifies and hands over the pairs it lets go that many at
 * a time, as harmonics, and again on the output's rows): EstimateStreamedMemory, independent of
 * m once m > 3 k, below a double in-memory estimate once m > 2 StreamedBlockColumns (128).
 * A caller that accumulates what it receives adds its own arrays (vtkManifoldHarmonicSmoothing:
 * the signals' sums; a basis file: its writer, BasisFileWriterBytes) and gives the solve the rest
 * of the limit (MemoryShare).
 *
 * Memory planning (PlanBasisMemory, PlanStreamedMemory) chooses instead of refusing where it can:
 * when the estimate at the automatic band size does not fit, smaller bands (down to
 * SmallestPlannedBand pairs) shrink the Krylov term and the vectors kept for the seams;
 * ComputeBasis runs with the band size the plan chose and says so (a warning), the filters choose
 * their storage from the planned estimates.
 *
 * Used by vtkManifoldHarmonicBasis and vtkManifoldHarmonicSmoothing; tested by
 * Testing/Core/TestMemory.cxx.
 */
#ifndef spectral_Memory_h
#define spectral_Memory_h

#include "Solver/Bands.h" // EffectiveBandSize, the k of the estimate

#include <cstdint>

namespace spectral
{
/// The terms of the memory estimate of a basis computation, in bytes.
struct MemoryEstimate
{
  /// The output basis: n m values of the chosen precision.
  std::uint64_t Basis = 0;
  /// The eigensolver's own block of eigenvectors: nUsed m doubles.
  std::uint64_t Eigenvectors = 0;
  /// The Lanczos workspace of one band, the mesh and the operators: nUsed (9 k / 2 + 100)
  /// doubles.
  std::uint64_t Krylov = 0;
  /// The sparse factor: nUsed 80 (11 nUsed^(1/3) for a volume) (value, index) pairs of 12 bytes.
  std::uint64_t Factor = 0;

  /// The process's own memory that a solve touches first (BLAS buffers, thread stacks).
  std::uint64_t Overhead = 0;

  /// The sum of the five terms.
  std::uint64_t Total() const
  {
    return this->Basis + this->Eigenvectors + this->Krylov + this->Factor + this->Overhead;
  }
};

/**
 * Estimate the memory of computing an n by m basis (see the file documentation for the formula).
 * \param n Points of the output (rows of the basis array).
 * \param nUsed Points that triangles use (unknowns of the eigenproblem), <= n.
 * \param m Number of harmonics.
 * \param bandSize Eigenpairs per band (EigenOptions::BandSize); 0 for the automatic choice.
 * \param bytesPerValue Size of one value of the output basis: 8 (double) or 4 (float); 0 for
 *        none.
 * \param keepEigenvectors Whether the solver keeps its eigenvectors (false: a spectrum alone).
 * \param volume Whether the mesh is a volume (tetrahedra): the factor's fill of a 3-D mesh.
 * \return The terms of the estimate.
 */
MemoryEstimate EstimateBasisMemory(std::uint64_t n,
  std::uint64_t nUsed,
  int m,
  int bandSize,
  int bytesPerValue,
  bool keepEigenvectors = true,
  bool volume = false);

/// The most pairs a solve without KeepEigenvectors verifies and hands over at once as
/// harmonics (EigenOptions::Deliver), and a streamed basis its sink (BasisSink::Harmonics).
constexpr int StreamedBlockColumns = 64;

/**
 * Estimate the memory of streaming an n by m basis (BasisSink; see the file documentation):
 * EstimateBasisMemory of a spectrum alone, with the blocks in delivery as its Basis term.
 * \param n, nUsed, m, bandSize, volume As EstimateBasisMemory.
 */
MemoryEstimate EstimateStreamedMemory(std::uint64_t n,
  std::uint64_t nUsed,
  int m,
  int bandSize,
  bool volume = false);

/// The fewest eigenpairs a band is given when the plan makes bands smaller to fit
/// (PlanBasisMemory, PlanStreamedMemory): below it each band's factorization and block iteration
/// cost more than its vectors save.
constexpr int SmallestPlannedBand = 20;

/// How a computation runs in the memory it has: its band size and its estimate there.
struct MemoryPlan
{
  /// Eigenpairs per band to run with (EigenOptions::BandSize): the one asked for (0 for the
  /// automatic band) or, when smaller bands were needed to fit (Shrunk), the largest that fits.
  int BandSize = 0;
  /// The band the computation would have run with unplanned (EffectiveBandSize).
  int UnplannedBandSize = 0;
  /// Whether BandSize is smaller than the automatic band, to fit.
  bool Shrunk = false;
  /// The estimate at BandSize; when nothing fits, at SmallestPlannedBand: the least it needs.
  MemoryEstimate Estimate;
  /// Whether the estimate fits what is available (true when that is unknown).
  bool Fits = true;
};

/**
 * The memory plan of EstimateBasisMemory (its arguments but the band size): with the band size
 * asked for when it is set (bandSize > 0) or when the automatic one fits `available`;
 * otherwise with the largest band from the automatic one down to SmallestPlannedBand whose
 * estimate fits (the Krylov workspace, and the vectors a spectrum alone or a stream keeps for
 * its seams, grow with the band). Nothing fitting gives Fits false and the estimate at
 * SmallestPlannedBand. `available` 0 (unknown) fits everything.
 */
MemoryPlan PlanBasisMemory(std::uint64_t n,
  std::uint64_t nUsed,
  int m,
  int bandSize,
  int bytesPerValue,
  bool keepEigenvectors,
  bool volume,
  std::uint64_t available);

/// The memory plan of EstimateStreamedMemory (its arguments but the band size), by the rule of
/// PlanBasisMemory.
MemoryPlan PlanStreamedMemory(std::uint64_t n,
  std::uint64_t nUsed,
  int m,
  int bandSize,
  bool volume,
  std::uint64_t available);

/**
 * The share of `available` bytes (MemoryLimit or the system's) left to a solve whose caller
 * holds `reserved` bytes beside it (a smoothing's sums, a basis file's writer): at least one
 * byte, since 0 means unknown; 0 when `available` is unknown.
 */
std::uint64_t MemoryShare(std::uint64_t available, std::uint64_t reserved);

/**
 * The memory available to a new computation, in bytes: MemAvailable of /proc/meminfo on Linux
 * (free memory plus the caches the kernel can drop), otherwise the free physical pages reported
 * by sysconf(_SC_AVPHYS_PAGES).
 * \return The available bytes, or 0 when the system reports neither.
 */
std::uint64_t AvailableMemory();
} // namespace spectral

#endif
