// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Seams.h
 * @brief The one seam rule of every path (serial, gather to process 0, distributed SLEPc):
 *        which points are one point, and which copy of a welded point owns it.
 *
 * WeldPoints takes the points in one order (a piece's points; the pieces' points in rank order):
 * a point within `tolerance` times the diagonal of `bounds` of the first copy of a welded point
 * met before it is merged into the earliest such welded point; otherwise it starts a welded
 * point of its own. A point with a NaN or infinite coordinate stays apart.
 *
 * The owner rule: the copy that owns a welded point (counts it in sums over points, numbers it
 * in a distributed solve) is its first copy that `owned` marks (nonzero: not a ghost copy of
 * another piece's point), or its first copy if none is marked (or `owned` is empty). In rank
 * order this is the lowest rank that holds the point as its own.
 *
 * Used by vtkManifoldHarmonicsParallel (the serial weld and the gather) and by
 * Distributed/Numbering.cxx (the SLEPc numbering); tested by Filters/Testing/Cxx/TestWeldSeams.cxx
 * (serial), Testing/ParaView/TestParallelManifoldHarmonics.py.in (gather) and
 * Testing/Core/TestDistributed.cxx (OwnersFollowTheOwnerRule: the SLEPc numbering's owners).
 */
#ifndef spectral_Seams_h
#define spectral_Seams_h

#include <vector>

namespace spectral
{
/// The default seam tolerance: points within this fraction of the bounding box diagonal are one
/// point (pieces, or the faces of an unwelded mesh, may compute a shared point differently: a
/// sphere's 0 and 360 degree meridians differ by 1e-16 in sin(2 pi)).
constexpr double DefaultSeamTolerance = 1e-12;

/// The welding of a list of points (see the file documentation).
struct Welding
{
  /// Map[i]: the welded point of point i; welded points are numbered in order of first copy.
  std::vector<long long> Map;
  /// First[j]: the first copy of welded point j (it gives the coordinates).
  std::vector<long long> First;
  /// Counted[j]: the copy of welded point j that owns it (the owner rule).
  std::vector<long long> Counted;
  /// Whether some points were merged.
  bool Merged() const { return this->First.size() < this->Map.size(); }
  /// Whether point i is the copy that owns its welded point.
  bool Owns(long long i) const
  {
    return this->Counted[static_cast<std::size_t>(this->Map[static_cast<std::size_t>(i)])] == i;
  }
};

/**
 * The welding of the n points `xyz` (row-major, n by 3). `bounds` (xmin, xmax, ymin, ymax, zmin,
 * zmax) gives the diagonal (pass the same on every process); nullptr means the bounding box of
 * the finite points. `owned`: one flag per point (nonzero: the piece's own point), or empty.
 */
Welding WeldPoints(const double* xyz,
  long long n,
  const double* bounds,
  double tolerance,
  const std::vector<unsigned char>& owned = {});
} // namespace spectral

#endif
