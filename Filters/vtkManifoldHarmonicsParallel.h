// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsParallel.h
 * @brief Private helpers that make the manifold harmonic filters give the serial result when the
 *        mesh is distributed over several processes (pvbatch or pvserver under MPI).
 *
 * The basis is global: vtkManifoldHarmonicBasis gathers the pieces on process 0, merges the
 * points that pieces duplicate along their seams, solves there and sends every process the rows
 * of its own points. Ghost cells of the pieces are left out (vtkManifoldHarmonicsGhosts.h). A
 * point held several times (by several processes, or twice in one piece) is counted by its first
 * copy in rank order that its piece holds as its own (not as a ghost point; the first copy if
 * none does); the other copies are flagged vtkDataSetAttributes::DUPLICATEPOINT in the point
 * ghost array, so that the sums over points of vtkManifoldHarmonicTransform (then added over
 * processes) count it once. WeldPoints is this merge rule, shared by the serial run, the gather
 * and the SLEPc solver's numbering.
 *
 * Every function here is collective: all processes of the controller must call it, including
 * those without data. Not installed and not wrapped.
 */
#ifndef vtkManifoldHarmonicsParallel_h
#define vtkManifoldHarmonicsParallel_h

#include "Spectral/Common/Seams.h"
#include "Spectral/Filtering/Transfer.h"

#include "vtkSmartPointer.h"

#include <array>
#include <string>
#include <vector>

class vtkDataArray;
class vtkDataSet;
class vtkDoubleArray;
class vtkMultiProcessController;
class vtkPolyData;
class vtkUnsignedCharArray;

namespace vtkManifoldHarmonicsParallel
{
/// The default of vtkManifoldHarmonicBasis::SeamTolerance (Spectral/Common/Seams.h).
constexpr double SeamTolerance = spectral::DefaultSeamTolerance;

/// The seam rule of every path and its owner rule: Spectral/Common/Seams.h.
using spectral::Welding;
using spectral::WeldPoints;

/// The global controller when it has more than one process, otherwise nullptr (serial run).
vtkMultiProcessController* DistributedController();

/// Number of processes whose `hasData` is true (collective).
int CountRanks(vtkMultiProcessController* controller, bool hasData);

/// The piece of one process after the gather and merge: its points as rows of the merged mesh.
struct MergedMesh
{
  /// The merged triangle mesh (points and triangles only), valid on process 0.
  vtkSmartPointer<vtkPolyData> Surface;
  /// PointMaps[r][i]: merged id of point i of the piece of process r.
  std::vector<std::vector<vtkIdType>> PointMaps;
  /// Counted[r][i]: whether point i of the piece of process r is the copy of its merged point
  /// that sums over points count (WeldPoints, on the pieces in rank order; the owner is the
  /// process of that copy).
  std::vector<std::vector<bool>> Counted;
};

/**
 * Gather the triangle pieces (points, their point ghost flags and triangles; `piece` may be
 * empty, its ghost cells are already left out by vtkManifoldHarmonicsGhosts::CountedCells) on
 * process 0 and merge the points that coincide within `tolerance` of the bounding box diagonal
 * (WeldPoints), in one piece or across pieces. \return the merged mesh on process 0, an empty
 * MergedMesh elsewhere.
 */
MergedMesh GatherAndMerge(vtkMultiProcessController* controller,
  vtkPolyData* piece,
  double tolerance);

/// The rows of one process: harmonics (n_r by m), mass (n_r) and DUPLICATEPOINT flags (n_r) on
/// the points another process owns.
struct PieceBasis
{
  vtkSmartPointer<vtkDoubleArray> Harmonics;
  vtkSmartPointer<vtkDoubleArray> Mass;
  vtkSmartPointer<vtkUnsignedCharArray> Duplicates;
  spectral::Vector Eigenvalues;
  /// The worst pair's backward error and residual of the whole solve (the same on every
  /// process): the figures every basis output carries (AddSpectrumArrays).
  double MaxBackwardError = 0.0;
  double MaxResidual = 0.0;
};

/**
 * Send every process the rows of its points. On process 0 `ok` says whether the solve
 * succeeded and `harmonics` (merged n by m), `mass` (merged n), `eigenvalues` (m) and
 * `figures` (its MaxBackwardError and MaxResidual) hold its result; other processes pass empty
 * values. \return false on every process if process 0 failed.
 */
bool ScatterBasis(vtkMultiProcessController* controller,
  bool ok,
  const MergedMesh& merged,
  const spectral::RowMatrix& harmonics,
  const spectral::Vector& mass,
  const spectral::Vector& eigenvalues,
  const std::array<double, 2>& figures,
  PieceBasis& piece);

/// A named m by c matrix of coefficients (or any values to add over processes).
struct NamedMatrix
{
  std::string Name;
  spectral::RowMatrix Values;
};

/**
 * Sum the matrices of equal name over all processes; every process gets the union of the names
 * (in the order of first appearance by rank) with the sums. `eigenvalues` is not summed: the
 * first process that has some gives them to all. \return false (on every process) if two
 * processes disagree on the shape of a matrix of the same name.
 */
bool SumOverRanks(vtkMultiProcessController* controller,
  std::vector<NamedMatrix>& matrices,
  spectral::Vector& eigenvalues);

/// The sum of `values` over all processes, in place (collective).
void SumOverRanks(vtkMultiProcessController* controller, std::vector<double>& values);

} // namespace vtkManifoldHarmonicsParallel

#endif
