// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Numbering.h
 * @brief Global point numbers and connected components of a mesh distributed in pieces, without
 *        gathering it.
 *
 * Only the border points of a piece (BorderPoints in Operators.h) can be held by another piece:
 * every process receives the border points of all (O(sqrt n) per piece on a surface, O(n^(2/3))
 * in a volume, not the mesh) and merges them with the one seam rule (Common/Seams.h, WeldPoints
 * in rank order, the same on every process). The owner of a point is the copy the owner rule
 * names (the first copy in rank order that its piece holds as its own); each process numbers its
 * owned points contiguously after those of the lower ranks. Collective over `comm`.
 */
#ifndef spectral_Distributed_Numbering_h
#define spectral_Distributed_Numbering_h

#include "Common/Mesh.h"

#include <petscvec.h>

#include <vector>

namespace spectral
{
namespace distributed
{
/// Global numbers of the used points of this piece.
struct Numbering
{
  /// For each point of the piece: its global number and whether this process owns it.
  std::vector<PetscInt> Global;
  std::vector<char> Owned;
  PetscInt OwnedCount = 0;
  PetscInt Total = 0;
};

/**
 * The numbering of `mesh` (this process's piece, its points all used). `bounds` (the global
 * bounding box, the same on every process) scales the seam tolerance; `ownedPoints` flags the
 * piece's own points (empty: all); without `weld` every point is its own.
 */
Numbering NumberPoints(MPI_Comm comm,
  const TriangleMesh& mesh,
  const double bounds[6],
  bool weld,
  double tolerance,
  const std::vector<unsigned char>& ownedPoints);

/// The connected components of the whole mesh and what the solve needs of them.
struct Components
{
  /// The component (0..Count-1) of each point of the piece.
  std::vector<int> Label;
  int Count = 0;
  /// Per component, summed over all processes' owned points: the lumped mass (1_j^T D 1_j for
  /// the consistent mass too, whose rows sum to the lumped one) and the number of points.
  std::vector<double> Mass;
  std::vector<long long> Points;
  /// The components by decreasing number of points (ties by label): the order of their zero
  /// eigenvalues, as the core's (Components.cxx).
  std::vector<int> Order;
};

/**
 * The connected components of the distributed mesh (collective). Each process labels the
 * components of its own cells; the border points, the only links between local components, are
 * exchanged as (global number, local component) pairs; every process unites the local
 * components that share a point the same way and numbers them by their first local component in
 * rank order. Masses (from `lumped`, the distributed lumped mass) and point counts are summed
 * over the owned points of all processes.
 */
Components DistributedComponents(MPI_Comm comm,
  const TriangleMesh& mesh,
  const Numbering& numbering,
  Vec lumped);
} // namespace distributed
} // namespace spectral

#endif
