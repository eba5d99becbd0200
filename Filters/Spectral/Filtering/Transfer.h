// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Transfer.h
 * @brief The manifold harmonic transform, its inverse, and spectral transfer functions.
 *
 * A signal x on the n points of a mesh (one value per point, c components) has the manifold
 * harmonic coefficients x~_k = <x, H^k>_D = sum_i x_i D_ii H^k_i, where H^k are the M-orthonormal
 * eigenvectors of L h = lambda D h and D is the lumped mass. A filter multiplies each coefficient
 * by F(omega_k) with the frequency omega_k = sqrt(lambda_k) and sums the harmonics back
 * (B. Vallet and B. Levy, "Spectral Geometry Processing with Manifold Harmonics", Computer
 * Graphics Forum 27(2), 2008, sections 3 and 5). The frequencies above the last computed
 * harmonic are not lost: the remainder x - sum_k x~_k H^k can be added back with one gain, the
 * mean of F over [omega_m, omega_Nyquist] (eq. 10 of the paper).
 *
 * The basis is read through a row-major view, so the n by m point-data array of the VTK layer
 * (one tuple of m components per point) is used in place, without a copy. It may hold doubles
 * or floats (vtkManifoldHarmonicBasis' BasisPrecision): every function taking a basis has an
 * overload for each, and both accumulate in double, so a float basis only adds its own rounding
 * (relative 6e-8 per entry) to the results. The rows of the basis are split over
 * TransformThreads() threads (see Threads.h).
 *
 * Used by vtkManifoldHarmonicTransform and vtkSpectralFilter; tested by
 * Testing/Core/TestTransfer.cxx.
 */
#ifndef spectral_Transfer_h
#define spectral_Transfer_h

#include "Common/Mesh.h"

#include <utility>
#include <vector>

namespace spectral
{
/// Dense row-major matrix of doubles: one point (or one harmonic) a row.
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
/// Dense row-major matrix of floats: the layout of a basis stored in single precision.
using FloatRowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
/// n by m basis, row i holds the m harmonics at point i (a view on existing memory).
using BasisView = Eigen::Map<const RowMatrix>;
/// n by m basis stored as floats, row i holds the m harmonics at point i (a view).
using FloatBasisView = Eigen::Map<const FloatRowMatrix>;
/// n by c signals (row i = point i) or m by c coefficients (row k = harmonic k), viewed in place.
using ConstRowView = Eigen::Map<const RowMatrix>;

/**
 * Manifold harmonic transform: the coefficients of signals in an M-orthonormal basis.
 *
 * X~ = H^T (D X), that is x~_kj = sum_i H_ik D_ii X_ij. One pass over H, no copy of it: each
 * thread sums the products of its own rows into its own m by c partial sum, and the partial
 * sums are added at the end in the order of the rows (so thread counts differ by round-off only).
 *
 * \param H n by m basis, double or float, M-orthonormal for M = diag(mass) (H^T D H = I).
 * \param mass Lumped mass D, length n, the one the basis was computed with. Points of zero mass
 *        add nothing, even where X is not finite there (points used by no triangle).
 * \param X n by c signals (c >= 1 components per point).
 * \param threads Threads to split the rows over; 0 (default) chooses TransformThreads(n, m): every
 *        core (Common/Threads.h), fewer for small products.
 * \return m by c coefficients, row k for harmonic k, accumulated in double.
 * \throws InvalidInput if H, mass and X disagree on n.
 */
RowMatrix ForwardTransform(
  const BasisView& H, const Vector& mass, const ConstRowView& X, int threads = 0);
RowMatrix ForwardTransform(
  const FloatBasisView& H, const Vector& mass, const ConstRowView& X, int threads = 0);

/**
 * Inverse transform with per-harmonic gains and optional re-injection of the high frequencies.
 *
 * Y = sum_k gains_k x~_k H^k + hfGain (X - sum_k x~_k H^k), computed in one product as
 * Y = H (diag(gains - hfGain) X~) + hfGain X. With gains = 1 and hfGain = 0 this is the
 * D-orthogonal projection of X onto the span of H; with m = n it reproduces X.
 *
 * Each thread computes its own rows of Y, reading its rows of H once.
 *
 * \param H n by m basis, double or float.
 * \param gains Length m: the transfer function at each harmonic (see Gains).
 * \param coefficients m by c, the ForwardTransform of X.
 * \param X n by c, the original signals; may have 0 rows when hfGain == 0 (it is then unused).
 * \param hfGain Gain applied to the part of X that the basis does not represent (0: drop it).
 * \param threads Threads to split the rows over; 0 (default) chooses TransformThreads(n, m): every
 *        core (Common/Threads.h), fewer for small products.
 * \return n by c filtered signals, computed in double.
 * \throws InvalidInput if the sizes disagree, or X is empty while hfGain != 0.
 */
RowMatrix InverseTransform(const BasisView& H, const Vector& gains,
  const ConstRowView& coefficients, const ConstRowView& X, double hfGain, int threads = 0);
RowMatrix InverseTransform(const FloatBasisView& H, const Vector& gains,
  const ConstRowView& coefficients, const ConstRowView& X, double hfGain, int threads = 0);

/**
 * The filter stage of one signal, as vtkSpectralFilter runs it (and the benchmark times it):
 * InverseTransform(H, gains, coefficients, X, hfGain, threads), after which the points of zero
 * mass (used by no triangle, so outside the surface the basis describes) keep their value in X
 * instead of being scaled by hfGain.
 *
 * \param H n by m basis, double or float.
 * \param mass Lumped mass, length n.
 * \param gains, coefficients, hfGain, threads As InverseTransform.
 * \param X n by c, the original signals (required, also when hfGain == 0).
 * \return n by c filtered signals.
 * \throws InvalidInput as InverseTransform, and if mass or X does not have n rows.
 */
RowMatrix FilterSignal(const BasisView& H, const Vector& mass, const Vector& gains,
  const ConstRowView& coefficients, const ConstRowView& X, double hfGain, int threads = 0);
RowMatrix FilterSignal(const FloatBasisView& H, const Vector& mass, const Vector& gains,
  const ConstRowView& coefficients, const ConstRowView& X, double hfGain, int threads = 0);

/// The transfer functions F(omega) of SpectralFilter (values match vtkSpectralFilter's enum).
enum class FilterKind
{
  LowPass = 0,          ///< 1 below Cutoff, 0 above.
  HighPass = 1,         ///< 0 below Cutoff, 1 above.
  BandPass = 2,         ///< 1 inside [Cutoff, UpperCutoff], 0 outside.
  BandStop = 3,         ///< 0 inside [Cutoff, UpperCutoff], 1 outside.
  Enhancement = 4,      ///< 1 below Cutoff, Gain above.
  BandExaggeration = 5, ///< Gain inside [Cutoff, UpperCutoff], 1 outside.
  HeatDiffusion = 6,    ///< exp(-Time omega^2) = exp(-Time lambda).
  Custom = 7            ///< Piecewise linear through ControlPoints.
};

/**
 * Parameters of a transfer function. Only the fields used by Kind are read and validated.
 *
 * Every step (at Cutoff and UpperCutoff) is a raised cosine over
 * [omega_c (1 - Transition / 2), omega_c (1 + Transition / 2)], which is C^1 and symmetric about
 * omega_c (F(omega_c) is halfway); Transition = 0 gives a sharp step where omega = omega_c
 * counts as below the cutoff.
 */
struct FilterParameters
{
  FilterKind Kind = FilterKind::LowPass;
  /// omega_c >= 0: low/high pass cutoff, lower band edge, enhancement threshold.
  double Cutoff = 1.0;
  /// Upper band edge (>= Cutoff) for BandPass, BandStop and BandExaggeration.
  double UpperCutoff = 2.0;
  /// Width of each smooth step relative to its cutoff (>= 0; 0 = sharp).
  double Transition = 0.1;
  /// Gain of Enhancement (above Cutoff) and BandExaggeration (inside the band).
  double Gain = 2.0;
  /// t >= 0 of HeatDiffusion.
  double Time = 0.0;
  /// Custom: (omega, gain) pairs with strictly increasing omega; F is linear between them and
  /// constant beyond the first and the last.
  std::vector<std::pair<double, double>> ControlPoints;
};

/**
 * The transfer function F at one frequency.
 * \param p Filter parameters.
 * \param omega Frequency sqrt(lambda), >= 0.
 * \return F(omega).
 * \throws InvalidInput for a negative or non-finite omega, a negative or non-finite cutoff or
 *         transition, UpperCutoff < Cutoff, a negative Time, a non-finite Gain, no control
 *         points, or control points whose omega is not strictly increasing.
 */
double Gain(const FilterParameters& p, double omega);

/**
 * The gains of all harmonics: F(sqrt(max(lambda_k, 0))). Eigenvalues slightly below zero (the
 * constant harmonic, to round-off) count as omega = 0.
 * \param p Filter parameters.
 * \param lambda Eigenvalues, length m.
 * \return Length m.
 * \throws InvalidInput as Gain, and for a NaN eigenvalue.
 */
Vector Gains(const FilterParameters& p, const Vector& lambda);

/**
 * How the frequencies of FilterParameters (Cutoff, UpperCutoff, the omega of the ControlPoints)
 * and its Time are given (values match vtkSpectralFilter::CutoffUnitsType). The one home of the
 * rule that turns a relative cutoff into a frequency, for vtkSpectralFilter and
 * vtkManifoldHarmonicSmoothing (whose CutoffFraction is FractionOfHighest).
 * - Absolute: omega in radians per unit length; Time in squared units of length.
 * - FractionOfHighest: omega = value * omega_max, omega_max = sqrt(lambda_{m-1}) the highest
 *   computed frequency (HighestFrequency).
 * - HarmonicIndex: omega = the frequency of harmonic `value` (HarmonicFrequency).
 * In both relative units Time is in units of 1 / lambda_1, lambda_1 the first non-zero
 * eigenvalue: Time 1 damps the lowest non-constant harmonic by exp(-1), whatever the size of
 * the model and the number of harmonics computed. Transition and Gain have no units.
 */
enum class FrequencyUnits
{
  Absolute = 0,
  FractionOfHighest = 1,
  HarmonicIndex = 2
};

/**
 * The frequency above which F is constant: the end of the last step's transition (LowPass,
 * HighPass, Enhancement: Cutoff (1 + Transition / 2); the band kinds: UpperCutoff (1 +
 * Transition / 2)), the last control point (Custom); infinity for HeatDiffusion, which never is.
 * Above it, every frequency gets the gain F(infinity) (a low pass: exactly 0).
 * 	hrows InvalidInput as Gain.
 */
double ConstantAbove(const FilterParameters& p);

/**
 * The highest computed frequency omega_max = sqrt(max(lambda_{m-1}, 0)).
 * \param lambda Eigenvalues, ascending, length m.
 * \return omega_max, 0 for an empty lambda.
 */
double HighestFrequency(const Vector& lambda);

/**
 * The frequency of harmonic `index`: sqrt(max(lambda_k, 0)) for an integer index k, linear in
 * between (so that a slider moves the cutoff continuously); indices beyond m - 1 give omega_max.
 * \param lambda Eigenvalues, ascending, length m >= 1.
 * \param index >= 0.
 * \throws InvalidInput for a negative or non-finite index or an empty lambda.
 */
double HarmonicFrequency(const Vector& lambda, double index);

/**
 * The parameters p, given in `units`, with their frequencies and time in absolute units (see
 * FrequencyUnits). p is validated first, in its own units (a negative cutoff is refused whatever
 * the units).
 * \param lambda Eigenvalues of the basis, ascending, length m >= 1.
 * \param firstNonZeroEigenvalue lambda_1 of the relative time unit; 0 when the basis has no
 *        non-constant harmonic, where a relative Time becomes 0 (nothing to diffuse).
 * \throws InvalidInput as Gain, and as HarmonicFrequency.
 */
FilterParameters ToAbsoluteUnits(const FilterParameters& p, FrequencyUnits units,
  const Vector& lambda, double firstNonZeroEigenvalue);

/**
 * Nyquist frequency pi / h of a mesh whose mean edge length is h = edgeLengthSum / edgeCount:
 * the highest frequency its sampling can carry, in the units of omega = sqrt(lambda). The one
 * home of that formula. Taking the sums rather than the mesh lets the pieces of a distributed
 * mesh add theirs up first (vtkSpectralFilter); each triangle counts its three edges, so a piece
 * contributes MeanEdgeLength(piece) * 3 * faces and 3 * faces.
 * \return pi / h, or 0 when there is no edge or h is not positive and finite.
 */
double NyquistFrequency(double edgeLengthSum, double edgeCount);

/**
 * Nyquist frequency of a mesh, pi / (mean edge length): NyquistFrequency(sum, count) over its
 * triangles' edges.
 * \throws InvalidInput if the mesh has no triangle or only zero-length edges.
 */
double NyquistFrequency(const TriangleMesh& mesh);

/**
 * Mean of F over [omegaLow, omegaHigh]: the gain given to the frequencies that the basis does
 * not resolve (eq. 10 of Vallet and Levy, with omegaLow = omega_m and omegaHigh the Nyquist
 * frequency). Piecewise exact quadrature: Gauss-Legendre between the breakpoints of F, the
 * error function for HeatDiffusion.
 * \return The mean, or F(omegaLow) if omegaHigh <= omegaLow.
 * \throws InvalidInput as Gain.
 */
double MeanGain(const FilterParameters& p, double omegaLow, double omegaHigh);
} // namespace spectral

#endif
