// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicsStages.h"

#include "vtkDataArray.h"
#include "vtkManifoldHarmonicsCutoffs.h"
#include "vtkManifoldHarmonicsEnums.h"
#include "vtkManifoldHarmonicsGhosts.h"
#include "vtkManifoldHarmonicsParallel.h"
#include "vtkPointSet.h"

namespace vtkManifoldHarmonicsStages
{
//------------------------------------------------------------------------------
spectral::Vector OwnedMass(const vtkManifoldHarmonicsArrays::Basis& basis, vtkPointSet* withBasis)
{
  return basis.MassVector().cwiseProduct(vtkManifoldHarmonicsGhosts::OwnedPoints(withBasis));
}

//------------------------------------------------------------------------------
spectral::RowMatrix LocalCoefficients(const vtkManifoldHarmonicsArrays::Basis& basis,
  const spectral::Vector& ownedMass,
  vtkDataArray* signal,
  int threads)
{
  return basis.ForwardTransform(
    ownedMass, vtkManifoldHarmonicsArrays::Signal(signal).View(), threads);
}

//------------------------------------------------------------------------------
double NyquistFrequency(vtkMultiProcessController* controller, std::vector<double> sums)
{
  if (controller)
  {
    vtkManifoldHarmonicsParallel::SumOverRanks(controller, sums);
  }
  return spectral::NyquistFrequency(sums[0], sums[1]);
}

//------------------------------------------------------------------------------
Design DesignFilter(const spectral::FilterParameters& given,
  int units,
  const spectral::Vector& lambda,
  double nyquist)
{
  Design design;
  design.Lambda = lambda;
  design.Units = units;
  design.FirstNonZero = vtkManifoldHarmonicsCutoffs::FirstNonZeroEigenvalue(lambda, nyquist);
  design.Given = given;
  design.Parameters = spectral::ToAbsoluteUnits(given,
    vtkManifoldHarmonicsEnums::To(vtkManifoldHarmonicsEnums::CutoffUnits, units, "CutoffUnits"),
    lambda,
    design.FirstNonZero);
  design.Gains = spectral::Gains(design.Parameters, lambda);
  return design;
}

//------------------------------------------------------------------------------
double MeanGainAbove(const Design& design, double nyquist)
{
  if (nyquist <= 0.0)
  {
    throw spectral::InvalidInput(
      "the Nyquist frequency needs a mesh with triangles of non-zero, finite edge length");
  }
  // Mean gain of F over [omega_m, omega_Nyquist], eq. 10 of Vallet and Levy.
  return spectral::MeanGain(design.Parameters, spectral::HighestFrequency(design.Lambda), nyquist);
}

//------------------------------------------------------------------------------
double ReinjectionGain(vtkObject* self, const Design& design, double nyquist, bool reinject)
{
  const double highFrequencyGain = reinject ? MeanGainAbove(design, nyquist) : 0.0;
  vtkManifoldHarmonicsCutoffs::WarnAboutCutoffs(self,
    design.Units,
    reinject,
    design.Given,
    design.Parameters,
    design.Lambda,
    nyquist,
    design.Gains,
    highFrequencyGain);
  return highFrequencyGain;
}
} // namespace vtkManifoldHarmonicsStages
