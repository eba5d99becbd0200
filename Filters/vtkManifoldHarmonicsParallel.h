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

#include "Spectral/Filtering/Transfer.h"

#include "vtkSmartPointer.h"

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
/// The default of vtkManifoldHarmonicBasis::SeamTolerance: points within this fraction of the
/// bounding box diagonal are one point (pieces, or the faces of an unwelded mesh, may compute a
/// shared point differently: a sphere's 0 and 360 degree meridians differ by 1e-16 in sin(2 pi)).
constexpr double SeamTolerance = 1e-12;

/**
 * The seam rule of every path (serial, gather to process 0, SLEPc): which points are one point.
 * A point within `tolerance` times the diagonal of `bounds` of the first copy of a welded point
 * met before it (in the order given) is merged into the earliest such welded point; otherwise it
 * starts a welded point of its own. `bounds` gives the diagonal (the same on every process),
 * nullptr means the bounding box of the finite points. A point with a NaN or infinite coordinate
 * stays apart (the solver reports it if a cell uses it). The point that stands for a welded point
 * in sums over points is its first copy that `owned` marks (nonzero), or its first copy if none is
 * marked (or `owned` is empty); the other copies are flagged
 * vtkManifoldHarmonicsGhosts::NotOwnedPointFlag so that they count zero times.
 */
struct Welding
{
  /// Map[i]: the welded point of point i; welded points are numbered in order of first copy.
  std::vector<vtkIdType> Map;
  /// First[j]: the first copy of welded point j (it gives the coordinates).
  std::vector<vtkIdType> First;
  /// Counted[j]: the copy of welded point j that sums over points count (see above).
  std::vector<vtkIdType> Counted;
  /// Whether some points were merged.
  bool Merged() const { return this->First.size() < this->Map.size(); }
};

/// The welding of the n points `xyz` (row-major, n by 3), see Welding.
Welding WeldPoints(const double* xyz,
  vtkIdType n,
  const double* bounds,
  double tolerance,
  const std::vector<unsigned char>& owned = {});

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
};

/**
 * Send every process the rows of its points. On process 0 `ok` says whether the solve
 * succeeded and `harmonics` (merged n by m), `mass` (merged n) and `eigenvalues` (m) hold its
 * result; other processes pass empty values. \return false on every process if process 0 failed.
 */
bool ScatterBasis(vtkMultiProcessController* controller,
  bool ok,
  const MergedMesh& merged,
  const spectral::RowMatrix& harmonics,
  const spectral::Vector& mass,
  const spectral::Vector& eigenvalues,
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
