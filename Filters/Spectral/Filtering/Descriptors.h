// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Descriptors.h
 * @brief Spectral shape descriptors: heat and wave kernel signatures, global point signature,
 * diffusion, commute-time and biharmonic distances, ShapeDNA.
 *
 * Every descriptor is a sum over the eigenpairs (lambda_k, h_k) of a manifold harmonic basis:
 * h_k is column k of the n by m basis H (D-orthonormal, H^T D H = I), read in place through a
 * row-major view of doubles or floats (Transfer.h) and accumulated in double. The eigenvalues of
 * the constant harmonics (one per connected component) are zero to round-off; which ones they
 * are is the caller's rule (the VTK layer asks vtkManifoldHarmonicsArrays::IsNonZeroEigenvalue)
 * and reaches the core as Spectrum::NonZero. Those eigenvalues count as exactly 0 where a
 * formula takes e^{-lambda t}, and their harmonics are left out where a formula divides by
 * lambda or takes its logarithm.
 *
 * Used by vtkSpectralDescriptors; tested by Testing/Core/TestDescriptors.cxx; example
 * Examples/Python/descriptors.py.
 */
#ifndef spectral_Descriptors_h
#define spectral_Descriptors_h

#include "Common/Mesh.h"
#include "Filtering/Transfer.h"

#include <vector>

namespace spectral
{
/// The number of heat kernel times when none is given (Sun, Ovsjanikov and Guibas use 100).
constexpr int DefaultNumberOfHeatKernelTimes = 16;
/// The number of wave kernel energies when none is given (Aubry et al. use 100).
constexpr int DefaultNumberOfEnergies = 100;
/// sigma of the wave kernel in steps between consecutive energies (Aubry et al.: w = 7).
constexpr double WaveKernelSigmaInSteps = 7.0;
/// The relative truncation error the harmonic counts of HeatKernelHarmonicsNeeded aim at.
constexpr double DefaultTruncationTolerance = 0.01;

/// The eigenvalues of a basis and which of them belong to non-constant harmonics.
struct Spectrum
{
  /// m eigenvalues, ascending.
  Vector Lambda;
  /// m flags: true where Lambda[k] is clear of zero (a non-constant harmonic).
  std::vector<bool> NonZero;
};

/**
 * The eigenvalues a heat kernel uses: Lambda with the zero ones set to exactly 0.
 * \throws InvalidInput if NonZero does not have m entries or a non-zero eigenvalue is not a
 *         positive finite number.
 */
Vector HeatEigenvalues(const Spectrum& spectrum);

/// The indices k of the non-constant harmonics, ascending. \throws InvalidInput as above.
std::vector<Eigen::Index> NonZeroIndices(const Spectrum& spectrum);

/**
 * The default heat kernel times of Sun, Ovsjanikov and Guibas ("A Concise and Provably
 * Informative Multi-Scale Signature Based on Heat Diffusion", SGP 2009, section 5): `count`
 * times log-spaced over [4 ln 10 / lambda_max, 4 ln 10 / lambda_1], lambda_1 the smallest and
 * lambda_max the largest non-zero eigenvalue, i.e. from the time at which the highest computed
 * harmonic has decayed to 1e-4 to the time at which the lowest one has.
 * \param count >= 1 (1 gives the geometric mean of the two ends).
 * \return `count` times, ascending.
 * \throws InvalidInput if there is no non-zero eigenvalue or count < 1.
 */
Vector DefaultHeatKernelTimes(const Spectrum& spectrum, int count = DefaultNumberOfHeatKernelTimes);

/**
 * The heat trace Z(t) = sum_k e^{-lambda_k t} over the m eigenpairs, for each time.
 * \throws InvalidInput for a negative or non-finite time.
 */
Vector HeatTrace(const Spectrum& spectrum, const Vector& times);

/**
 * Heat kernel signature (Sun, Ovsjanikov and Guibas 2009): HKS(i, t) = sum_k e^{-lambda_k t}
 * h_k(i)^2, the heat that stays at point i after time t from a unit source there.
 * \param H n by m basis (double or float).
 * \param times T diffusion times, each >= 0 and finite.
 * \param scaleNormalize Divide column t by the heat trace Z(t) (section 5 of the paper), which
 *        makes the signature independent of the global scale of the shape up to the times.
 * \return n by T, column j for times[j].
 * \throws InvalidInput for a bad time or sizes that disagree.
 */
RowMatrix HeatKernelSignature(const BasisView& H,
  const Spectrum& spectrum,
  const Vector& times,
  bool scaleNormalize);
RowMatrix HeatKernelSignature(const FloatBasisView& H,
  const Spectrum& spectrum,
  const Vector& times,
  bool scaleNormalize);

/**
 * How many harmonics the heat kernel at time t needs for a relative truncation error of its
 * trace below `tolerance`: the smallest M with sum_{k >= M} e^{-lambda_k t} <= tolerance Z(t).
 * The eigenvalues beyond the computed ones are estimated by Weyl's law (WeylEigenvalue,
 * Common/Eigenvalues.h): on a surface of area A, lambda_k ~ 4 pi k / A, so that the tail is the
 * geometric series q^M / (1 - q) with q = e^{-4 pi t / A}; in a volume V,
 * lambda_k ~ c k^(2/3) with c = (6 pi^2 / V)^(2/3), whose tail is estimated by the integral
 * of e^{-c t x^(2/3)} over x >= M - 1/2 (an incomplete gamma function). Z(t) is the computed
 * trace plus that estimate of the tail beyond m. The trace bounds the signature's error on
 * average: the mass-weighted mean of HKS(., t) is Z(t) / measure.
 * \param measure The total area (dimension 2) or volume (dimension 3), > 0: the sum of the
 *        lumped mass.
 * \param dimension 2 for a surface, 3 for a volume.
 * \param time t >= 0; t = 0 needs every harmonic and returns the largest int.
 * \return M, at least 1. The basis is long enough when M <= m.
 * \throws InvalidInput for a non-positive measure, a dimension other than 2 and 3, a negative
 *         time or a tolerance outside (0, 1).
 */
int HeatKernelHarmonicsNeeded(const Spectrum& spectrum,
  double measure,
  int dimension,
  double time,
  double tolerance = DefaultTruncationTolerance);

/// Wave kernel energies (in log lambda) and the width of the energy filters.
struct WaveKernelEnergies
{
  /// E energies e_j, ascending, evenly spaced.
  Vector Energies;
  /// The standard deviation sigma of the log-normal energy filters, > 0.
  double Sigma = 0.0;
};

/**
 * The energies of Aubry, Schlickewei and Cremers ("The Wave Kernel Signature: A Quantum
 * Mechanical Approach to Shape Analysis", ICCV Workshops 2011, section 4.2): `count` energies
 * evenly spaced in log lambda over [log lambda_1 + 2 sigma, log lambda_max - 2 sigma] (lambda_1
 * and lambda_max the smallest and the largest non-zero eigenvalue), with sigma = 7 delta where
 * delta is the step between consecutive energies. The paper defines the margins with sigma and
 * sigma with the step; solved together they give delta = R / (count + 27) with
 * R = log(lambda_max / lambda_1), margins of 14 delta, and count >= 1 always fits. (Common
 * implementations take delta = R / count before the margins instead, which leaves no energy
 * for count <= 28.)
 * \param count E >= 1.
 * \param sigma 0 for the paper's 7 delta; otherwise sigma itself (> 0), with energies over
 *        [log lambda_1 + 2 sigma, log lambda_max - 2 sigma].
 * \throws InvalidInput if there is no non-zero eigenvalue, count < 1, sigma < 0, or an explicit
 *         sigma leaves no room for the energies (4 sigma > R; the message gives R / 4).
 */
WaveKernelEnergies DefaultWaveKernelEnergies(const Spectrum& spectrum,
  int count = DefaultNumberOfEnergies,
  double sigma = 0.0);

/**
 * The weights of the wave kernel (Aubry et al. 2011, section 4.2): W_kj = g_k(e_j) /
 * sum_k g_k(e_j) with g_k(e) = exp(-(e - log lambda_k)^2 / (2 sigma^2)) over the non-zero
 * eigenvalues, 0 for the zero ones. The signature is WKS(i, e_j) = sum_k W_kj h_k(i)^2, and
 * the wave kernel between two points p and x is sum_k W_kj h_k(p) h_k(x), whose coefficients in
 * the basis are W_kj h_k(p) (the landmark descriptors of FunctionalMap.h).
 * \return m by E, each column summing to 1.
 * \throws InvalidInput if there is no non-zero eigenvalue or sigma <= 0.
 */
DenseMatrix WaveKernelWeights(const Spectrum& spectrum, const WaveKernelEnergies& energies);

/**
 * Wave kernel signature (Aubry et al. 2011, eq. 6 with the energy filters of section 4.2):
 * WKS(i, e) = sum_k h_k(i)^2 g_k(e) / sum_k g_k(e), g_k(e) = exp(-(e - log lambda_k)^2 /
 * (2 sigma^2)), both sums over the non-zero eigenvalues. Each column is a weighted mean of the
 * h_k(i)^2, so with an orthonormal basis sum_i D_ii WKS(i, e) = 1.
 * \param H n by m basis (double or float).
 * \return n by E, column j for energies.Energies[j].
 * \throws InvalidInput if there is no non-zero eigenvalue or sigma <= 0.
 */
RowMatrix WaveKernelSignature(const BasisView& H,
  const Spectrum& spectrum,
  const WaveKernelEnergies& energies);
RowMatrix WaveKernelSignature(const FloatBasisView& H,
  const Spectrum& spectrum,
  const WaveKernelEnergies& energies);

/**
 * Global point signature (Rustamov, "Laplace-Beltrami Eigenfunctions for Deformation Invariant
 * Shape Representation", SGP 2007): GPS(i) = (h_1(i)/sqrt(lambda_1), ..., h_K(i)/sqrt(lambda_K))
 * over the first K non-constant harmonics. Euclidean distances between GPS points approximate
 * the commute-time distance.
 * \param components K, 1 <= K <= the number of non-zero eigenvalues.
 * \return n by K.
 * \throws InvalidInput for K out of range.
 */
RowMatrix GlobalPointSignature(const BasisView& H, const Spectrum& spectrum, int components);
RowMatrix GlobalPointSignature(const FloatBasisView& H, const Spectrum& spectrum, int components);

/// The spectral distances (values match vtkSpectralDescriptors' DistanceKinds).
enum class DistanceKind
{
  Diffusion = 0,   ///< w = e^{-2 lambda t}, Coifman and Lafon's diffusion distance at time t.
  CommuteTime = 1, ///< w = 1 / lambda, without the area factor (see DistanceWeights).
  Biharmonic = 2   ///< w = 1 / lambda^2, Lipman, Rustamov and Funkhouser 2010.
};

/**
 * The weights w_k of d^2(x, y) = sum_k w_k (h_k(x) - h_k(y))^2:
 * - Diffusion: e^{-2 lambda_k t}, over all harmonics (constant ones differ between components
 *   only);
 * - CommuteTime: 1 / lambda_k over the non-constant harmonics, with no area factor: the
 *   expected commute time of Brownian motion between x and y is A d^2 (A the area). On a
 *   surface sum_k 1 / lambda_k diverges like log m (Weyl), so this distance grows with the
 *   number of harmonics and is most useful to compare points within one basis;
 * - Biharmonic: 1 / lambda_k^2 over the non-constant harmonics (Lipman, Rustamov and
 *   Funkhouser, "Biharmonic Distance", ACM TOG 29(3), 2010); its tail converges like 1 / m.
 * Zero-eigenvalue harmonics weigh 0 in the last two.
 * \param time t >= 0 (Diffusion only).
 * \return m weights.
 * \throws InvalidInput for a negative or non-finite time.
 */
Vector DistanceWeights(const Spectrum& spectrum, DistanceKind kind, double time = 0.0);

/**
 * The spectral distance of every point from one source point:
 * d(i) = sqrt(sum_k w_k (h_k(i) - h_k(source))^2).
 * \param weights m non-negative weights (DistanceWeights).
 * \param source Row of H, 0 <= source < n.
 * \return n distances; d(source) = 0.
 * \throws InvalidInput for a source out of range or weights of the wrong size.
 */
Vector SpectralDistance(const BasisView& H, const Vector& weights, Eigen::Index source);
Vector SpectralDistance(const FloatBasisView& H, const Vector& weights, Eigen::Index source);

/**
 * ShapeDNA (Reuter, Wolter and Peinecke, "Laplace-Beltrami spectra as 'Shape-DNA' of surfaces
 * and solids", Computer-Aided Design 38(4), 2006): the eigenvalues scaled to be invariant under
 * a uniform scaling of the shape, lambda_k |Omega|^{2/d} for a d-dimensional domain of measure
 * |Omega|. Surfaces pass their area and d = 2 (lambda_k A); tetrahedral meshes will pass their
 * volume and d = 3 (lambda_k V^{2/3}).
 * \param measure |Omega| > 0.
 * \param dimension d >= 1.
 * \return m scaled eigenvalues.
 * \throws InvalidInput for a non-positive or non-finite measure or d < 1.
 */
Vector ShapeDNA(const Vector& lambda, double measure, int dimension = 2);
} // namespace spectral

#endif
