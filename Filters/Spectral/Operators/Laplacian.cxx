// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Operators/Laplacian.h"

#include "Operators/IntrinsicDelaunay.h"

#include <string>

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
} // anonymous namespace

//------------------------------------------------------------------------------
DiscreteLaplacian AssembleLaplacian(const PreparedMesh& prepared,
  const LaplacianOptions& options,
  const Monitor& monitor)
{
  DiscreteLaplacian out;
  const TriangleMesh& mesh = prepared.Mesh;
  const bool consistent = options.Mass == MassKind::Consistent;
  if (options.Laplacian == LaplacianKind::IntrinsicDelaunay)
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
  return out;
}

//------------------------------------------------------------------------------
std::vector<std::string> PreparationWarnings(const PreparedMesh& prepared)
{
  std::vector<std::string> warnings;
  if (prepared.DegenerateTriangles > 0)
  {
    warnings.push_back("Left out " + std::to_string(prepared.DegenerateTriangles) +
      " degenerate (zero-area) triangles.");
  }
  if (prepared.DuplicateTriangles > 0)
  {
    warnings.push_back("Left out " + std::to_string(prepared.DuplicateTriangles) +
      " duplicated triangles (the same three points as another triangle, in either "
      "orientation).");
  }
  if (prepared.UnusedPoints > 0)
  {
    warnings.push_back(std::to_string(prepared.UnusedPoints) +
      (prepared.UnusedPoints == 1 ? " point is used by no triangle; its harmonics are 0."
                                  : " points are used by no triangle; their harmonics are 0."));
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
