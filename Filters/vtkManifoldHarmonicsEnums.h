// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsEnums.h
 * @brief Private: the one table of each enumerated property of the filters, mapping its int
 *        value (the VTK enum, the ParaView XML's EnumerationDomain) to the core's enum and to the
 *        name PrintSelf prints.
 *
 * Every conversion goes through To(), which refuses a value that is in no row (a property set
 * through a setter without a clamp, or a value the XML offers that C++ does not know) with
 * spectral::InvalidInput; Name() gives the row's name, or "invalid". The XML's enumerations are
 * checked against the C++ enums by Testing/ParaView/TestManifoldHarmonicsXMLDefaults.py.in.
 */
#ifndef vtkManifoldHarmonicsEnums_h
#define vtkManifoldHarmonicsEnums_h

#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicSmoothing.h"
#include "vtkSpectralDescriptors.h"
#include "vtkSpectralFilter.h"

#include "Spectral/Common/BasisFile.h"
#include "Spectral/Common/Mesh.h"
#include "Spectral/Filtering/Descriptors.h"
#include "Spectral/Filtering/Transfer.h"
#include "Spectral/Operators/Laplacian.h"

#include <string>

namespace vtkManifoldHarmonicsEnums
{
/// One value of an enumerated property: the filter's int, the core's enum, the printed name.
template<typename CoreEnum>
struct Entry
{
  int Value;
  CoreEnum Core;
  const char* Name;
};

/// vtkManifoldHarmonicBasis::MassMatrix.
constexpr Entry<spectral::MassKind> MassMatrix[] = {
  { vtkManifoldHarmonicBasis::LUMPED, spectral::MassKind::Lumped, "Lumped" },
  { vtkManifoldHarmonicBasis::CONSISTENT, spectral::MassKind::Consistent, "Consistent" },
};

/// vtkManifoldHarmonicBasis::Laplacian.
constexpr Entry<spectral::LaplacianKind> Laplacian[] = {
  { vtkManifoldHarmonicBasis::COTANGENT, spectral::LaplacianKind::Cotangent, "Cotangent" },
  { vtkManifoldHarmonicBasis::INTRINSIC_DELAUNAY,
    spectral::LaplacianKind::IntrinsicDelaunay,
    "Intrinsic Delaunay" },
};

/// vtkManifoldHarmonicBasis::BoundaryCondition.
constexpr Entry<spectral::BoundaryCondition> BoundaryCondition[] = {
  { vtkManifoldHarmonicBasis::NEUMANN, spectral::BoundaryCondition::Neumann, "Neumann" },
  { vtkManifoldHarmonicBasis::DIRICHLET, spectral::BoundaryCondition::Dirichlet, "Dirichlet" },
};

/// vtkManifoldHarmonicBasis::BasisPrecision: the bytes of one stored value.
constexpr Entry<int> BasisPrecision[] = {
  { vtkManifoldHarmonicBasis::FLOAT, 4, "Float" },
  { vtkManifoldHarmonicBasis::DOUBLE, 8, "Double" },
};

/// vtkManifoldHarmonicBasis::Storage.
constexpr Entry<spectral::BasisStorage> Storage[] = {
  { vtkManifoldHarmonicBasis::AUTOMATIC, spectral::BasisStorage::Automatic, "Automatic" },
  { vtkManifoldHarmonicBasis::IN_MEMORY, spectral::BasisStorage::InMemory, "In Memory" },
  { vtkManifoldHarmonicBasis::FILE, spectral::BasisStorage::File, "File" },
};

/// vtkManifoldHarmonicBasis::Solver (no core enum: the engine the filter calls).
constexpr Entry<int> Solver[] = {
  { vtkManifoldHarmonicBasis::BUILT_IN, vtkManifoldHarmonicBasis::BUILT_IN, "Built-in" },
  { vtkManifoldHarmonicBasis::SLEPC, vtkManifoldHarmonicBasis::SLEPC, "SLEPc" },
};

/// vtkManifoldHarmonicSmoothing::Storage (no core enum: the path the filter takes). AUTOMATIC and
/// IN_MEMORY mean what they mean for vtkManifoldHarmonicBasis::Storage; the smoothing streams where
/// the basis filter would use a file.
constexpr Entry<int> SmoothingStorage[] = {
  { vtkManifoldHarmonicSmoothing::AUTOMATIC, vtkManifoldHarmonicSmoothing::AUTOMATIC, "Automatic" },
  { vtkManifoldHarmonicSmoothing::IN_MEMORY, vtkManifoldHarmonicSmoothing::IN_MEMORY, "In Memory" },
  { vtkManifoldHarmonicSmoothing::STREAMED, vtkManifoldHarmonicSmoothing::STREAMED, "Streamed" },
};
/// vtkSpectralFilter::FilterKind.
constexpr Entry<spectral::FilterKind> FilterKind[] = {
  { vtkSpectralFilter::LOW_PASS, spectral::FilterKind::LowPass, "Low Pass" },
  { vtkSpectralFilter::HIGH_PASS, spectral::FilterKind::HighPass, "High Pass" },
  { vtkSpectralFilter::BAND_PASS, spectral::FilterKind::BandPass, "Band Pass" },
  { vtkSpectralFilter::BAND_STOP, spectral::FilterKind::BandStop, "Band Stop" },
  { vtkSpectralFilter::ENHANCEMENT, spectral::FilterKind::Enhancement, "Enhancement" },
  { vtkSpectralFilter::BAND_EXAGGERATION,
    spectral::FilterKind::BandExaggeration,
    "Band Exaggeration" },
  { vtkSpectralFilter::HEAT_DIFFUSION, spectral::FilterKind::HeatDiffusion, "Heat Diffusion" },
  { vtkSpectralFilter::CUSTOM, spectral::FilterKind::Custom, "Custom" },
};

/// vtkSpectralFilter::CutoffUnits.
constexpr Entry<spectral::FrequencyUnits> CutoffUnits[] = {
  { vtkSpectralFilter::ABSOLUTE_FREQUENCY,
    spectral::FrequencyUnits::Absolute,
    "Absolute Frequency" },
  { vtkSpectralFilter::FRACTION_OF_HIGHEST,
    spectral::FrequencyUnits::FractionOfHighest,
    "Fraction Of Highest" },
  { vtkSpectralFilter::HARMONIC_INDEX, spectral::FrequencyUnits::HarmonicIndex, "Harmonic Index" },
};

/// vtkSpectralDescriptors::DistanceKind.
constexpr Entry<spectral::DistanceKind> DistanceKind[] = {
  { vtkSpectralDescriptors::DIFFUSION, spectral::DistanceKind::Diffusion, "Diffusion" },
  { vtkSpectralDescriptors::COMMUTE_TIME, spectral::DistanceKind::CommuteTime, "Commute Time" },
  { vtkSpectralDescriptors::BIHARMONIC, spectral::DistanceKind::Biharmonic, "Biharmonic" },
};

/**
 * The core's value of `value` in `table`.
 * \param property The property's name, for the message.
 * \throws spectral::InvalidInput when no row has `value`.
 */
template<typename CoreEnum, std::size_t N>
CoreEnum To(const Entry<CoreEnum> (&table)[N], int value, const char* property)
{
  for (const Entry<CoreEnum>& entry : table)
  {
    if (entry.Value == value)
    {
      return entry.Core;
    }
  }
  throw spectral::InvalidInput(
    std::string(property) + " " + std::to_string(value) + " is none of its values");
}

/// The name of `value` in `table` ("invalid" when no row has it).
template<typename CoreEnum, std::size_t N>
const char* Name(const Entry<CoreEnum> (&table)[N], int value)
{
  for (const Entry<CoreEnum>& entry : table)
  {
    if (entry.Value == value)
    {
      return entry.Name;
    }
  }
  return "invalid";
}
} // namespace vtkManifoldHarmonicsEnums

#endif
