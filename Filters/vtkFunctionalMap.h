// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkFunctionalMap
 * @brief Correspondence between two surfaces through their manifold harmonics (functional
 *        maps with ZoomOut refinement), attribute transfer and aligned harmonics.
 *
 * vtkFunctionalMap finds, for every point of a TARGET surface (input port 0), the point of a
 * SOURCE surface (input port 1, SetSourceConnection / SetSourceData) it corresponds to, by the
 * functional map of Ovsjanikov et al. ("Functional Maps: A Flexible Representation of Maps
 * Between Shapes", ACM TOG 31(4), 2012): the k x k matrix C that takes the coefficients of a
 * function on the source (in its first k harmonics) to those of the same function on the target,
 * a_target = C a_source. C is estimated from the preservation of spectral descriptors (wave and
 * heat kernel signatures over several scales), commutativity with the two Laplacians and
 * optional landmarks, with InitialSize harmonics, then refined spectrally to FinalSize harmonics
 * (ZoomOut: Melzi et al., ACM TOG 38(6), 2019). The numerics are the core's
 * (Filters/Spectral/Filtering/FunctionalMap.h, spectral::ComputeFunctionalMap); this class reads
 * the inputs, runs it and writes the arrays.
 *
 * Inputs: each is either the output of vtkManifoldHarmonicBasis (the point array
 * `ManifoldHarmonics`, double or float, `ManifoldHarmonicsMass` and the field array
 * `ManifoldHarmonicsEigenvalues`; its basis is used as it is) or a plain surface, whose basis
 * the filter computes with an internal vtkManifoldHarmonicBasis (NumberOfHarmonics harmonics,
 * that filter's other defaults). The internal bases are kept between executions, one per input:
 * changing only the map or transfer settings does not solve them again; a new input object or a
 * modified one does.
 *
 * Output port 0: a shallow copy of the target plus
 * - `CorrespondingPointIds` (vtkIdTypeArray): the source point id of every target point; -1 for
 *   target points used by no triangle (zero mass: no harmonics, never matched).
 * - the transferred arrays (TransferArrays, default on): every point array of the source
 *   except its basis arrays, its ghost array and the arrays this filter writes, under the
 *   source array's name; when the target already has a point array of that name, under
 *   `<name>_Transferred` (the target's own array is kept). Each array is carried either through
 *   the point map (x_target(j) = x_source(CorrespondingPointIds[j]), exact values: labels, ids,
 *   any type) or through the functional map (x_target = Phi_target C Phi_source^T M_source
 *   x_source: a smooth field, no nearest-point staircase). By default floating-point arrays go
 *   through the functional map and every other array (integers, ids, strings) through the point
 *   map; SmoothArrays and LabelArrays name arrays that go the other way. An integer or
 *   non-numeric array in SmoothArrays is an error (its values would not be integers: make it a
 *   floating-point array first). Target points without a match get NaN (floating-point
 *   arrays), 0 (integer arrays) or an empty string.
 * - `AlignedHarmonics` (AlignHarmonics on, default off): the target's first FinalSize
 *   harmonics re-ordered, sign-flipped and, within groups of (nearly) equal eigenvalues, rotated
 *   so that harmonic k of the target matches harmonic k of the source through the map
 *   (spectral::AlignModes). Map every shape of a set to ONE reference shape (the reference as
 *   Source, each subject as Input) and harmonic k means the same on every subject: compare
 *   coefficients, filter or average across subjects.
 *
 * Output port 1: a vtkTable of the map C, k rows (target harmonics) and k columns
 * `SourceHarmonic_<j>` (one per source harmonic j): row i of column j is C_ij.
 *
 * Orientation: a shape with a mirror symmetry (a face, a body, a hand) has an
 * orientation-reversing map that preserves every descriptor as well as the right one;
 * descriptors alone may pick it (left and right swapped). The remedies: Landmarks (a few pairs
 * of corresponding points; almost free: L x NumberOfDescriptors more descriptor columns, and the
 * refinement keeps them as fixed pairs; one pair off every symmetry plane decides, two or three
 * are safer) and OrientationTerm (the orientation-preserving term of Ren et al., "Continuous and
 * Orientation-preserving Correspondences via Functional Maps", ACM TOG 37(6), 2018: no user
 * input, but one operator per tenth descriptor to build, O(F k^2) each for F triangles, and the
 * initial map becomes one dense system of k^2 unknowns, O(k^6): about 0.1 s at k = 30, a few
 * seconds at the limit InitialSize <= 60 (more is an error); it needs consistently oriented
 * triangles on both inputs (a warning counts the edges whose two triangles are oriented alike,
 * spectral::OrientationConflicts), and keeps the orientation they give: turn the target's
 * triangles over to ask for the mirror map; the refinement is unchanged).
 *
 * Errors (vtkErrorMacro, both outputs empty): a missing or empty input (points without cells
 * are a point cloud, as for vtkManifoldHarmonicBasis), a weight that is negative, infinite or
 * NaN, NaN or infinity in an array transferred through the functional map at a point of the
 * source's surface, an internal basis that fails (its error becomes this filter's one
 * message, naming the input; its warnings become this filter's), inconsistent basis arrays,
 * sizes larger than a basis, OrientationTerm with InitialSize above 60, landmark lists
 * of different lengths or with ids out of range, an array named in both SmoothArrays and
 * LabelArrays or missing from the source, an integer array in SmoothArrays, distributed runs
 * (several processes: both whole surfaces are needed on one process). An aborted execution
 * leaves both outputs empty.
 *
 * @warning Memory: the two bases (n x m doubles each, internal ones kept with the filter) and
 * n_target x FinalSize doubles for the point map search. Time: the bases' eigensolves, then
 * roughly (FinalSize - InitialSize) / ZoomOutStep nearest-neighbour searches in the spectral
 * embedding, on at most ZoomOutSamples points of each shape, and one on every point.
 *
 * Example: Examples/Python/functional_map.py. Tests: Filters/Testing/Cxx/TestFunctionalMap.cxx,
 * Testing/Core/TestFunctionalMap.cxx, Testing/ParaView/TestManifoldHarmonicsFunctionalMap.py.in.
 *
 * @sa vtkManifoldHarmonicBasis vtkSpectralDescriptors vtkManifoldHarmonicTransform
 */
#ifndef vtkFunctionalMap_h
#define vtkFunctionalMap_h

#include "vtkManifoldHarmonicsAlgorithm.h"
#include "vtkManifoldHarmonicsModule.h" // For export macro

#include <memory> // For the internal state
#include <string> // For the array lists
#include <vector> // For the array lists

class vtkAlgorithmOutput;
class vtkDataObject;
class vtkIdList;
class vtkTable;

class VTKMANIFOLDHARMONICS_EXPORT vtkFunctionalMap : public vtkManifoldHarmonicsAlgorithm
{
public:
  ///@{
  /**
   * Standard methods for instantiation, type information, and printing.
   */
  static vtkFunctionalMap* New();
  vtkTypeMacro(vtkFunctionalMap, vtkManifoldHarmonicsAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The table of the map C on output port 1 (GetOutput() is port 0's point set).
   */
  vtkTable* GetMapOutput();
  ///@}

  ///@{
  /**
   * The source shape (input port 1): the shape whose point ids CorrespondingPointIds holds and
   * whose arrays are transferred. The target is input port 0 (SetInputConnection).
   */
  void SetSourceConnection(vtkAlgorithmOutput* output);
  void SetSourceData(vtkDataObject* source);
  vtkDataObject* GetSource();
  ///@}

  ///@{
  /**
   * The number m of harmonics of the internal bases (inputs without basis arrays), at least 1.
   * It must be at least FinalSize. Default is vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS.
   */
  virtual void SetNumberOfHarmonics(int m);
  vtkGetMacro(NumberOfHarmonics, int);
  ///@}

  ///@{
  /**
   * Connected components of fewer points are left out of the internal bases (see
   * vtkManifoldHarmonicBasis::SetMinimumComponentSize): a scan's debris then takes no harmonic
   * and gets no corresponding point (-1). Inputs that carry their own basis are taken as they are.
   * Default is 0: every component.
   */
  vtkSetClampMacro(MinimumComponentSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(MinimumComponentSize, int);
  ///@}

  ///@{
  /**
   * The memory, in MiB, that the internal bases may take together (see
   * vtkManifoldHarmonicBasis::SetMemoryLimit, whose estimate, smaller bands and error they use):
   * each basis is computed within this limit less what the other one holds already. 0 uses
   * what the system reports available when each is computed. Range [0, VTK_DOUBLE_MAX].
   * Default is 0.
   */
  vtkSetClampMacro(MemoryLimit, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  ///@{
  /**
   * The size k of the map estimated from descriptors (the harmonics it uses on each shape).
   * 0 (the default, spectral::FunctionalMapOptions) takes min(30, FinalSize)
   * (spectral::DefaultFunctionalMapInitialSize); otherwise at least 1 and at most FinalSize.
   */
  vtkSetClampMacro(InitialSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(InitialSize, int);
  ///@}

  ///@{
  /**
   * The size k of the map after ZoomOut refinement, the size of the output table and of
   * AlignedHarmonics; equal to InitialSize: no refinement. 0 (the default,
   * spectral::FunctionalMapOptions) takes the harmonics both bases have, up to 100
   * (spectral::DefaultFunctionalMapFinalSize); otherwise at most the harmonics of either basis.
   */
  vtkSetClampMacro(FinalSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(FinalSize, int);
  ///@}

  ///@{
  /**
   * The growth of k per ZoomOut iteration: 1 (the default, spectral::DefaultZoomOutStep, as
   * Melzi et al.) is the most accurate, larger steps are faster. Range [1, VTK_INT_MAX].
   */
  vtkSetClampMacro(ZoomOutStep, int, 1, VTK_INT_MAX);
  vtkGetMacro(ZoomOutStep, int);
  ///@}

  ///@{
  /**
   * The ZoomOut iterations run on this many points of each shape (farthest-point samples,
   * landmarks included) when a shape has more; the final point map is on every point. 0: on
   * every point (slower on large scans: each iteration costs n_target x n_source x k).
   * Otherwise at least twice the final size (the core refuses less with an error).
   * Range [0, VTK_INT_MAX]. Default 2000 (spectral::DefaultZoomOutSamples).
   */
  vtkSetClampMacro(ZoomOutSamples, int, 0, VTK_INT_MAX);
  vtkGetMacro(ZoomOutSamples, int);
  ///@}

  ///@{
  /**
   * The number of descriptors (wave kernel energies) per shape of the initial estimate. Range
   * [1, VTK_INT_MAX]. Default 50 (spectral::DefaultNumberOfMapDescriptors).
   */
  vtkSetClampMacro(NumberOfDescriptors, int, 1, VTK_INT_MAX);
  vtkGetMacro(NumberOfDescriptors, int);
  ///@}

  ///@{
  /**
   * The weights of the terms of the initial estimate: descriptor preservation (default 1, must
   * be above 0), commutativity with the Laplacians (default 0.1,
   * spectral::DefaultCommutativityWeight), landmarks relative to the other descriptors (default 1,
   * spectral::DefaultLandmarkWeight) and orientation (default 0.1,
   * spectral::DefaultOrientationWeight, used with OrientationTerm). Each
   * term is divided by its own scale, so the weights are free of units. Range [0, inf): a
   * negative, infinite or NaN weight is an error when the filter runs (not clamped, which would
   * turn an infinite weight into a huge finite one).
   */
  vtkSetMacro(DescriptorWeight, double);
  vtkGetMacro(DescriptorWeight, double);
  vtkSetMacro(CommutativityWeight, double);
  vtkGetMacro(CommutativityWeight, double);
  vtkSetMacro(LandmarkWeight, double);
  vtkGetMacro(LandmarkWeight, double);
  vtkSetMacro(OrientationWeight, double);
  vtkGetMacro(OrientationWeight, double);
  ///@}

  ///@{
  /**
   * The orientation-preserving term (Ren et al. 2018) against orientation-reversing (mirror)
   * maps of symmetric shapes (see the class documentation for its cost); needs InitialSize at
   * most 60. Default off (spectral::FunctionalMapOptions).
   */
  vtkSetMacro(OrientationTerm, bool);
  vtkGetMacro(OrientationTerm, bool);
  vtkBooleanMacro(OrientationTerm, bool);
  ///@}

  ///@{
  /**
   * Landmarks: pairs of corresponding points, SourceLandmarks[i] on the source and
   * TargetLandmarks[i] on the target. Both lists must have the same length and ids of points of
   * their shape; they are checked at execution. Empty by default. The Set methods copy the list;
   * Add appends one id; RemoveAll empties a list (ParaView's properties use Add and RemoveAll).
   */
  void SetSourceLandmarks(vtkIdList* ids);
  void SetTargetLandmarks(vtkIdList* ids);
  vtkIdList* GetSourceLandmarks();
  vtkIdList* GetTargetLandmarks();
  void AddSourceLandmark(vtkIdType id);
  void AddTargetLandmark(vtkIdType id);
  void RemoveAllSourceLandmarks();
  void RemoveAllTargetLandmarks();
  ///@}

  ///@{
  /**
   * Whether the point arrays of the source are transferred to the target (see the class
   * documentation for which arrays and their names). Default on.
   */
  vtkSetMacro(TransferArrays, bool);
  vtkGetMacro(TransferArrays, bool);
  vtkBooleanMacro(TransferArrays, bool);
  ///@}

  ///@{
  /**
   * The source arrays transferred through the functional map although they would go through the
   * point map by default (a field stored as integers is refused: convert it first), and those
   * transferred through the point map although they are floating-point (labels stored as
   * floats, colours to copy exactly). Empty by default. An array in both lists, or missing from
   * the source, is an error.
   */
  void AddSmoothArray(const char* name);
  void RemoveAllSmoothArrays();
  int GetNumberOfSmoothArrays();
  const char* GetSmoothArray(int index);
  void AddLabelArray(const char* name);
  void RemoveAllLabelArrays();
  int GetNumberOfLabelArrays();
  const char* GetLabelArray(int index);
  ///@}

  ///@{
  /**
   * Whether to write `AlignedHarmonics`, the target's harmonics aligned to the source's (see
   * the class documentation). Default off.
   */
  vtkSetMacro(AlignHarmonics, bool);
  vtkGetMacro(AlignHarmonics, bool);
  vtkBooleanMacro(AlignHarmonics, bool);
  ///@}

  ///@{
  /**
   * The names this filter writes: the point arrays `CorrespondingPointIds` and
   * `AlignedHarmonics`, the suffix `_Transferred` of a transferred array whose name the target
   * already has, and the prefix `SourceHarmonic_` of the table's columns.
   */
  static const char* CorrespondingPointIdsArrayName();
  static const char* AlignedHarmonicsArrayName();
  static const char* TransferredSuffix();
  static const char* MapColumnPrefix();
  ///@}

  /// Includes the landmark lists' modification times.
  vtkMTimeType GetMTime() override;

protected:
  vtkFunctionalMap();
  ~vtkFunctionalMap() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// The stages of a request (see vtkManifoldHarmonicsAlgorithm for errors and aborts).
  int Execute(vtkPointSet* input, vtkPointSet* output, vtkTable* table) override;
  const char* GetWorkName() override { return "Functional map"; }

  int NumberOfHarmonics;
  int MinimumComponentSize;
  double MemoryLimit;
  int InitialSize;
  int FinalSize;
  int ZoomOutStep;
  int ZoomOutSamples;
  int NumberOfDescriptors;
  double DescriptorWeight;
  double CommutativityWeight;
  double LandmarkWeight;
  double OrientationWeight;
  bool OrientationTerm;
  bool TransferArrays;
  bool AlignHarmonics;
  std::vector<std::string> SmoothArrays;
  std::vector<std::string> LabelArrays;

private:
  struct Internals;
  /// The basis of the shape on `port`: its own arrays, or those of its internal basis, updated.
  /// \return false after an abort.
  bool UpdateBasis(int port, vtkPointSet* input, vtkPointSet*& withBasis);
  double BasisMemoryLimit(int port) const;
  /// The internal bases' progress as this filter's (the first half); passes an abort on.
  void ForwardProgress(vtkObject* caller, unsigned long event, void* data);
  /// Keeps the first error of an internal basis (or of its executive) during an update, which
  /// Execute reports as this filter's one error.
  void RecordBasisError(vtkObject* caller, unsigned long event, void* data);

  std::unique_ptr<Internals> Internal;

  vtkFunctionalMap(const vtkFunctionalMap&) = delete;
  void operator=(const vtkFunctionalMap&) = delete;
};

#endif
