// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSpectralDescriptors
 * @brief Spectral shape descriptors of a mesh from its manifold harmonic basis.
 *
 * vtkSpectralDescriptors computes, from the eigenpairs (lambda_k, h_k) of the Laplace-Beltrami
 * operator written by vtkManifoldHarmonicBasis, point descriptors that depend on the intrinsic
 * geometry only (unchanged by rigid motions and by bendings that keep lengths), and the
 * scale-invariant spectrum of the shape:
 *
 * - `HeatKernelSignature` (Sun, Ovsjanikov and Guibas, SGP 2009), one component per time t:
 *   HKS(i, t) = sum_k e^{-lambda_k t} h_k(i)^2. Small times describe the shape near the point
 *   (high at tips and protrusions), large times its overall position. HeatKernelTimes (empty by
 *   default: 16 times log-spaced over [4 ln 10 / lambda_max, 4 ln 10 / lambda_1], as in the
 *   paper, lambda_1 the smallest and lambda_max the largest non-zero eigenvalue);
 *   ScaleNormalizeHeatKernel divides each column by the heat trace sum_k e^{-lambda_k t}.
 * - `WaveKernelSignature` (Aubry, Schlickewei and Cremers, ICCV Workshops 2011), one component
 *   per energy e: WKS(i, e) = sum_k h_k(i)^2 g_k(e) / sum_k g_k(e) with
 *   g_k(e) = exp(-(e - log lambda_k)^2 / (2 sigma^2)) over the non-zero eigenvalues.
 *   NumberOfEnergies energies evenly spaced in log lambda over [log lambda_1 + 2 sigma,
 *   log lambda_max - 2 sigma]; WaveKernelSigma 0 (default) takes the paper's sigma = 7 times
 *   the step between consecutive energies (solved with the margins: step =
 *   log(lambda_max / lambda_1) / (NumberOfEnergies + 27)).
 * - `GlobalPointSignature` (Rustamov, SGP 2007): h_k(i) / sqrt(lambda_k) for the first
 *   NumberOfGPSComponents non-constant harmonics (clamped, with a warning, to those computed).
 * - `SpectralDistance` from one point (SourcePoint, or the point nearest SourceLocation when
 *   UseSourceLocation is on): d(x, y)^2 = sum_k w_k (h_k(x) - h_k(y))^2 with w_k =
 *   e^{-2 lambda_k t} (DIFFUSION at DiffusionTime t), 1 / lambda_k (COMMUTE_TIME, without the
 *   area factor: the commute time of Brownian motion is A d^2) or 1 / lambda_k^2 (BIHARMONIC,
 *   Lipman, Rustamov and Funkhouser, ACM TOG 2010).
 * - Output port 1 (`ShapeDNA`, Reuter, Wolter and Peinecke, CAD 2006): a vtkTable of m rows,
 *   `Index` (k), `Eigenvalue` (lambda_k) and `ScaledEigenvalue` (lambda_k A, A the area, the sum
 *   of the lumped mass; lambda_k V^{2/3}, V the volume, for an input of 3-D cells): equal for
 *   shapes that differ by a uniform scaling.
 *
 * The eigenvalues of the constant harmonics (one per connected component) are those that
 * vtkManifoldHarmonicsArrays::IsNonZeroEigenvalue calls zero (below 1e-10 omega_N^2, omega_N =
 * pi / mean edge length, as vtkSpectralFilter): they count as 0 in e^{-lambda t} and are left
 * out of the sums that divide by lambda or take log lambda (WKS, GPS, commute time,
 * biharmonic). A heat kernel time t (or 2t for the diffusion distance) for which the computed
 * harmonics miss more than 1% of the heat trace gets a warning with the number of harmonics
 * that would do: Weyl's law lambda_k ~ 4 pi k / A turns the missing tail into a geometric series
 * (spectral::HeatKernelHarmonicsNeeded). The WKS energies always lie inside the computed
 * spectrum, with the paper's margins of 2 sigma at both ends.
 *
 * Input: the output of vtkManifoldHarmonicBasis (any vtkPointSet with the point-data arrays
 * `ManifoldHarmonics`, double or float, read in place, and `ManifoldHarmonicsMass`, and the
 * field-data array `ManifoldHarmonicsEigenvalues`). Output port 0: a shallow copy of the input
 * plus the enabled point-data arrays (vtkDoubleArray) and the field-data arrays
 * `HeatKernelSignatureTimes` and `WaveKernelSignatureEnergies` (the times and energies used).
 * Points used by no triangle (zero mass) have no harmonics: their descriptors are NaN.
 *
 * Defaults: HKS on, WKS, GPS and distance off; the ShapeDNA table is always filled.
 *
 * Errors (vtkErrorMacro, empty output): missing basis arrays (run ManifoldHarmonicBasis
 * upstream), a negative heat kernel or diffusion time, a SourcePoint out of range or used by no
 * triangle, a WaveKernelSigma too wide for the spectrum, a basis without non-constant
 * harmonics when a descriptor needs one. An aborted execution leaves both outputs empty.
 *
 * @warning The harmonics are read once per descriptor, in place; the arrays cost n doubles per
 * component (16 times, 100 energies). Distributed runs: the area and the Nyquist frequency
 * (the scale of zero eigenvalues) are those of the whole surface (summed over the processes,
 * ghost cells left out and shared points counted once), so the signatures and ShapeDNA equal a
 * serial run's; process 0 alone fills the ShapeDNA table. The distance source is still a point
 * of each piece (SourcePoint is a point id of the piece, SourceLocation its nearest point in
 * the piece): use the spectral distance in serial runs.
 *
 * Example: Examples/Python/descriptors.py. Tests: Filters/Testing/Cxx/
 * TestSpectralDescriptors.cxx, Testing/Core/TestDescriptors.cxx.
 *
 * @sa vtkManifoldHarmonicBasis vtkManifoldHarmonicTransform vtkSpectralFilter
 */
#ifndef vtkSpectralDescriptors_h
#define vtkSpectralDescriptors_h

#include "vtkManifoldHarmonicsAlgorithm.h"
#include "vtkManifoldHarmonicsModule.h" // For export macro

#include <memory> // For the mesh figures

class vtkDoubleArray;
class vtkTable;

namespace vtkManifoldHarmonicsArrays
{
class MeshFiguresCache;
}

class VTKMANIFOLDHARMONICS_EXPORT vtkSpectralDescriptors : public vtkManifoldHarmonicsAlgorithm
{
public:
  ///@{
  /**
   * Standard methods for instantiation, type information, and printing.
   */
  static vtkSpectralDescriptors* New();
  vtkTypeMacro(vtkSpectralDescriptors, vtkManifoldHarmonicsAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  ///@}

  /**
   * The spectral distances; the values match the ParaView enumeration and
   * spectral::DistanceKind.
   */
  enum DistanceKinds
  {
    DIFFUSION = 0,
    COMMUTE_TIME = 1,
    BIHARMONIC = 2
  };

  ///@{
  /**
   * Compute the point array `HeatKernelSignature`. Default on.
   */
  vtkSetMacro(ComputeHeatKernelSignature, bool);
  vtkGetMacro(ComputeHeatKernelSignature, bool);
  vtkBooleanMacro(ComputeHeatKernelSignature, bool);
  ///@}

  ///@{
  /**
   * The heat kernel times t (squared units of length), one component of the signature each.
   * Empty (default): 16 times log-spaced over [4 ln 10 / lambda_max, 4 ln 10 / lambda_1].
   * A negative time is an error at execution. SetNumberOfHeatKernelTimes keeps the first times
   * and appends zeros, to be set with SetHeatKernelTime (ParaView sets the count, then each).
   */
  void SetNumberOfHeatKernelTimes(int count);
  int GetNumberOfHeatKernelTimes();
  void SetHeatKernelTime(int index, double time);
  double GetHeatKernelTime(int index);
  void AddHeatKernelTime(double time);
  void RemoveAllHeatKernelTimes();
  ///@}

  ///@{
  /**
   * Divide each time's column of the heat kernel signature by the heat trace
   * sum_k e^{-lambda_k t}. Default off.
   */
  vtkSetMacro(ScaleNormalizeHeatKernel, bool);
  vtkGetMacro(ScaleNormalizeHeatKernel, bool);
  vtkBooleanMacro(ScaleNormalizeHeatKernel, bool);
  ///@}

  ///@{
  /**
   * Compute the point array `WaveKernelSignature`. Default off.
   */
  vtkSetMacro(ComputeWaveKernelSignature, bool);
  vtkGetMacro(ComputeWaveKernelSignature, bool);
  vtkBooleanMacro(ComputeWaveKernelSignature, bool);
  ///@}

  ///@{
  /**
   * Number of wave kernel energies, one component each. Range [1, VTK_INT_MAX]. Default 100,
   * as in the paper.
   */
  vtkSetClampMacro(NumberOfEnergies, int, 1, VTK_INT_MAX);
  vtkGetMacro(NumberOfEnergies, int);
  ///@}

  ///@{
  /**
   * Standard deviation sigma of the wave kernel's energy filters, in log lambda. 0 (default):
   * the paper's 7 times the step between energies. A sigma over log(lambda_max / lambda_1) / 4
   * leaves no room for the margins and is an error. Range [0, VTK_DOUBLE_MAX].
   */
  vtkSetClampMacro(WaveKernelSigma, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(WaveKernelSigma, double);
  ///@}

  ///@{
  /**
   * Compute the point array `GlobalPointSignature`. Default off.
   */
  vtkSetMacro(ComputeGlobalPointSignature, bool);
  vtkGetMacro(ComputeGlobalPointSignature, bool);
  vtkBooleanMacro(ComputeGlobalPointSignature, bool);
  ///@}

  ///@{
  /**
   * Number K of components of the global point signature, the first K non-constant harmonics;
   * more than the basis has is clamped with a warning. Range [1, VTK_INT_MAX]. Default 10.
   */
  vtkSetClampMacro(NumberOfGPSComponents, int, 1, VTK_INT_MAX);
  vtkGetMacro(NumberOfGPSComponents, int);
  ///@}

  ///@{
  /**
   * Compute the point array `SpectralDistance` from the source point. Default off.
   */
  vtkSetMacro(ComputeSpectralDistance, bool);
  vtkGetMacro(ComputeSpectralDistance, bool);
  vtkBooleanMacro(ComputeSpectralDistance, bool);
  ///@}

  ///@{
  /**
   * The distance (see the class documentation). Default BIHARMONIC, the one whose truncation
   * error vanishes fastest as harmonics are added.
   */
  vtkSetClampMacro(DistanceKind, int, DIFFUSION, BIHARMONIC);
  vtkGetMacro(DistanceKind, int);
  void SetDistanceKindToDiffusion() { this->SetDistanceKind(DIFFUSION); }
  void SetDistanceKindToCommuteTime() { this->SetDistanceKind(COMMUTE_TIME); }
  void SetDistanceKindToBiharmonic() { this->SetDistanceKind(BIHARMONIC); }
  ///@}

  ///@{
  /**
   * Time t of the DIFFUSION distance (squared units of length). 0 (default): the middle of the
   * default heat kernel times, 4 ln 10 / sqrt(lambda_1 lambda_max). Negative is an error at
   * execution.
   */
  vtkSetMacro(DiffusionTime, double);
  vtkGetMacro(DiffusionTime, double);
  ///@}

  ///@{
  /**
   * Id of the source point of the distance. Default 0. Outside [0, n) is an error at
   * execution.
   */
  vtkSetMacro(SourcePoint, vtkIdType);
  vtkGetMacro(SourcePoint, vtkIdType);
  ///@}

  ///@{
  /**
   * Take the point nearest SourceLocation as the source instead of SourcePoint (ParaView users
   * pick a location). Default off; SourceLocation defaults to (0, 0, 0).
   */
  vtkSetMacro(UseSourceLocation, bool);
  vtkGetMacro(UseSourceLocation, bool);
  vtkBooleanMacro(UseSourceLocation, bool);
  vtkSetVector3Macro(SourceLocation, double);
  vtkGetVector3Macro(SourceLocation, double);
  ///@}

  /**
   * The source point of the last execution's distance (SourcePoint, or the point nearest
   * SourceLocation); -1 before.
   */
  vtkGetMacro(UsedSourcePoint, vtkIdType);

  /**
   * The ShapeDNA table of output port 1.
   */
  vtkTable* GetShapeDNAOutput();

  ///@{
  /**
   * Names of the output arrays: `HeatKernelSignature`, `WaveKernelSignature`,
   * `GlobalPointSignature`, `SpectralDistance`, the field data `HeatKernelSignatureTimes` and
   * `WaveKernelSignatureEnergies`, and the ShapeDNA column `ScaledEigenvalue` (its `Index` and
   * `Eigenvalue` columns are named as the transform's spectrum's).
   */
  static const char* HeatKernelSignatureArrayName();
  static const char* WaveKernelSignatureArrayName();
  static const char* GlobalPointSignatureArrayName();
  static const char* SpectralDistanceArrayName();
  static const char* HeatKernelTimesArrayName();
  static const char* WaveKernelEnergiesArrayName();
  static const char* ScaledEigenvalueColumnName();
  ///@}

protected:
  vtkSpectralDescriptors();
  ~vtkSpectralDescriptors() override;

  /// The stages of a request (see vtkManifoldHarmonicsAlgorithm for errors and aborts).
  int Execute(vtkPointSet* input, vtkPointSet* output, vtkTable* shapeDNA) override;
  const char* GetWorkName() override { return "Spectral descriptors"; }

  bool ComputeHeatKernelSignature;
  vtkDoubleArray* HeatKernelTimes;
  bool ScaleNormalizeHeatKernel;
  bool ComputeWaveKernelSignature;
  int NumberOfEnergies;
  double WaveKernelSigma;
  bool ComputeGlobalPointSignature;
  int NumberOfGPSComponents;
  bool ComputeSpectralDistance;
  int DistanceKind;
  double DiffusionTime;
  vtkIdType SourcePoint;
  bool UseSourceLocation;
  double SourceLocation[3];
  vtkIdType UsedSourcePoint = -1;
  /// The edge sums and kind of the input's cells, computed once per input object and MTime.
  std::unique_ptr<vtkManifoldHarmonicsArrays::MeshFiguresCache> MeshFigures;

  /// ShapeDNA alone, from a basis computed with EigenvaluesOnly (no harmonics), for a surface
  /// of the given area (dimension 2) or a volume of the given volume (dimension 3).
  int ShapeDNAOnly(vtkPointSet* input,
    double area,
    int dimension,
    vtkPointSet* output,
    vtkTable* table);

private:
  vtkSpectralDescriptors(const vtkSpectralDescriptors&) = delete;
  void operator=(const vtkSpectralDescriptors&) = delete;
};

#endif
