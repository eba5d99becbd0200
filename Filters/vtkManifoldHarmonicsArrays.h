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
#include "vtkWeakPointer.h"

#include <string>
#include <vector>

class vtkDataArray;
class vtkDataSet;
class vtkDoubleArray;
class vtkInformationVector;
class vtkPointSet;
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
std::string FindBasis(vtkDataSet* input, Basis& basis);

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
 * Whether the input holds a spectrum without harmonics (vtkManifoldHarmonicBasis with
 * EigenvaluesOnly): the eigenvalues and the mass, no harmonics array.
 */
bool IsSpectrumOnly(vtkDataSet* input);

/**
 * The message of a filter that needs the basis arrays and did not find them: why they are
 * missing (an input without polygons or volume cells, which vtkManifoldHarmonicBasis passes
 * through without a basis; a spectrum computed with EigenvaluesOnly, IsSpectrumOnly) or which
 * filter to run upstream.
 */
std::string MissingBasisAdvice(vtkDataSet* input);

/**
 * The error of the point-data array `name` whose values are not finite (NaN or infinity) at
 * points of the surface, which makes `what` ("its transform") undefined, with `remedy` ("Deselect
 * the array"): the transform's and the functional map's one text.
 */
std::string NotFiniteOnSurface(const std::string& name, const char* what, const char* remedy);

/**
 * The cells of any vtkPointSet in the core's form (spectral::TriangleMesh), with what the
 * conversion did to them. Every point of the input is a point of the mesh; ghost cells are
 * left out (the rule of vtkManifoldHarmonicsGhosts.h).
 *
 * - 2-D cells: triangles as they are; the module's one polygon rule for the rest, in every kind
 *   of point set: quadrilaterals and polygons split by vtkPolygon::Triangulate (ear cutting,
 *   concave ones too, as vtkTriangleFilter does), triangle strips into their triangles, pixels
 *   along the diagonal from their point 0 to their point 3.
 * - 3-D cells: tetrahedra as they are; hexahedra, voxels, wedges and pyramids split into
 *   tetrahedra, conformingly: each cell is coned from its point of smallest id over the faces
 *   that do not hold it, and each quadrilateral face is split along the diagonal through its
 *   point of smallest id, so two cells that share a face split it alike.
 * - vertices and lines are left out (a point set with no other cell is a point cloud).
 * - any other cell (quadratic, polyhedral, ...) is counted as unsupported.
 * Every one of these interpretations that changes what the harmonics describe is said in
 * Warnings() or PointCloudWarning().
 */
struct CoreMesh
{
  spectral::TriangleMesh Mesh;
  /// 2-D and 3-D input cells.
  vtkIdType SurfaceCells = 0;
  vtkIdType VolumeCells = 0;
  /// 2-D cells other than triangles split into triangles; 3-D cells other than tetrahedra split
  /// into tetrahedra.
  vtkIdType SplitPolygons = 0;
  vtkIdType SplitVolumeCells = 0;
  /// Vertex and line cells (left out), and cells of a kind the module does not take.
  vtkIdType VertexCells = 0;
  vtkIdType LineCells = 0;
  vtkIdType UnsupportedCells = 0;
  /// The class name of the first unsupported cell.
  std::string UnsupportedType;

  /// Whether there is a surface or a volume to compute harmonics on.
  bool HasCells() const { return this->SurfaceCells + this->VolumeCells > 0; }
  /// Whether the input is a point cloud: points, and no cell but vertices.
  bool IsPointCloud() const;
  /// Why the cells cannot be used (2-D and 3-D cells mixed, unsupported cells); empty if they
  /// can.
  std::string Problem() const;
  /// What the conversion changed or left out, one sentence each: cells split, vertex and line
  /// cells left out beside surface or volume cells, edges shared by more than two triangles
  /// (non-manifold: the harmonics join the sheets that meet there).
  std::vector<std::string> Warnings() const;
  /// For a point cloud (IsPointCloud), that it is solved as one: the point count, the setting
  /// that applies (numberOfNeighbors) and what to do if the cells were lost; empty otherwise.
  std::string PointCloudWarning(int numberOfNeighbors) const;
};

/// Convert the cells of a point set (see CoreMesh).
CoreMesh ToCoreMesh(vtkPointSet* input);

/// Whether ToCoreMesh(input) would give cells or a point cloud (HasCells() || IsPointCloud()),
/// from the cell types alone, without converting the mesh.
bool HasCellsOrIsPointCloud(vtkPointSet* input);

/**
 * RequestDataObject of the filters whose first output has the type of their input (any
 * vtkPointSet): makes output port 0 an instance of the input's class; other ports keep the
 * types their FillOutputPortInformation names.
 */
int OutputLikeInput(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

/**
 * The sum of the edge lengths of the cells of `input` (ToCoreMesh, ghost cells left out) and
 * their number (spectral::EdgeCount), or for a point cloud its spectral::CloudEdgeSums: added
 * over the processes of a distributed run, they give
 * the Nyquist frequency of the whole mesh, spectral::NyquistFrequency(sums[0], sums[1]).
 */
std::vector<double> EdgeSums(vtkPointSet* input);
/// EdgeSums of an input already converted by ToCoreMesh.
std::vector<double> EdgeSums(const CoreMesh& cells);

/// What the filters downstream of the basis need of the mesh itself, on this process (the rest
/// they read from the basis arrays): its EdgeSums and whether its cells are a volume.
struct MeshFigures
{
  std::vector<double> EdgeSums = { 0.0, 0.0 };
  bool IsVolume = false;
};

/**
 * The one adapter between an input and its MeshFigures: the cells are converted (ToCoreMesh)
 * once per input object and modification time. A filter keeps one and asks it on every
 * execution, so that changing the filter's settings alone does not walk the mesh again; another
 * input object is converted even with the same MTime.
 */
class MeshFiguresCache
{
public:
  const MeshFigures& Of(vtkPointSet* input);

private:
  vtkWeakPointer<vtkPointSet> Input;
  vtkMTimeType Time = 0;
  MeshFigures Figures;
};
} // namespace vtkManifoldHarmonicsArrays

#endif
