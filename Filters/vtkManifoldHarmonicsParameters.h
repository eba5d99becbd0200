// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsParameters.h
 * @brief Private: the checks of the parameters that several filters share.
 *
 * NumberOfHarmonics is a parameter of vtkManifoldHarmonicBasis and of
 * vtkManifoldHarmonicSmoothing, which refuse a value below 1 with the same error. (Its default
 * is vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS.) Not installed and not wrapped.
 */
#ifndef vtkManifoldHarmonicsParameters_h
#define vtkManifoldHarmonicsParameters_h

#include "vtkObject.h"
#include "vtkSetGet.h"

namespace vtkManifoldHarmonicsParameters
{
/**
 * Whether `requested` may become the NumberOfHarmonics of `self` (vtkManifoldHarmonicBasis,
 * vtkManifoldHarmonicSmoothing): at least 1. If not, an error of `self` says so and that the
 * `current` value stays.
 */
inline bool AcceptNumberOfHarmonics(vtkObject* self, int requested, int current)
{
  if (requested < 1)
  {
    vtkErrorWithObjectMacro(self,
      << "NumberOfHarmonics must be at least 1, not " << requested << "; it stays " << current
      << ".");
    return false;
  }
  return true;
}
} // namespace vtkManifoldHarmonicsParameters

#endif
