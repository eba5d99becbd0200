// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsParameters.h
 * @brief Private: the checks of the parameters that several filters share.
 *
 * NumberOfHarmonics is a parameter of vtkManifoldHarmonicBasis and of
 * vtkManifoldHarmonicSmoothing, which refuse a value below 1 with the same error. (Its default
 * is vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS.) MemoryLimit is a parameter of both
 * too, in MiB (MemoryLimitBytes). NaN settings are refused by all filters (AcceptNumbers). Not
 * installed and not wrapped.
 */
#ifndef vtkManifoldHarmonicsParameters_h
#define vtkManifoldHarmonicsParameters_h

#include "Spectral/Common/BasisFile.h" // ByteCount
#include "vtkObject.h"
#include "vtkSetGet.h"

#include <algorithm>        // For std::max
#include <cmath>            // For std::isnan
#include <cstdint>          // For std::uint64_t
#include <initializer_list> // For AcceptNumbers
#include <iomanip>          // For std::setprecision
#include <sstream>          // For Bytes
#include <string>           // For Bytes
#include <utility>          // For std::pair

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

/**
 * Whether `self` may run with the settings `values` (name, value): none is NaN. If one is, an
 * error of `self` names them all. vtkSetClampMacro lets NaN through; the filters refuse it when
 * they execute, with the same settings on every process of a distributed run.
 */
inline bool AcceptNumbers(vtkObject* self,
  std::initializer_list<std::pair<const char*, double>> values)
{
  std::string names;
  int count = 0;
  for (const auto& value : values)
  {
    if (std::isnan(value.second))
    {
      names += (count++ > 0 ? ", " : "") + std::string(value.first);
    }
  }
  if (count > 0)
  {
    vtkErrorWithObjectMacro(
      self, << names << (count == 1 ? " is" : " are") << " NaN (not a number): set a number.");
  }
  return count == 0;
}

/// MemoryLimit (MiB, vtkManifoldHarmonicBasis and vtkManifoldHarmonicSmoothing) in bytes for the
/// core (spectral::BasisOptions::MemoryLimit): 0 (ask the system) stays 0, a limit below one
/// byte still limits.
inline std::uint64_t MemoryLimitBytes(double mebibytes)
{
  return mebibytes > 0.0
    ? std::max<std::uint64_t>(1, static_cast<std::uint64_t>(mebibytes * 1048576.0))
    : 0;
}

/// A byte count for people: "1.5 GiB", "380.0 MiB", "12.0 KiB" (spectral::ByteCount, the one
/// rule of the core's messages and the filters').
inline std::string Bytes(std::uint64_t bytes)
{
  return spectral::ByteCount(bytes);
}
} // namespace vtkManifoldHarmonicsParameters

#endif
