// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSpectralFilter
 * @brief Filter the geometry and point data of a mesh in the manifold harmonic basis.
 *
 * vtkSpectralFilter multiplies the manifold harmonic coefficients x~_k of a signal by a transfer
 * function F evaluated at the frequency omega_k = sqrt(lambda_k) of each harmonic, and sums the
 * harmonics back:
 *
 *   y = sum_k F(omega_k) x~_k H^k + g_hf (x - sum_k x~_k H^k),
 *
 * (B. Vallet and B. Levy, "Spectral Geometry Processing with Manifold Harmonics", Computer
 * Graphics Forum 27(2), 2008, section 5). The last term re-injects the details that the m
 * computed harmonics do not represent, with the mean gain g_hf of F over [omega_m, omega_N]
 * (eq. 10 of the paper), where omega_m = sqrt(lambda_{m-1}) is the highest computed frequency
 * and omega_N = pi / (mean edge length) the Nyquist frequency of the mesh. Without it
 * (ReinjectHighFrequencies off) the output lies in the span of the m harmonics.
 *
 * Input: the output of vtkManifoldHarmonicTransform, i.e. the basis arrays of
 * vtkManifoldHarmonicBasis plus field-data arrays `<Signal>_Coefficients`. Every signal that has
 * coefficients and whose source still exists is filtered (choose the signals on the transform):
 * - `Points_Coefficients`: the filtered coordinates always replace the points (same precision
 *   as the input points).
 * - `<Array>_Coefficients`: the filtered array is added as `<Array>_Filtered`, or replaces
 *   `<Array>` when ReplaceInput is on. Either way it has the type of the input array
 *   (NewInstance); integer arrays (e.g. unsigned char colours) are rounded and clamped to their
 *   type's range. Filtered normals (the array the input marks as its normals, GetNormals()) are
 *   scaled back to unit length, whether they replace the input's or are added as
 *   `<Normals>_Filtered`.
 * - Like VTK's smoothing filters, the filter passes the other point data on unchanged: point
 *   normals of the input no longer match filtered points unless they are filtered too (select
 *   them on the transform, ReplaceInput on) or recomputed downstream (vtkPolyDataNormals,
 *   "Generate Surface Normals" in ParaView).
 * The coefficients of a replaced signal are replaced by the filtered ones, F(omega_k) x~_k, so
 * that the output can feed another vtkSpectralFilter. Points that no triangle uses (zero mass)
 * keep their input values.
 *
 * Transfer functions (FilterKind; each step is a raised cosine whose relative width is
 * Transition, 0 for a sharp step):
 * - LOW_PASS (0): 1 below Cutoff, 0 above.          - HIGH_PASS (1): 0 below Cutoff, 1 above.
 * - BAND_PASS (2): 1 in [Cutoff, UpperCutoff].       - BAND_STOP (3): 0 in [Cutoff, UpperCutoff].
 * - ENHANCEMENT (4): 1 below Cutoff, Gain above.
 * - BAND_EXAGGERATION (5): Gain in [Cutoff, UpperCutoff], 1 outside.
 * - HEAT_DIFFUSION (6): exp(-Time omega^2), the heat kernel after time Time.
 * - CUSTOM (7): piecewise linear through the control points (omega, gain), constant beyond them.
 *
 * Units (CutoffUnits) of Cutoff, UpperCutoff, the omega of the control points and Time:
 * - FRACTION_OF_HIGHEST (1, the default): a fraction of the highest computed frequency
 *   omega_max = sqrt(lambda_{m-1}); the default low pass at 0.5 keeps about the lowest quarter of
 *   the computed harmonics on any model at any scale.
 * - HARMONIC_INDEX (2): the frequency of harmonic k (fractional k interpolates between two
 *   harmonics); with Transition 0 a low pass at k keeps the harmonics 0 to k.
 * - ABSOLUTE_FREQUENCY (0): radians per unit length of the mesh, omega = 2 pi / wavelength (the
 *   Frequency column of the spectrum); the same value means different things on models of
 *   different sizes.
 * In both relative units Time is in units of 1 / lambda_1 (lambda_1 the first non-zero
 * eigenvalue): Time 1 damps the lowest non-constant harmonic by exp(-1). Transition and Gain
 * have no units. The rule is spectral::ToAbsoluteUnits (Filters/Spectral/Filtering/Transfer.h).
 *
 * Errors and warnings: a negative (or non-finite) Cutoff, UpperCutoff or Time that the filter
 * kind uses is an error at execution (the setters accept it, so that what a panel shows is what
 * the filter reports on; the filter fails, as for any invalid parameter). A cutoff below the
 * first non-zero frequency or above the highest computed one is a warning that names both
 * frequencies and the gains that result; so is a basis of constant harmonics only, and a
 * cutoff that falls among the rounding-sized frequencies of the constant harmonics (those
 * components would move towards the origin).
 *
 * The filter keeps no state that affects its input: changing its parameters re-executes only
 * this filter, not the basis nor the transform upstream, so it can be driven interactively.
 *
 * @warning The basis is read in place (no copy). The cost is n * m * c multiply-adds per signal.
 * Missing basis arrays, or arrays that disagree on n or m, are errors.
 *
 * Example: Examples/Cxx/ManifoldHarmonicFilter.cxx. Test: Filters/Testing/Cxx/
 * TestSpectralFilter.cxx.
 *
 * @sa vtkManifoldHarmonicBasis vtkManifoldHarmonicTransform vtkWindowedSincPolyDataFilter
 */
#ifndef vtkSpectralFilter_h
#define vtkSpectralFilter_h

#include "vtkManifoldHarmonicsAlgorithm.h"
#include "vtkManifoldHarmonicsModule.h" // For export macro

#include <memory> // For the mesh figures

class vtkDoubleArray;
class vtkTable;
namespace vtkManifoldHarmonicsArrays
{
class MeshFiguresCache;
}

class VTKMANIFOLDHARMONICS_EXPORT vtkSpectralFilter : public vtkManifoldHarmonicsAlgorithm
{
public:
  ///@{
  /**
   * Standard methods for instantiation, type information, and printing.
   */
  static vtkSpectralFilter* New();
  vtkTypeMacro(vtkSpectralFilter, vtkManifoldHarmonicsAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  ///@}

  /**
   * The transfer functions: the one declaration of their values. The core's
   * spectral::FilterKind is converted from them by a checked switch (vtkSpectralFilter.cxx), and
   * the ParaView enumeration is checked against them by
   * Testing/ParaView/TestManifoldHarmonicsXMLDefaults.py.in.
   */
  enum FilterKinds
  {
    LOW_PASS = 0,
    HIGH_PASS = 1,
    BAND_PASS = 2,
    BAND_STOP = 3,
    ENHANCEMENT = 4,
    BAND_EXAGGERATION = 5,
    HEAT_DIFFUSION = 6,
    CUSTOM = 7
  };

  /**
   * How the cutoffs and the heat time are given (see the class documentation): the one
   * declaration of their values, converted to spectral::FrequencyUnits by a checked switch
   * (vtkSpectralFilter.cxx) and checked against the ParaView enumeration by
   * Testing/ParaView/TestManifoldHarmonicsXMLDefaults.py.in.
   */
  enum CutoffUnitsType
  {
    ABSOLUTE_FREQUENCY = 0,
    FRACTION_OF_HIGHEST = 1,
    HARMONIC_INDEX = 2
  };

  ///@{
  /**
   * Units of Cutoff, UpperCutoff, the control points' omega and Time. Default is
   * FRACTION_OF_HIGHEST (with Cutoff spectral::DefaultCutoffFraction = 0.5).
   */
  vtkSetClampMacro(CutoffUnits, int, ABSOLUTE_FREQUENCY, HARMONIC_INDEX);
  vtkGetMacro(CutoffUnits, int);
  void SetCutoffUnitsToAbsoluteFrequency() { this->SetCutoffUnits(ABSOLUTE_FREQUENCY); }
  void SetCutoffUnitsToFractionOfHighest() { this->SetCutoffUnits(FRACTION_OF_HIGHEST); }
  void SetCutoffUnitsToHarmonicIndex() { this->SetCutoffUnits(HARMONIC_INDEX); }
  ///@}

  ///@{
  /**
   * The transfer function F (see the class documentation). Default is LOW_PASS.
   */
  vtkSetClampMacro(FilterKind, int, LOW_PASS, CUSTOM);
  vtkGetMacro(FilterKind, int);
  void SetFilterKindToLowPass() { this->SetFilterKind(LOW_PASS); }
  void SetFilterKindToHighPass() { this->SetFilterKind(HIGH_PASS); }
  void SetFilterKindToBandPass() { this->SetFilterKind(BAND_PASS); }
  void SetFilterKindToBandStop() { this->SetFilterKind(BAND_STOP); }
  void SetFilterKindToEnhancement() { this->SetFilterKind(ENHANCEMENT); }
  void SetFilterKindToBandExaggeration() { this->SetFilterKind(BAND_EXAGGERATION); }
  void SetFilterKindToHeatDiffusion() { this->SetFilterKind(HEAT_DIFFUSION); }
  void SetFilterKindToCustom() { this->SetFilterKind(CUSTOM); }
  ///@}

  ///@{
  /**
   * Cutoff frequency omega_c, in CutoffUnits: the edge of LOW_PASS, HIGH_PASS and ENHANCEMENT,
   * the lower band edge of the band kinds. Compare with the Frequency column of the transform's
   * spectrum. Valid range [0, VTK_DOUBLE_MAX]: a negative value is an error at execution.
   * Default is spectral::DefaultCutoffFraction = 0.5 (of the highest computed frequency).
   */
  vtkSetMacro(Cutoff, double);
  vtkGetMacro(Cutoff, double);
  ///@}

  ///@{
  /**
   * Upper band edge of BAND_PASS, BAND_STOP and BAND_EXAGGERATION, in CutoffUnits; must not be
   * below Cutoff (an error at execution, as a negative value). Default is 1 (the highest
   * computed frequency).
   */
  vtkSetMacro(UpperCutoff, double);
  vtkGetMacro(UpperCutoff, double);
  ///@}

  ///@{
  /**
   * Width of each smooth step relative to its cutoff: the step runs over
   * [omega_c (1 - Transition/2), omega_c (1 + Transition/2)]. 0 is a sharp step. Range [0, 2].
   * Default is 0.1.
   */
  vtkSetClampMacro(Transition, double, 0.0, 2.0);
  vtkGetMacro(Transition, double);
  ///@}

  ///@{
  /**
   * Gain of ENHANCEMENT (above Cutoff) and BAND_EXAGGERATION (inside the band). Default is 2.
   */
  vtkSetMacro(Gain, double);
  vtkGetMacro(Gain, double);
  ///@}

  ///@{
  /**
   * Diffusion time t of HEAT_DIFFUSION, F = exp(-t omega^2); 0 is the identity, large t leaves
   * the mass-weighted mean. In units of 1 / lambda_1 with relative CutoffUnits, in squared units
   * of length with ABSOLUTE_FREQUENCY. A negative value is an error at execution. Default is 0.
   */
  vtkSetMacro(Time, double);
  vtkGetMacro(Time, double);
  ///@}

  ///@{
  /**
   * Control points (omega, gain) of the CUSTOM transfer function, with strictly increasing
   * omega; F is linear between them and constant beyond the first and the last. Default:
   * (0, 1) and (1, 0), a linear ramp from 1 to 0. SetNumberOfControlPoints keeps the first
   * points and appends (0, 1) points, to be set with SetControlPoint (ParaView sets the count,
   * then each point).
   */
  void SetNumberOfControlPoints(int count);
  int GetNumberOfControlPoints();
  void SetControlPoint(int index, double omega, double gain);
  void GetControlPoint(int index, double point[2]);
  void AddControlPoint(double omega, double gain);
  void RemoveAllControlPoints();
  ///@}

  ///@{
  /**
   * Re-inject the frequencies above the last computed harmonic, scaled by the mean gain of F
   * between omega_m and the Nyquist frequency (eq. 10 of Vallet and Levy). Off drops them: the
   * output is then made of the m harmonics only. Default is on.
   */
  vtkSetMacro(ReinjectHighFrequencies, bool);
  vtkGetMacro(ReinjectHighFrequencies, bool);
  vtkBooleanMacro(ReinjectHighFrequencies, bool);
  ///@}

  ///@{
  /**
   * Replace the point-data arrays by their filtered version (same name) instead of adding
   * `<Array>_Filtered`. The point coordinates are always replaced. Default is off.
   */
  vtkSetMacro(ReplaceInput, bool);
  vtkGetMacro(ReplaceInput, bool);
  vtkBooleanMacro(ReplaceInput, bool);
  ///@}

  /**
   * Suffix of the filtered arrays added when ReplaceInput is off: `_Filtered`.
   */
  static const char* FilteredSuffix();

  /**
   * The spectrum table of output port 1 ("Spectrum"), one row per harmonic: `Index` (k),
   * `Frequency` (omega_k), `Gain` (F(omega_k)) and, per filtered signal, `<Signal>_Magnitude`
   * (norm of the coefficient tuple before filtering) and `<Signal>_Filtered_Magnitude` (after).
   * It is recomputed whenever a parameter changes, so a line chart of it shows the transfer
   * function over the spectrum. In a distributed run only process 0 fills it.
   */
  vtkTable* GetSpectrumOutput();

  /**
   * Name of the gain column of the spectrum table: `Gain`.
   */
  static const char* GainColumnName();

  ///@{
  /**
   * Slider ranges for the ParaView panel, in CutoffUnits, from the basis of the last execution
   * (results, not parameters): FrequencyRange (for Cutoff and UpperCutoff) is [0, omega_max],
   * omega_max = sqrt(lambda_{m-1}) the highest computed frequency, in ABSOLUTE_FREQUENCY; [0, 1]
   * in FRACTION_OF_HIGHEST; [0, m - 1] in HARMONIC_INDEX. TimeRange is [0, 4 / lambda_1] in
   * ABSOLUTE_FREQUENCY, [0, 4] in relative units: up to where heat diffusion has damped the
   * lowest non-constant harmonic to exp(-4).
   * The zero eigenvalues of the constant harmonics are told from the others by
   * spectral::IsZeroEigenvalue (Filters/Spectral/Common/Eigenvalues.h) with the scale omega_N^2
   * (omega_N the Nyquist frequency, see the class documentation). Before the first
   * execution, and after one on a basis of constant harmonics only, [0, 1] and [0, 1] (or
   * [0, m - 1] for harmonic indices, [0, 2] for absolute frequencies): the panel takes its default
   * values from these ranges (Cutoff at the middle, UpperCutoff at the top, Time at the bottom),
   * which keeps them at the defaults 0.5, 1 and 0.
   */
  vtkGetVector2Macro(FrequencyRange, double);
  vtkGetVector2Macro(TimeRange, double);
  ///@}

  /**
   * The Nyquist frequency omega_N = pi / (mean edge length) of the input of the last execution
   * (a result, like the slider ranges; 0 before the first execution or without a triangle of
   * finite size). It bounds the re-injection and tells the zero eigenvalues of the constant
   * harmonics from the others.
   */
  vtkGetMacro(NyquistFrequency, double);

protected:
  vtkSpectralFilter();
  ~vtkSpectralFilter() override;

  /// The stages of a request (see vtkManifoldHarmonicsAlgorithm for errors and aborts).
  int Execute(vtkPointSet* input, vtkPointSet* output, vtkTable* spectrum) override;
  const char* GetWorkName() override { return "Spectral filter"; }

  int FilterKind;
  int CutoffUnits;
  double Cutoff;
  double UpperCutoff;
  double Transition;
  double Gain;
  double Time;
  bool ReinjectHighFrequencies;
  bool ReplaceInput;
  vtkDoubleArray* ControlPoints;

  /**
   * The edge sums of the input's cells (ghost cells left out) behind the Nyquist frequency of the
   * re-injection, computed once per input object and MTime: when only the filter's settings
   * change, the mesh is not walked again.
   */
  std::unique_ptr<vtkManifoldHarmonicsArrays::MeshFiguresCache> MeshFigures;

  double FrequencyRange[2];
  double TimeRange[2];
  double NyquistFrequency = 0.0;

private:
  vtkSpectralFilter(const vtkSpectralFilter&) = delete;
  void operator=(const vtkSpectralFilter&) = delete;
};

#endif
