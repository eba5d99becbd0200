// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsNames.h
 * @brief The names of the arrays and table columns the filters write and read: their one home.
 *
 * The public static accessors of the filters (vtkManifoldHarmonicBasis::HarmonicsArrayName(),
 * vtkManifoldHarmonicTransform::CoefficientsSuffix(), vtkSpectralFilter::FilteredSuffix(), ...)
 * return these constants; the filters and their helpers use them directly. Private: neither
 * installed nor wrapped, and it includes nothing of the module.
 */
#ifndef vtkManifoldHarmonicsNames_h
#define vtkManifoldHarmonicsNames_h

#include <string>

namespace vtkManifoldHarmonicsNames
{
/// Point data of vtkManifoldHarmonicBasis: n tuples of m components, the harmonics.
constexpr const char* Harmonics = "ManifoldHarmonics";
/// Point data of vtkManifoldHarmonicBasis: n values, the lumped mass.
constexpr const char* Mass = "ManifoldHarmonicsMass";
/// Field data of vtkManifoldHarmonicBasis: m values, the eigenvalues in ascending order.
constexpr const char* Eigenvalues = "ManifoldHarmonicsEigenvalues";
/// Field data of vtkManifoldHarmonicBasis: one value each, the largest componentwise backward
/// error and the largest relative residual of the returned pairs (spectral::BackwardErrors,
/// spectral::RelativeResiduals).
constexpr const char* BackwardError = "ManifoldHarmonicsBackwardError";
constexpr const char* Residual = "ManifoldHarmonicsResidual";
/// Field data of vtkManifoldHarmonicBasis with the SLEPc solver: one value each, the number of
/// eigenvalues in SLEPc's interval by the inertia of MUMPS factorizations at its ends, and
/// max |H^T M H - I|.
constexpr const char* InertiaCount = "ManifoldHarmonicsInertiaCount";
constexpr const char* OrthonormalityError = "ManifoldHarmonicsOrthonormalityError";

/// The signal name of the point coordinates (hence `Points_Coefficients`).
constexpr const char* Points = "Points";
/// Field data of vtkManifoldHarmonicTransform: `<Signal>_Coefficients`.
constexpr const char* CoefficientsSuffix = "_Coefficients";
/// Point data of vtkSpectralFilter with ReplaceInput off: `<Array>_Filtered`.
constexpr const char* FilteredSuffix = "_Filtered";
/// Spectrum columns: `<Signal>_Magnitude` (and `<Signal>_Filtered_Magnitude` of the filter).
constexpr const char* MagnitudeSuffix = "_Magnitude";

/// Spectrum columns: harmonic index k, eigenvalue lambda_k, frequency omega_k, gain F(omega_k).
constexpr const char* IndexColumn = "Index";
constexpr const char* EigenvalueColumn = "Eigenvalue";
constexpr const char* FrequencyColumn = "Frequency";
constexpr const char* GainColumn = "Gain";
/// vtkSpectralDescriptors: the point descriptors, their parameters (field data) and the
/// ShapeDNA column of scaled eigenvalues.
constexpr const char* HeatKernelSignature = "HeatKernelSignature";
constexpr const char* WaveKernelSignature = "WaveKernelSignature";
constexpr const char* GlobalPointSignature = "GlobalPointSignature";
constexpr const char* SpectralDistance = "SpectralDistance";
constexpr const char* HeatKernelTimes = "HeatKernelSignatureTimes";
constexpr const char* WaveKernelEnergies = "WaveKernelSignatureEnergies";
constexpr const char* ScaledEigenvalueColumn = "ScaledEigenvalue";

/// vtkFunctionalMap: the point arrays of the target (the source point id of each target point,
/// the target's harmonics aligned to the source's), the suffix of a transferred array whose
/// name the target already has, and the prefix of the map table's columns (one per source
/// harmonic: `SourceHarmonic_<j>`).
constexpr const char* CorrespondingPointIds = "CorrespondingPointIds";
constexpr const char* AlignedHarmonics = "AlignedHarmonics";
constexpr const char* TransferredSuffix = "_Transferred";
constexpr const char* MapColumnPrefix = "SourceHarmonic_";

/// `name` + `suffix` (an empty name for a null one).
inline std::string Concatenate(const char* name, const char* suffix)
{
  return std::string(name ? name : "") + suffix;
}
} // namespace vtkManifoldHarmonicsNames

#endif
