// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsArrays.h
 * @brief Private helpers of the filters: VTK arrays as Eigen matrices and back.
 *
 * They find and check the arrays of vtkManifoldHarmonicBasis on a data set, view VTK arrays as
 * Eigen matrices (without a copy for vtkDoubleArray), write Eigen matrices back into VTK
 * arrays and fill the spectrum tables. Array names come from vtkManifoldHarmonicsNames.h; no
 * filter's header is included. The basis array may be a vtkDoubleArray or a vtkFloatArray
 * (BasisPrecision); both are read in place. Not installed and not wrapped: this header includes
 * Eigen.
 */
#ifndef vtkManifoldHarmonicsArrays_h
#define vtkManifoldHarmonicsArrays_h

#include "Spectral/Filtering/Transfer.h"

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkDataArray;
class vtkDoubleArray;
class vtkPolyData;
class vtkTable;

namespace vtkManifoldHarmonicsArrays
{
/// The basis arrays of a data set as written by vtkManifoldHarmonicBasis.
struct Basis
{
  /// n tuples of m components, vtkDoubleArray or vtkFloatArray: component k of tuple i is H^k_i.
  vtkDataArray* Harmonics = nullptr;
  /// n tuples, one component: the lumped mass D_ii.
  vtkDataArray* Mass = nullptr;
  /// m tuples, one component, ascending.
  vtkDataArray* Eigenvalues = nullptr;
  vtkIdType NumberOfPoints = 0;
  int NumberOfHarmonics = 0;
  /// The memory of Harmonics: one of the two is set, by FindBasis.
  const double* Doubles = nullptr;
  const float* Floats = nullptr;

  /**
   * spectral::ForwardTransform on the harmonics in place, in their precision, on `threads`
   * threads (0: the core's default, see Common/Threads.h).
   */
  spectral::RowMatrix ForwardTransform(const spectral::Vector& mass,
    const spectral::ConstRowView& X,
    int threads) const;
  /**
   * spectral::FilterSignal (inverse transform with re-injection, points of zero mass kept) on
   * the harmonics in place, in their precision, on `threads` threads (0: the core's default).
   */
  spectral::RowMatrix FilterSignal(const spectral::Vector& mass,
    const spectral::Vector& gains,
    const spectral::ConstRowView& coefficients,
    const spectral::ConstRowView& X,
    double hfGain,
    int threads) const;
  /// The mass as a vector of length n.
  spectral::Vector MassVector() const;
  /// The eigenvalues as a vector of length m.
  spectral::Vector EigenvalueVector() const;
};

/**
 * Find the basis arrays on a data set and check that they agree with it and with each other.
 * \return An empty string on success, otherwise a message naming the missing or inconsistent
 *         array and the filter that produces it.
 */
std::string FindBasis(vtkPolyData* input, Basis& basis);

/**
 * The values of a data array as an n by c row-major matrix of doubles: a view of the array's
 * memory for a vtkDoubleArray, a copy converted once to double for any other array type.
 */
class Signal
{
public:
  explicit Signal(vtkDataArray* array);
  spectral::ConstRowView View() const;

private:
  spectral::RowMatrix Converted;
  const double* Data = nullptr;
  Eigen::Index Rows = 0;
  Eigen::Index Cols = 0;
};

/// A vtkDoubleArray of rows tuples with cols components holding a copy of values.
vtkSmartPointer<vtkDoubleArray> NewDoubleArray(const spectral::RowMatrix& values, const char* name);

/**
 * A new array of the same type as `prototype` (NewInstance) holding `values`. Integer types get
 * the values rounded to the nearest integer and clamped to the range of the type.
 */
vtkSmartPointer<vtkDataArray> NewArrayLike(vtkDataArray* prototype,
  const spectral::RowMatrix& values,
  const char* name);

/// A signal of the spectrum table: its name and its m by c coefficients.
struct SpectrumSignal
{
  std::string Name;
  spectral::RowMatrix Coefficients;
};

/**
 * Fill the spectrum table (output port 1) of vtkManifoldHarmonicTransform and of
 * vtkSpectralFilter, one row per harmonic k: `Index` (k), `Eigenvalue` (lambda_k, with
 * `eigenvalueColumn`), `Frequency` (omega_k = sqrt(max(lambda_k, 0))), `Gain` (gains_k, when
 * `gains` is given), then per signal `<Signal>_Magnitude` (the norm of coefficient row k) and,
 * with gains, `<Signal>_Filtered_Magnitude` (|gains_k| times it). Names from
 * vtkManifoldHarmonicsNames.h.
 */
void FillSpectrum(vtkTable* table,
  const spectral::Vector& lambda,
  bool eigenvalueColumn,
  const spectral::Vector* gains,
  const std::vector<SpectrumSignal>& signals);

/**
 * The message of a filter that needs the basis arrays and did not find them: why they are
 * missing (an input without polygons, which vtkManifoldHarmonicBasis passes through without a
 * basis) or which filter to run upstream.
 */
std::string MissingBasisAdvice(vtkPolyData* input);
/**
 * The triangles of the polygons (as fans) and strips of a mesh, with all its points, ghost
 * cells left out (vtkManifoldHarmonicsGhosts::CountedCells): what the mean edge length behind
 * the Nyquist frequency is measured on (vtkSpectralFilter, vtkSpectralDescriptors).
 */
spectral::TriangleMesh SurfaceTriangles(vtkPolyData* input);

/**
 * The sum of the edge lengths of the SurfaceTriangles of `input` (each triangle's three edges)
 * and their number: added over the processes of a distributed run, they give the Nyquist
 * frequency of the whole surface, spectral::NyquistFrequency(sums[0], sums[1]).
 */
std::vector<double> EdgeSums(vtkPolyData* input);
} // namespace vtkManifoldHarmonicsArrays

#endif
