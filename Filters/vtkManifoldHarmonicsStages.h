// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsStages.h
 * @brief Private: the stages after the basis, each written once and called by every filter that
 *        runs it: the transform of a signal (vtkManifoldHarmonicTransform), the Nyquist
 *        frequency, the design of a filter and its re-injection gain (vtkSpectralFilter), and
 *        vtkManifoldHarmonicSmoothing, which runs them on its cached basis.
 */
#ifndef vtkManifoldHarmonicsStages_h
#define vtkManifoldHarmonicsStages_h

#include "vtkManifoldHarmonicsArrays.h"

#include "Spectral/Filtering/Transfer.h"

#include <vector>

class vtkDataArray;
class vtkMultiProcessController;
class vtkObject;
class vtkPointSet;

namespace vtkManifoldHarmonicsStages
{
/**
 * The transform's weights on this process: the lumped mass of the points it owns, 0 on a copy
 * flagged DUPLICATEPOINT (vtkManifoldHarmonicsGhosts::OwnedPoints of `withBasis`).
 */
spectral::Vector OwnedMass(const vtkManifoldHarmonicsArrays::Basis& basis, vtkPointSet* withBasis);

/**
 * The transform of `signal` (n tuples of c components) in `basis` with the weights `ownedMass`
 * (OwnedMass): m by c coefficients summed over the points this process owns; added over the
 * processes of a distributed run they are the whole mesh's.
 */
spectral::RowMatrix LocalCoefficients(const vtkManifoldHarmonicsArrays::Basis& basis,
  const spectral::Vector& ownedMass,
  vtkDataArray* signal,
  int threads);

/**
 * The Nyquist frequency (spectral::NyquistFrequency) of the whole mesh from the
 * vtkManifoldHarmonicsArrays::EdgeSums of this process (ghost cells left out): in a distributed
 * run the sums of all processes are added up (collective).
 * \return 0 when the mesh (on every process) has no triangle of non-zero, finite size.
 */
double NyquistFrequency(vtkMultiProcessController* controller, std::vector<double> sums);

/// A filter designed for a basis: its eigenvalues, the parameters as given and in frequencies,
/// and the gain of each harmonic.
struct Design
{
  spectral::Vector Lambda;
  double FirstNonZero = 0.0;
  int Units = 0;
  spectral::FilterParameters Given;
  spectral::FilterParameters Parameters;
  spectral::Vector Gains;
};

/**
 * The parameters `given` in `units` (vtkSpectralFilter::CutoffUnitsType), validated there, in
 * frequencies for the eigenvalues `lambda`, and their gains.
 * \throws spectral::InvalidInput for invalid parameters or units.
 */
Design DesignFilter(const spectral::FilterParameters& given,
  int units,
  const spectral::Vector& lambda,
  double nyquist);

/**
 * The mean gain of the design's filter over [omega_max, nyquist], which eq. 10 of Vallet and Levy
 * re-injects, without warnings (ReinjectionGain warns).
 * \throws spectral::InvalidInput without a Nyquist frequency.
 */
double MeanGainAbove(const Design& design, double nyquist);

/**
 * The gain of the re-injected high frequencies (eq. 10 of Vallet and Levy; 0 without
 * re-injection), after the warnings about cutoffs the spectrum leaves no choice for (`self`'s).
 * \throws spectral::InvalidInput when re-injecting without a Nyquist frequency.
 */
double ReinjectionGain(vtkObject* self, const Design& design, double nyquist, bool reinject);
} // namespace vtkManifoldHarmonicsStages

#endif
