// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Streaming.h
 * @brief Filtering signals while their basis streams (BasisSink, Basis.h): the transform, the
 *        filter and eq. 10's re-injection a block of harmonics at a time, never the n by m basis.
 *
 * For each block H_b of harmonics the sink receives, the coefficients c_b = H_b^T D X of the
 * signals X are taken and H_b diag(g_b - hfGain) c_b is added to a sum S; at the end
 *
 *   Y = hfGain X + S = sum_k g_k x~_k H^k + hfGain (X - sum_k x~_k H^k),
 *
 * which is InverseTransform's formula (Filtering/Transfer.h) summed over the blocks: the filtered
 * part and eq. 10's re-injection of what the basis does not represent (B. Vallet and B. Levy,
 * 2008). Points of zero mass (used by no cell, left out, or Dirichlet boundary points) keep
 * their value in X, as FilterSignal keeps them. The filter comes from the caller's design stage
 * (StreamedDesign), given the highest eigenvalue lambda_{m-1} before any harmonic
 * (BasisSink::HighestFirst): the frequencies of relative units and the re-injection gain depend
 * on it; the gain of each harmonic is F(omega_k) of that filter, taken as the harmonic comes.
 *
 * Cost: only the harmonics whose gain differs from hfGain add to S; those above the frequency
 * where F becomes constant (ConstantAbove), when that constant is hfGain, are not solved for
 * (BasisSink::WantedUpTo). A low pass (hfGain 0 when its transition ends below the highest
 * frequency) needs the harmonics below the end of its transition alone: at the default cutoff
 * (half the highest frequency, transition 0.1), eigenvalues below (0.5 * 1.05)^2 = 0.28 of the
 * highest, by Weyl's law (lambda_k grows as k) about the lowest 28 % of the m harmonics. With
 * one connected component the highest eigenvalue itself costs a few inertia counts and one
 * short band (ComputeBasis), not the whole spectrum.
 *
 * Memory: X, the sum S and D X on the used points (3 n c doubles), besides what ComputeBasis
 * streams with (EstimateStreamedMemory, Solver/Memory.h).
 *
 * Used by vtkManifoldHarmonicSmoothing (its STREAMED storage); tested by
 * Testing/Core/TestStreaming.cxx (FilterMatchesInMemory).
 */
#ifndef spectral_Streaming_h
#define spectral_Streaming_h

#include "Basis.h"
#include "Filtering/Transfer.h"

#include <functional>
#include <vector>

namespace spectral
{
/**
 * The design stage of a streamed filter: given the highest eigenvalue of the basis, lambda_{m-1}
 * (mesh units), returns the filter in absolute frequencies (FilterParameters, ToAbsoluteUnits)
 * and sets `hfGain`, the gain of the frequencies the basis does not represent (0 drops them).
 */
using StreamedDesign = std::function<FilterParameters(double highest, double& hfGain)>;

/// Filters signals with a basis that streams (see the file documentation).
class StreamedFilter
{
public:
  /**
   * \param X n by c signals, one row per point of the mesh given to ComputeBasis (copied).
   * \param design The gains (called once, from BasisSink::Begin).
   */
  StreamedFilter(const ConstRowView& X, StreamedDesign design);

  /// The sink to set as BasisOptions::Sink (HighestFirst on); it refers to this filter, which
  /// must outlive the ComputeBasis call.
  BasisSink Sink();

  /**
   * The filtered signals Y (n by c), once ComputeBasis has returned.
   * \throws InvalidInput if no basis was streamed into the filter.
   */
  RowMatrix Result() const;

  /**
   * The filtered signals of points that each take a row of the streamed mesh: point i takes row
   * rowOf[i] (-1: none; several points may share a row, e.g. the copies of a welded seam point)
   * and re-injects its own value, Y_i = hfGain X_i + S_{rowOf[i]} where that row has mass,
   * Y_i = X_i otherwise. Result() is ResultOn(the signals given, the identity).
   * \param X rowOf.size() by c signals of the points.
   * \throws InvalidInput if no basis was streamed, or the sizes disagree.
   */
  RowMatrix ResultOn(const ConstRowView& X, const std::vector<long long>& rowOf) const;

private:
  void Begin(const BasisResult& basis);
  void Add(const Vector& values, const DenseMatrix& harmonics);

  RowMatrix Signals;
  StreamedDesign Design;
  bool Begun = false;
  std::vector<int> Rows;
  Vector Mass;
  /// The filter in absolute frequencies, its re-injection gain, and the largest eigenvalue
  /// whose harmonic adds to S (infinity: any).
  FilterParameters Parameters;
  double HighFrequencyGain = 0.0;
  double WantedUpTo = 0.0;
  /// D X on the used points, and the sum S of the blocks' filtered parts there.
  DenseMatrix Weighted;
  DenseMatrix Sum;
};
} // namespace spectral

#endif
