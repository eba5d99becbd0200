// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file EigenSolver.h
 * @brief The smallest eigenpairs of a generalized symmetric problem L h = lambda M h, band by band.
 *
 * The band-by-band shift-invert strategy follows B. Vallet and B. Levy, "Spectral Geometry
 * Processing with Manifold Harmonics" (2008), section 4: each band factors L - sigma M once
 * (SupernodalLDLT on CHOLMOD's analysis, or CHOLMOD's simplicial LDL^T) and runs a block Lanczos
 * iteration (or Spectra's implicitly restarted Lanczos) on (L - sigma M)^-1 M in the M inner
 * product. Consecutive bands overlap; where they meet, the
 * vectors of both bands are merged by a Rayleigh-Ritz step on their joint span, so membership is
 * decided by M-orthogonality (rank), never by comparing eigenvalues. Sylvester's law of inertia
 * (the negative pivots of each LDL^T) proves that no eigenvalue below each shift was lost.
 * A diagonal M (the lumped mass) is scaled away first: the iteration runs on the standard
 * problem D^-1/2 L D^-1/2 y = lambda y, with y = D^1/2 h, where the inner product needs no
 * product with M.
 *
 * The parts of the solver and where they live are listed at the top of EigenSolver.cxx.
 *
 * Used by vtkManifoldHarmonicBasis; tested by Testing/Core/TestEigenSolver.cxx.
 */
#ifndef spectral_EigenSolver_h
#define spectral_EigenSolver_h

#include "Common/Defaults.h"
#include "Common/Mesh.h"
#include "Common/Monitor.h"

#include <functional>

namespace spectral
{
/// The Lanczos iteration run within each band.
enum class LanczosMethod
{
  /// Block Lanczos with thick restarts and full reorthogonalization by matrix products (default).
  Block,
  /// Spectra's implicitly restarted Lanczos (SymGEigsShiftSolver), one vector at a time.
  Spectra
};

/// The sparse factorization of L - sigma M behind each shift-invert band.
enum class FactorizationMethod
{
  /// LDL^T on CHOLMOD's supernodal analysis with dense block kernels (SupernodalLDLT, default).
  Supernodal,
  /// CHOLMOD's simplicial LDL^T, one column at a time (slower; kept as the reference).
  Simplicial
};

/// Settings of SmallestEigenpairs. The defaults suit meshes from 10^3 to 10^6 points.
struct EigenOptions
{
  /// m, the number of eigenpairs wanted (1 <= m <= n).
  int NumberOfEigenpairs = DefaultNumberOfHarmonics;
  /// Eigenpairs requested per band; 0 chooses automatically (the band policy of Bands.h).
  int BandSize = 0;
  /// Relative convergence tolerance of the Lanczos iteration within a band.
  double Tolerance = 1e-11;
  /// Maximum number of Lanczos restarts within a band.
  int MaxIterations = 1000;
  /// Largest relative residual a returned pair may have (see RelativeResiduals).
  double ResidualTolerance = 1e-8;
  /**
   * Largest componentwise backward error a returned pair may have when its relative residual
   * exceeds ResidualTolerance (see BackwardErrors): a pair is accepted when either measure is
   * within its tolerance. The backward error does not weigh rows by 1 / D_ii, so rounding in the
   * rows of tiny points (a range scan's near-coincident points) does not count against it. 0
   * leaves the relative residual alone to decide.
   */
  double BackwardErrorTolerance = 1e-8;
  /// Problems with at most this many unknowns (or with m > n / 3) are solved densely.
  int DenseThreshold = 1000;
  /// The iteration within each band.
  LanczosMethod Method = LanczosMethod::Block;
  /// The factorization of L - sigma M.
  FactorizationMethod Factorization = FactorizationMethod::Supernodal;
  /// Threads of the factorizations, solves and block products: 0 every core (the rule of
  /// Common/Threads.h); the results do not depend on it beyond round-off.
  int Threads = 0;
  /**
   * Whether to return the eigenvectors. Without them (a spectrum alone), the band-by-band
   * solve keeps only the vectors its seams still need: it verifies the older pairs (residuals
   * and backward errors, as the final check does) before it lets their vectors go, so its
   * memory no longer grows with m, and EigenResult::Eigenvectors is empty.
   */
  bool KeepEigenvectors = true;
  /**
   * Without KeepEigenvectors: receives the pairs the solve lets go, as soon as they are verified,
   * each pair of index < NumberOfEigenpairs exactly once, in ascending blocks: `first` is the
   * index of the block's first pair among the returned ones (0 is the first pair at or above
   * StartValue), `values` its eigenvalues as the result returns them, `vectors` (n by the block
   * size) its eigenvectors as the result would have held them with KeepEigenvectors: of the
   * caller's pencil, M-orthonormal, signs by NormalizeSigns (Acceptance.h), the constant null
   * pair exact (ConstantNullSpace). The band path delivers a block at each retirement (Bands.h),
   * the dense path all at once after its final check. A solve that throws may have delivered
   * some blocks first (verified ones). Empty: the vectors are dropped.
   */
  std::function<void(int first, const Vector& values, const DenseMatrix& vectors)> Deliver;
  /**
   * Pairs that start above the bottom of the spectrum: when StartIndex > 0, the solve returns
   * the NumberOfEigenpairs smallest eigenvalues at or above StartValue, and StartIndex must be
   * the number of eigenvalues below StartValue (the caller's inertia count of L - StartValue M,
   * CountEigenvaluesBelow). The bands start at StartValue, and every inertia proof counts these
   * StartIndex eigenvalues as found.
   */
  int StartIndex = 0;
  double StartValue = 0.0;
  /**
   * Whether the null space of L is the constants: a connected mesh with natural (Neumann)
   * conditions, whose rows of L sum to zero. The constant harmonic 1 / sqrt(1^T M 1) is then
   * known: with StartIndex 0 it is returned as the first pair with eigenvalue exactly 0, and the
   * other pairs are computed in its M-orthogonal complement (deflation), so that neither the
   * rounding of L (cotangents of 1e8 on a scan's near-coincident points) nor the machine's
   * floating-point kernels move the zero eigenvalue. False computes every pair.
   */
  bool ConstantNullSpace = false;
};

/// Seconds spent in each stage of SmallestEigenpairs.
struct EigenTimings
{
  /// Symbolic analysis and LDL^T factorizations of L - sigma M.
  double Factorization = 0.0;
  /// Triangular solves: applications of (L - sigma M)^-1 M.
  double Solve = 0.0;
  /// Reorthogonalization and normalization of the Krylov blocks.
  double Orthogonalization = 0.0;
  /// Ritz values and vectors, restarts and the merging of bands.
  double RayleighRitz = 0.0;
  /// Inertia checks and residuals.
  double Verification = 0.0;
};

/// The result of SmallestEigenpairs.
struct EigenResult
{
  /// m eigenvalues, ascending.
  Vector Eigenvalues;
  /// n by m, column k is the eigenvector of Eigenvalues[k]; M-orthonormal; the entry of largest
  /// magnitude of each column is positive.
  DenseMatrix Eigenvectors;
  /// Largest entry of RelativeResiduals over the returned pairs.
  double MaxResidual = 0.0;
  /// Largest entry of BackwardErrors over the returned pairs.
  double MaxBackwardError = 0.0;
  /// Number of bands (shift-invert Lanczos runs), 0 for the dense path.
  int Bands = 0;
  /// Number of LDL^T factorizations (bands, retries and the final inertia check).
  int Factorizations = 0;
  /// Number of vectors solved with a factorization of L - sigma M: applications of
  /// (L - sigma M)^-1 M, and the refinement of bands whose residuals failed.
  long long OperatorApplications = 0;
  /// The most eigenvector columns the band loop held at once (its block of accepted vectors,
  /// after each merge). Without KeepEigenvectors the memory estimate counts three bands' worth
  /// (EstimateBasisMemory, Solver/Memory.h).
  int MostKeptVectors = 0;
  /// Bands run again, from another start with fewer pairs: after a band stalled or an inertia
  /// count disagreed (Bands.h).
  int Retries = 0;
  /// The most columns a band's Krylov basis held (the block iteration, LanczosMethod::Block). A
  /// retry holds no more than a first run (RetryPairs, Bands.h): the memory estimate counts
  /// those (Solver/Memory.h).
  int MostKrylovColumns = 0;
  EigenTimings Seconds;
  /// The relative residual tolerance the pairs were verified to (EigenOptions::
  /// ResidualTolerance; a caller that relaxed it solved with the relaxed one).
  double ResidualTolerance = 0.0;
};

/**
 * The m smallest eigenpairs of L h = lambda M h.
 *
 * \param L n by n, sparse, symmetric positive semi-definite (e.g. CotanStiffness).
 * \param M n by n, sparse, symmetric positive definite (e.g. Diagonal(LumpedMass) or
 *          ConsistentMass), with a pattern contained in that of L plus the diagonal.
 * \param options m, band size, tolerances, where the pairs start, whether to keep the vectors.
 * \param monitor progress in [0, 1] and cancellation, polled inside every operator application.
 * \return Eigenvalues ascending, eigenvectors M-orthonormal with a deterministic sign (none
 *         without options.KeepEigenvectors); with options.ConstantNullSpace and StartIndex 0,
 *         the first pair is (0, 1 / sqrt(1^T M 1)) exactly and the others are M-orthogonal to it.
 * \throws InvalidInput if the sizes disagree or StartIndex + m is not in [1, n].
 * \throws SolverFailure if a band does not converge, a factorization fails, an inertia count
 *         disagrees with the eigenvalues found, or a pair has both a relative residual above
 *         ResidualTolerance and a backward error above BackwardErrorTolerance.
 * \throws Cancelled if monitor.Cancelled returned true.
 */
EigenResult SmallestEigenpairs(const SparseMatrix& L,
  const SparseMatrix& M,
  const EigenOptions& options,
  const Monitor& monitor = Monitor());

/**
 * Relative residuals of eigenpairs: for each k,
 * ||L h_k - lambda_k M h_k||_{D^-1} / max(|lambda_k|, lambda_ref), where D holds the row sums of
 * M and lambda_ref is the smallest |lambda| that is not zero by IsZeroEigenvalue (Common/
 * Eigenvalues.h) with the largest as the scale (the first non-zero
 * frequency), so that zero eigenvalues are measured against the scale of the spectrum; it is at
 * least 1e-6 trace(L) / trace(M), which only matters when no non-zero eigenvalue is returned.
 */
Vector RelativeResiduals(const SparseMatrix& L,
  const SparseMatrix& M,
  const Vector& lambda,
  const DenseMatrix& Phi);

/**
 * Componentwise (Oettli-Prager) backward errors of eigenpairs: for each k,
 * max_i |r_i| / d_i with r = L h_k - lambda_k M h_k and d = |L| |h_k| + |lambda_k| |M| |h_k|: the
 * smallest eps such that (h_k, lambda_k) is an exact eigenpair of a pencil (L + dL, M + dM) with
 * |dL| <= eps |L| and |dM| <= eps |M| entry by entry. Each d_i is floored at
 * BackwardErrorFloor (Verification.h) times the largest, so that rows where the harmonic and
 * its neighbours vanish are measured against the vector's scale, where their rounding lives.
 * Invariant under a diagonal scaling of the rows, it measures a pair against the data's own
 * precision, where the relative residual (RelativeResiduals) punishes rounding in rows of tiny
 * mass.
 */
Vector BackwardErrors(const SparseMatrix& L,
  const SparseMatrix& M,
  const Vector& lambda,
  const DenseMatrix& Phi);

/// max |Phi^T M Phi - I| over all entries. (RelativeResiduals and this: Verification.cxx.)
double OrthonormalityError(const DenseMatrix& Phi, const SparseMatrix& M);

/**
 * Number of eigenvalues of L h = lambda M h below sigma, from the inertia of an LDL^T
 * factorization of L - sigma M (Sylvester's law of inertia; Factorization.h).
 * \throws SolverFailure if the factorization fails (sigma is an eigenvalue).
 */
int CountEigenvaluesBelow(const SparseMatrix& L, const SparseMatrix& M, double sigma);
} // namespace spectral

#endif
