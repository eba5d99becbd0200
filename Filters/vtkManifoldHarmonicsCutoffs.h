// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsCutoffs.h
 * @brief Private: the cutoff units of vtkSpectralFilter (CutoffUnits) in the VTK layer.
 *
 * The checked mapping of vtkSpectralFilter::CutoffUnitsType onto spectral::FrequencyUnits (whose
 * rule, spectral::ToAbsoluteUnits, turns relative cutoffs into frequencies), the ranges of the
 * panel's sliders in each unit, and the warnings about cutoffs that leave the transfer function
 * no choice. The zero eigenvalues of the constant harmonics are told from the others by
 * spectral::IsZeroEigenvalue with the scale omega_N^2 (omega_N the Nyquist frequency). Not
 * installed and not wrapped. Tested by Filters/Testing/Cxx/TestSpectralFilter.cxx.
 */
#ifndef vtkManifoldHarmonicsCutoffs_h
#define vtkManifoldHarmonicsCutoffs_h

#include "Spectral/Filtering/Transfer.h"

class vtkObject;

namespace vtkManifoldHarmonicsCutoffs
{
/// The slider ranges of a filter that has not run: [0, 1] and [0, 1], around the defaults.
void InitialRanges(double frequency[2], double time[2]);

/// lambda_1, the first eigenvalue clear of the zero ones (spectral::IsZeroEigenvalue with the
/// scale omega_N^2, `nyquist` = omega_N; not finite counts as zero); 0 if none.
double FirstNonZeroEigenvalue(const spectral::Vector& lambda, double nyquist);

/// The ranges of the Cutoff and Time sliders (vtkSpectralFilter::GetFrequencyRange and
/// GetTimeRange) in the filter's units, from the eigenvalues of the basis (see there).
void SliderRanges(const spectral::Vector& lambda,
  double firstNonZero,
  int units,
  double frequency[2],
  double time[2]);

/// The warnings of an execution whose cutoffs leave the transfer function no choice: a basis of
/// constant harmonics only, constant harmonics whose rounding-sized frequencies straddle the
/// cutoff (their components move towards the origin), and a cutoff below the first non-zero
/// frequency or above the highest computed one. given: the parameters in the filter's units;
/// absolute: the same in frequencies; units: vtkSpectralFilter::CutoffUnitsType of `given`;
/// reinject: whether the filter re-injects the high frequencies. The warnings are `self`'s.
void WarnAboutCutoffs(vtkObject* self,
  int units,
  bool reinject,
  const spectral::FilterParameters& given,
  const spectral::FilterParameters& absolute,
  const spectral::Vector& lambda,
  double nyquist,
  const spectral::Vector& gains,
  double highFrequencyGain);
} // namespace vtkManifoldHarmonicsCutoffs

#endif
