// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Operators/Laplacian.h"

#include "Operators/IntrinsicDelaunay.h"

#include <string>
#include <utility>

namespace spectral
{
namespace
{
//------------------------------------------------------------------------------
// The intrinsic Delaunay operators, with a warning about the edges that could not be flipped.
void AssembleIntrinsic(const TriangleMesh& mesh,
  bool consistent,
  const Monitor& monitor,
  DiscreteLaplacian& out)
{
  const IntrinsicTriangulation T = IntrinsicDelaunay(mesh, monitor);
  out.Warnings = IntrinsicDelaunayWarnings(T);
  out.Stiffness = IntrinsicCotanStiffness(T);
  out.LumpedMass = IntrinsicLumpedMass(T);
  out.Mass = consistent ? IntrinsicConsistentMass(T) : spectral::Diagonal(out.LumpedMass);
}

//------------------------------------------------------------------------------
// The rows and columns `keep` of A (explicit zeros kept, so that the pattern stays the graph).
SparseMatrix Restrict(const SparseMatrix& A, const std::vector<int>& compact, Eigen::Index size)
{
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(A.nonZeros()));
  for (int j = 0; j < A.outerSize(); ++j)
  {
    const int column = compact[static_cast<std::size_t>(j)];
    if (column < 0)
    {
      continue;
    }
    for (SparseMatrix::InnerIterator it(A, j); it; ++it)
    {
      const int row = compact[static_cast<std::size_t>(it.row())];
      if (row >= 0)
      {
        entries.emplace_back(row, column, it.value());
      }
    }
  }
  SparseMatrix R(size, size);
  R.setFromTriplets(entries.begin(), entries.end());
  R.makeCompressed();
  return R;
}

//------------------------------------------------------------------------------
// Dirichlet conditions: the boundary points leave the operators (the harmonics vanish there).
void EliminateBoundary(const TriangleMesh& mesh, DiscreteLaplacian& out)
{
  const std::vector<char> boundary = BoundaryPoints(mesh);
  const Eigen::Index n = mesh.Vertices.rows();
  std::vector<int> compact(static_cast<std::size_t>(n), -1);
  std::vector<int> ids;
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < n; ++i)
  {
    if (!boundary[static_cast<std::size_t>(i)])
    {
      compact[static_cast<std::size_t>(i)] = static_cast<int>(kept.size());
      kept.push_back(i);
      ids.push_back(out.InputPointIds[static_cast<std::size_t>(i)]);
    }
  }
  const Eigen::Index interior = static_cast<Eigen::Index>(kept.size());
  if (interior == n)
  {
    out.Warnings.push_back("BoundaryCondition Dirichlet is ignored: the surface is closed (no "
                           "boundary edges), so the harmonics satisfy no boundary condition.");
    return;
  }
  if (interior == 0)
  {
    throw InvalidInput("every point lies on the boundary: with BoundaryCondition Dirichlet no "
                       "harmonic is left; refine the mesh or choose Neumann");
  }
  out.Stiffness = Restrict(out.Stiffness, compact, interior);
  out.Mass = Restrict(out.Mass, compact, interior);
  out.LumpedMass = Vector(out.LumpedMass(kept));
  out.InputPointIds = std::move(ids);
  out.Components = LabelComponents(out.Stiffness);
  out.ConstantHarmonics = false;
  out.BoundaryPoints = static_cast<int>(n - interior);
}
} // anonymous namespace

//------------------------------------------------------------------------------
DiscreteLaplacian AssembleLaplacian(const PreparedMesh& prepared,
  const LaplacianOptions& options,
  const Monitor& monitor)
{
  DiscreteLaplacian out;
  const TriangleMesh& mesh = prepared.Mesh;
  const bool consistent = options.Mass == MassKind::Consistent;
  const bool intrinsic = options.Laplacian == LaplacianKind::IntrinsicDelaunay;
  if (intrinsic && mesh.IsVolume())
  {
    out.Warnings.push_back("The intrinsic Delaunay Laplacian is for triangle surfaces: the "
                           "tetrahedra get the cotangent (P1) Laplacian.");
  }
  if (intrinsic && !mesh.IsVolume())
  {
    AssembleIntrinsic(mesh, consistent, monitor, out);
  }
  else
  {
    out.Stiffness = CotanStiffness(mesh);
    out.LumpedMass = LumpedMass(mesh);
    out.Mass = consistent ? ConsistentMass(mesh) : spectral::Diagonal(out.LumpedMass);
  }
  out.InputPointIds = prepared.InputPointIds;
  out.Components = LabelComponents(mesh);
  out.Diameter = BoundingBoxDiagonal(mesh.Vertices);
  if (options.Boundary == BoundaryCondition::Dirichlet)
  {
    EliminateBoundary(mesh, out);
  }
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::string> PreparationWarnings(const PreparedMesh& prepared)
{
  std::vector<std::string> warnings;
  const std::string cells = prepared.Volume ? " tetrahedra" : " triangles";
  const std::string cell = prepared.Volume ? " tetrahedron" : " triangle";
  if (prepared.DegenerateTriangles > 0)
  {
    warnings.push_back("Left out " + std::to_string(prepared.DegenerateTriangles) +
      (prepared.Volume ? " degenerate (zero-volume)" : " degenerate (zero-area)") + cells + ".");
  }
  if (prepared.DuplicateTriangles > 0)
  {
    warnings.push_back("Left out " + std::to_string(prepared.DuplicateTriangles) + " duplicated" +
      cells + " (the same" + (prepared.Volume ? " four" : " three") + " points as another" + cell +
      ", in either orientation).");
  }
  if (prepared.UnusedPoints > 0)
  {
    warnings.push_back(std::to_string(prepared.UnusedPoints) +
      (prepared.UnusedPoints == 1 ? " point is used by no" + cell + "; its harmonics are 0."
                                  : " points are used by no" + cell + "; their harmonics are 0."));
  }
  if (prepared.SmallComponents > 0)
  {
    warnings.push_back("Left out " + std::to_string(prepared.SmallComponents) +
      (prepared.SmallComponents == 1 ? " connected component" : " connected components") +
      " smaller than MinimumComponentSize (" + std::to_string(prepared.SmallComponentPoints) +
      " points): their harmonics and mass are 0.");
  }
  return warnings;
}
} // namespace spectral
