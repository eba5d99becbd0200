// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkManifoldHarmonicSmoothing
 * @brief One-step low-pass smoothing of a surface in its manifold harmonic basis.
 *
 * vtkManifoldHarmonicSmoothing computes the basis of its input with an internal
 * vtkManifoldHarmonicBasis, kept between executions, and runs on it the stages of
 * vtkManifoldHarmonicTransform and of a LOW_PASS vtkSpectralFilter (the same functions,
 * vtkManifoldHarmonicsStages.h) on the point coordinates; it returns the input with the smoothed
 * point coordinates: the coordinates keep their harmonics below the cutoff frequency and lose those
 * above (B. Vallet and B. Levy, "Spectral Geometry Processing with Manifold Harmonics", Computer
 * Graphics Forum 27(2), 2008, section 5).
 *
 * The cutoff is given relative to the spectrum that is computed: the cutoff frequency is
 * CutoffFraction * omega_max, where omega_max = sqrt(lambda_{m-1}) is the frequency of the
 * highest of the m = NumberOfHarmonics harmonics. So CutoffFraction 0.5 keeps about the lowest
 * quarter of the harmonics (on a surface the number of harmonics below omega grows like
 * omega^2), and 1 keeps (nearly) all of them. The step from gain 1 to gain 0 is a raised cosine
 * of relative width 0.1 around the cutoff (vtkSpectralFilter::Transition). This is
 * vtkSpectralFilter's Cutoff in its FRACTION_OF_HIGHEST units, by the same rule
 * (spectral::ToAbsoluteUnits), and with the same default (spectral::DefaultCutoffFraction).
 * The warnings of the internal stages (a point cloud, a cutoff outside the spectrum) are this
 * filter's.
 *
 * Input: any vtkPointSet with polygons (triangulated internally) or linear 3-D cells (split into
 * tetrahedra internally; see vtkManifoldHarmonicBasis). Output: the input (cells, point
 * and cell data) with smoothed points of the same precision; no basis array is added. For the
 * harmonics, the spectrum or other transfer functions, use the three filters themselves. As with
 * VTK's smoothers, point normals of the input are passed on unchanged and describe the unsmoothed
 * surface: recompute them downstream (vtkPolyDataNormals).
 *
 * Parameters:
 * - NumberOfHarmonics (default vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS): the m
 *   harmonics computed; more harmonics keep finer details below the cutoff and cost more time
 *   (see vtkManifoldHarmonicBasis).
 * - CutoffFraction (default 0.5, range [0.001, 1]): the cutoff as a fraction of omega_max.
 * - BasisPrecision (default vtkManifoldHarmonicBasis::DOUBLE): the precision of the internal
 *   basis; FLOAT halves its memory and changes the smoothed points by float round-off only.
 * - NumberOfThreads (default 0, all cores): the threads of the eigensolve and of the transform
 *   and filter stages.
 * - Solver (default vtkManifoldHarmonicBasis::BUILT_IN), SlepcPartitions (default 1) and
 *   SlepcOptions (default none): the eigensolver of the basis and its settings (see
 *   vtkManifoldHarmonicBasis::SetSolver); SLEPC solves distributed over the MPI processes.
 * - WeldSeams (default on) and SeamTolerance (default 1e-12 of the bounding box diagonal): the
 *   seam rule of the basis (vtkManifoldHarmonicBasis::SetWeldSeams): coincident points are one
 *   point and all their copies move alike, so seams stay closed.
 *
 * - MemoryLimit (default 0: the memory the system reports available) and Storage (default
 *   AUTOMATIC): where the basis lives. IN_MEMORY keeps the internal basis (n * m values) between
 *   executions; STREAMED never holds it: the eigensolver hands each verified band of harmonics
 *   to the transform and filter stages, which add its contribution and let it go
 *   (spectral::StreamedFilter, Filters/Spectral/Streaming.h), so memory is the mesh, the sparse
 *   factor and a few bands' vectors, whatever m (spectral::EstimateStreamedMemory), in bands
 *   smaller than the automatic ones (down to spectral::SmallestPlannedBand eigenpairs) where
 *   those do not fit (spectral::PlanStreamedMemory; the basis warns). AUTOMATIC
 *   keeps the basis in memory when its estimate (spectral::EstimateBasisMemory, the basis
 *   filter's check) fits in MemoryLimit (or the available memory), and streams otherwise, with
 *   a warning saying so and why; GetChosenStorage tells which ran. Only what cannot run at all is
 *   refused: STREAMED (or AUTOMATIC) when even the streamed estimate does not fit (the error
 *   names the memory that would let it run), IN_MEMORY when the basis does not fit (the basis
 *   filter's error). STREAMED runs serially with the Built-in solver: in a distributed run or
 *   with the SLEPc solver it is refused, and AUTOMATIC keeps the basis in memory (the basis
 *   filter's parallel paths, and their memory checks).
 *
 * The filter keeps its internal basis between executions (IN_MEMORY): when only CutoffFraction
 * changes (a slider in ParaView), it re-runs the cheap filter stage alone. A new input,
 * NumberOfHarmonics or BasisPrecision recomputes the basis. STREAMED has no basis to keep: every
 * execution, a new CutoffFraction included, solves again: the highest eigenvalue first, since
 * the cutoff is relative to the highest frequency (with one connected component a few inertia
 * counts and one short band; with several, the whole spectrum), then the harmonics below the
 * end of the low pass's transition alone (those above it have gain 0: spectral::StreamedFilter,
 * about a quarter of them at CutoffFraction 0.5), less work than the basis in memory;
 * for interactive filtering of a basis larger than memory, compute it once with
 * vtkManifoldHarmonicBasis and filter it with vtkManifoldHarmonicTransform and
 * vtkSpectralFilter. The streamed result equals the in-memory one to round-off
 * (TestManifoldHarmonicSmoothing.StreamedSameAsInMemory). Progress covers the eigensolve, and an
 * abort stops it and leaves the output empty.
 *
 * @warning The cost of IN_MEMORY is that of vtkManifoldHarmonicBasis: n * m doubles (floats with
 * BasisPrecision FLOAT) and an eigensolve, and the basis stays in memory with the filter.
 *
 * Test: Filters/Testing/Cxx/TestManifoldHarmonicSmoothing.cxx.
 *
 * @sa vtkManifoldHarmonicBasis vtkManifoldHarmonicTransform vtkSpectralFilter
 * vtkWindowedSincPolyDataFilter
 */
#ifndef vtkManifoldHarmonicSmoothing_h
#define vtkManifoldHarmonicSmoothing_h

#include "vtkManifoldHarmonicBasis.h" // For BasisPrecisionType, DEFAULT_NUMBER_OF_HARMONICS
#include "vtkManifoldHarmonicsAlgorithm.h"
#include "vtkManifoldHarmonicsModule.h" // For export macro
#include "vtkSmartPointer.h"            // For the internal basis
#include "vtkWeakPointer.h"             // For the internal basis

#include <memory> // For the mesh figures
#include <string> // For SlepcOptions

class vtkPointSet;
namespace vtkManifoldHarmonicsArrays
{
class MeshFiguresCache;
}

class VTKMANIFOLDHARMONICS_EXPORT vtkManifoldHarmonicSmoothing
  : public vtkManifoldHarmonicsAlgorithm
{
public:
  ///@{
  /**
   * Standard methods for instantiation, type information, and printing.
   */
  static vtkManifoldHarmonicSmoothing* New();
  vtkTypeMacro(vtkManifoldHarmonicSmoothing, vtkManifoldHarmonicsAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;
  ///@}

  ///@{
  /**
   * Number m of harmonics to compute (lowest frequencies first): at least 1 (a smaller value is
   * refused with an error and the previous value kept), clamped at execution to the number of
   * points triangles use. It must exceed the number of connected components of the surface,
   * whose harmonics are constant (frequency 0): with no other harmonic the execution fails with
   * an error and an empty output. Default is vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS.
   */
  virtual void SetNumberOfHarmonics(int m);
  vtkGetMacro(NumberOfHarmonics, int);
  ///@}

  ///@{
  /**
   * Cutoff frequency as a fraction of the highest computed frequency omega_max =
   * sqrt(lambda_{m-1}): harmonics below CutoffFraction * omega_max are kept, those above are
   * removed. Smaller is smoother. Range [0.001, 1]. Default is 0.5
   * (spectral::DefaultCutoffFraction, also vtkSpectralFilter's default Cutoff).
   */
  vtkSetClampMacro(CutoffFraction, double, 0.001, 1.0);
  vtkGetMacro(CutoffFraction, double);
  ///@}

  ///@{
  /**
   * Precision of the basis computed internally, passed on to
   * vtkManifoldHarmonicBasis::SetBasisPrecision: one of vtkManifoldHarmonicBasis'
   * BasisPrecisionType values (declared there only). vtkManifoldHarmonicBasis::FLOAT halves
   * the memory of its n x m harmonics; the eigensolver still works in double and the smoothed
   * points differ from DOUBLE's by float round-off. Default is vtkManifoldHarmonicBasis::DOUBLE.
   */
  vtkSetClampMacro(BasisPrecision,
    int,
    vtkManifoldHarmonicBasis::FLOAT,
    vtkManifoldHarmonicBasis::DOUBLE);
  vtkGetMacro(BasisPrecision, int);
  void SetBasisPrecisionToFloat() { this->SetBasisPrecision(vtkManifoldHarmonicBasis::FLOAT); }
  void SetBasisPrecisionToDouble() { this->SetBasisPrecision(vtkManifoldHarmonicBasis::DOUBLE); }
  ///@}

  ///@{
  /**
   * The boundary condition of the harmonics, passed on to
   * vtkManifoldHarmonicBasis::SetBoundaryCondition: vtkManifoldHarmonicBasis::NEUMANN (the
   * boundary moves freely) or vtkManifoldHarmonicBasis::DIRICHLET (the boundary points stay
   * where they are: the smoothing passes them through unchanged). Default is
   * vtkManifoldHarmonicBasis::NEUMANN.
   */
  vtkSetClampMacro(BoundaryCondition,
    int,
    vtkManifoldHarmonicBasis::NEUMANN,
    vtkManifoldHarmonicBasis::DIRICHLET);
  vtkGetMacro(BoundaryCondition, int);
  ///@}

  ///@{
  /**
   * The neighbours of each point of a point cloud, passed on to
   * vtkManifoldHarmonicBasis::SetNumberOfNeighbors (not used for meshes). Range [2,
   * VTK_INT_MAX]. Default is vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_NEIGHBORS.
   */
  vtkSetClampMacro(NumberOfNeighbors, int, 2, VTK_INT_MAX);
  vtkGetMacro(NumberOfNeighbors, int);
  ///@}

  ///@{
  /**
   * The eigensolver of the internal basis, one of vtkManifoldHarmonicBasis' SolverType values
   * (declared there only): vtkManifoldHarmonicBasis::BUILT_IN or vtkManifoldHarmonicBasis::SLEPC
   * (needs vtkManifoldHarmonicBasis::HasSlepc()). Default is vtkManifoldHarmonicBasis::BUILT_IN.
   */
  vtkSetClampMacro(Solver,
    int,
    vtkManifoldHarmonicBasis::BUILT_IN,
    vtkManifoldHarmonicBasis::SLEPC);
  vtkGetMacro(Solver, int);
  void SetSolverToBuiltIn() { this->SetSolver(vtkManifoldHarmonicBasis::BUILT_IN); }
  void SetSolverToSlepc() { this->SetSolver(vtkManifoldHarmonicBasis::SLEPC); }
  ///@}

  ///@{
  /**
   * SLEPc's partitions and options of the internal basis (SLEPC only): see
   * vtkManifoldHarmonicBasis::SetSlepcPartitions and SetSlepcOptions. Defaults are 1 and "".
   */
  vtkSetClampMacro(SlepcPartitions, int, 1, VTK_INT_MAX);
  vtkGetMacro(SlepcPartitions, int);
  vtkSetStdStringFromCharMacro(SlepcOptions);
  vtkGetCharFromStdStringMacro(SlepcOptions);
  ///@}

  ///@{
  /**
   * The seam rule of the internal basis: see vtkManifoldHarmonicBasis::SetWeldSeams and
   * SetSeamTolerance. Defaults are on and 1e-12; SeamTolerance range [0, 0.1].
   */
  vtkSetMacro(WeldSeams, bool);
  vtkGetMacro(WeldSeams, bool);
  vtkBooleanMacro(WeldSeams, bool);
  vtkSetClampMacro(SeamTolerance, double, 0.0, 0.1);
  vtkGetMacro(SeamTolerance, double);
  ///@}

  ///@{
  /**
   * The memory the basis may take, in MiB: see vtkManifoldHarmonicBasis::SetMemoryLimit, whose
   * estimate and message it uses (the one home of its meaning); here it also decides the
   * AUTOMATIC Storage. 0 means the memory the system reports available. Range [0,
   * VTK_DOUBLE_MAX]. Default is 0.
   */
  vtkSetClampMacro(MemoryLimit, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  /// Where the basis lives (see the class documentation).
  enum StorageType
  {
    AUTOMATIC = 0,
    IN_MEMORY = 1,
    STREAMED = 2
  };

  ///@{
  /**
   * Where the basis lives: AUTOMATIC (in memory when it fits in MemoryLimit, else streamed),
   * IN_MEMORY (kept between executions) or STREAMED (never held; every execution solves again).
   * See the class documentation. Default is AUTOMATIC.
   */
  vtkSetClampMacro(Storage, int, AUTOMATIC, STREAMED);
  vtkGetMacro(Storage, int);
  void SetStorageToAutomatic() { this->SetStorage(AUTOMATIC); }
  void SetStorageToInMemory() { this->SetStorage(IN_MEMORY); }
  void SetStorageToStreamed() { this->SetStorage(STREAMED); }
  ///@}

  /// The storage the last execution used: IN_MEMORY or STREAMED (AUTOMATIC before any).
  vtkGetMacro(ChosenStorage, int);

protected:
  vtkManifoldHarmonicSmoothing();
  ~vtkManifoldHarmonicSmoothing() override;

  /// The stages of a request (see vtkManifoldHarmonicsAlgorithm for errors and aborts).
  int Execute(vtkPointSet* input, vtkPointSet* output, vtkTable* table) override;
  const char* GetWorkName() override { return "Manifold harmonic smoothing"; }

  int NumberOfHarmonics;
  double CutoffFraction;
  int BasisPrecision;
  int BoundaryCondition;
  int NumberOfNeighbors;
  int Solver;
  int SlepcPartitions;
  std::string SlepcOptions;
  bool WeldSeams;
  double SeamTolerance;
  double MemoryLimit;
  int Storage;
  int ChosenStorage;

private:
  /// The internal basis's input becomes a shallow copy of `input` when the input changed.
  void UpdateBasisInput(vtkPointSet* input);
  /// The internal basis with this filter's settings, updated. \return false after an abort.
  bool UpdateBasis();
  /// The internal basis's settings: this filter's (`memoryLimit` in MiB).
  void ConfigureBasis(double memoryLimit);
  /// IN_MEMORY or STREAMED for this input (a warning when AUTOMATIC streams); -1 after an
  /// error (reported): what cannot run at all.
  int ChooseStorage(vtkPointSet* input);
  /// The STREAMED execution: the low pass of the points while the basis streams.
  int ExecuteStreamed(vtkPointSet* input, vtkPointSet* output);
  /// The basis's progress as 0 to 0.9 of this filter's; passes an abort on to the basis.
  void ForwardProgress(vtkObject* caller, unsigned long event, void* data);

  // The internal basis, kept between executions so that a new cutoff reuses it.
  vtkSmartPointer<vtkPointSet> Input;    // shallow copy of the input, replaced when it changes
  vtkWeakPointer<vtkPointSet> InputData; // the input object of that copy
  vtkMTimeType InputTime = 0;            // and its MTime then
  vtkSmartPointer<vtkManifoldHarmonicBasis> Basis;
  // The edge sums of the basis's output (the Nyquist frequency), once per basis.
  std::unique_ptr<vtkManifoldHarmonicsArrays::MeshFiguresCache> MeshFigures;

  vtkManifoldHarmonicSmoothing(const vtkManifoldHarmonicSmoothing&) = delete;
  void operator=(const vtkManifoldHarmonicSmoothing&) = delete;
};

#endif
