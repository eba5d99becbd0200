// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkManifoldHarmonicTransform
 * @brief Manifold harmonic coefficients of the point coordinates and of point-data arrays.
 *
 * vtkManifoldHarmonicTransform projects signals defined on the points of a mesh onto its
 * manifold harmonics H^0 ... H^{m-1}, the eigenvectors computed by vtkManifoldHarmonicBasis.
 * For a signal x with c components per point, coefficient k is
 *
 *   x~_k = sum_i x_i D_ii H^k_i,
 *
 * the inner product of x and H^k weighted by the lumped mass D (B. Vallet and B. Levy,
 * "Spectral Geometry Processing with Manifold Harmonics", Computer Graphics Forum 27(2), 2008,
 * section 3.3). It is the discrete counterpart of a Fourier transform on the surface: small k are
 * the smooth, large-scale parts of x, large k the fine details. It is exact for a basis computed
 * with the lumped mass (the default); a basis computed with the consistent mass is orthonormal
 * for D only to discretization error, and so are its coefficients.
 *
 * Input: the output of vtkManifoldHarmonicBasis, i.e. any vtkPointSet (a surface or a volume)
 * with the point-data arrays
 * `ManifoldHarmonics` (n tuples of m components) and `ManifoldHarmonicsMass` (n values) and the
 * field-data array `ManifoldHarmonicsEigenvalues` (m values, ascending). Their names come from
 * vtkManifoldHarmonicBasis::HarmonicsArrayName(), MassArrayName() and EigenvaluesArrayName().
 *
 * Output port 0: a shallow copy of the input plus, for every transformed signal, a field-data
 * vtkDoubleArray `<Signal>_Coefficients` of m tuples with as many components as the signal. The
 * point coordinates are the signal `Points` (PointsName()), hence `Points_Coefficients`.
 *
 * Output port 1 ("Spectrum"): a vtkTable of m rows with the columns `Index` (k), `Eigenvalue`
 * (lambda_k), `Frequency` (omega_k = sqrt(max(lambda_k, 0))) and, per signal,
 * `<Signal>_Magnitude`, the Euclidean norm of the coefficient tuple: ready for a line chart of
 * the spectrum against the frequency.
 *
 * Parameters:
 * - TransformPoints (default on): transform the point coordinates.
 * - PointDataArraySelection (default: nothing enabled): the point-data arrays to transform. Any
 *   numeric type and any number of components; arrays that are not double are converted to double
 *   once. The basis arrays themselves are never transformed.
 * - NumberOfThreads (default 0, all cores): the threads the transform runs on.
 *
 * Progress is reported after each signal; an abort (AbortExecute) leaves both outputs empty.
 *
 * The coefficients feed vtkSpectralFilter, which multiplies them by a transfer function and
 * reconstructs the signals.
 *
 * Distributed runs: each process sums over its own points (points flagged DUPLICATEPOINT in the
 * point ghost array count 0) and the coefficients are then added over all processes, so every
 * process gets the coefficients of the whole surface. The spectrum table is filled on process 0
 * only, so that ParaView, which appends the tables of all processes, shows it once.
 *
 * @warning The harmonics are read in place (no copy of the n by m basis). The transform costs
 * n * m * c multiply-adds per signal. Missing basis arrays, or arrays that disagree on n or m,
 * are errors.
 *
 * Example: Examples/Cxx/ManifoldHarmonicFilter.cxx. Test: Filters/Testing/Cxx/
 * TestManifoldHarmonicTransform.cxx.
 *
 * @sa vtkManifoldHarmonicBasis vtkSpectralFilter
 */
#ifndef vtkManifoldHarmonicTransform_h
#define vtkManifoldHarmonicTransform_h

#include "vtkManifoldHarmonicsAlgorithm.h"
#include "vtkManifoldHarmonicsModule.h" // For export macro

class vtkCallbackCommand;
class vtkDataArraySelection;
class vtkTable;

class VTKMANIFOLDHARMONICS_EXPORT vtkManifoldHarmonicTransform
  : public vtkManifoldHarmonicsAlgorithm
{
public:
  ///@{
  /**
   * Standard methods for instantiation, type information, and printing.
   */
  static vtkManifoldHarmonicTransform* New();
  vtkTypeMacro(vtkManifoldHarmonicTransform, vtkManifoldHarmonicsAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  ///@}

  ///@{
  /**
   * Transform the point coordinates into the field-data array `Points_Coefficients`
   * (m tuples of 3 components) and the spectrum column `Points_Magnitude`. Default on.
   */
  vtkSetMacro(TransformPoints, bool);
  vtkGetMacro(TransformPoints, bool);
  vtkBooleanMacro(TransformPoints, bool);
  ///@}

  /**
   * The point-data arrays to transform: an array is transformed when it is listed and enabled
   * (e.g. `GetPointDataArraySelection()->EnableArray("Normals")`). Default: empty, so only the
   * coordinates are transformed. Changing the selection modifies this filter.
   */
  vtkDataArraySelection* GetPointDataArraySelection();

  /**
   * The spectrum table of output port 1 (columns Index, Eigenvalue, Frequency and one
   * `<Signal>_Magnitude` per transformed signal).
   */
  vtkTable* GetSpectrumOutput();

  ///@{
  /**
   * Names used in the output: the suffix of coefficient arrays (`_Coefficients`), the suffix of
   * the spectrum columns (`_Magnitude`), the signal name of the point coordinates (`Points`) and
   * the first three spectrum columns (`Index`, `Eigenvalue`, `Frequency`).
   */
  static const char* CoefficientsSuffix();
  static const char* MagnitudeSuffix();
  static const char* PointsName();
  static const char* IndexColumnName();
  static const char* EigenvalueColumnName();
  static const char* FrequencyColumnName();
  ///@}

protected:
  vtkManifoldHarmonicTransform();
  ~vtkManifoldHarmonicTransform() override;

  /// The stages of a request (see vtkManifoldHarmonicsAlgorithm for errors and aborts).
  int Execute(vtkPointSet* input, vtkPointSet* output, vtkTable* spectrum) override;
  const char* GetWorkName() override { return "Manifold harmonic transform"; }

  bool TransformPoints;
  vtkDataArraySelection* PointDataArraySelection;
  vtkCallbackCommand* SelectionObserver;

private:
  vtkManifoldHarmonicTransform(const vtkManifoldHarmonicTransform&) = delete;
  void operator=(const vtkManifoldHarmonicTransform&) = delete;
};

#endif
