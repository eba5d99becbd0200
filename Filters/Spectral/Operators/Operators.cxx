// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Operators/Operators.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>

namespace spectral
{
namespace
{
using Point = Eigen::Vector3d;

Point Corner(const TriangleMesh& mesh, int f, int c)
{
  return mesh.Vertices.row(mesh.Faces(f, c)).transpose();
}

/// Twice the area of triangle f.
double DoubleArea(const TriangleMesh& mesh, int f)
{
  const Point a = Corner(mesh, f, 0);
  return (Corner(mesh, f, 1) - a).cross(Corner(mesh, f, 2) - a).norm();
}

bool IsDegenerate(const TriangleMesh& mesh, int f)
{
  const Point a = Corner(mesh, f, 0);
  const Point b = Corner(mesh, f, 1);
  const Point c = Corner(mesh, f, 2);
  const double longest =
    std::max({ (b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm() });
  const double doubleArea = (b - a).cross(c - a).norm();
  return !(doubleArea > 1e-12 * longest);
}

/**
 * Keeps the first of triangles with the same three corners (either orientation): `corners`
 * holds the sorted corners of each triangle of `kept`, in the same order; both are reduced to
 * the triangles kept, in their input order, and `duplicates` counts the others.
 */
void LeaveOutDuplicates(std::vector<std::array<int, 3>>& corners,
  std::vector<int>& kept,
  int& duplicates)
{
  std::vector<std::size_t> order(kept.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(),
    order.end(),
    [&corners](std::size_t a, std::size_t b) { return corners[a] < corners[b]; });
  std::vector<char> keep(kept.size(), 1);
  for (std::size_t i = 1; i < order.size(); ++i)
  {
    if (corners[order[i]] == corners[order[i - 1]])
    {
      keep[order[i]] = 0; // stable: the earlier input triangle stays
      ++duplicates;
    }
  }
  std::size_t next = 0;
  for (std::size_t i = 0; i < kept.size(); ++i)
  {
    if (keep[i])
    {
      kept[next++] = kept[i];
    }
  }
  kept.resize(next);
  corners.clear();
}

/// Union-find root with path halving.
int Root(std::vector<int>& parent, int i)
{
  while (parent[i] != i)
  {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}
} // namespace

//------------------------------------------------------------------------------
PreparedMesh PrepareMesh(const TriangleMesh& input)
{
  const int numPts = static_cast<int>(input.Vertices.rows());
  const int numTris = static_cast<int>(input.Faces.rows());
  for (int f = 0; f < numTris; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      const int id = input.Faces(f, c);
      if (id < 0 || id >= numPts)
      {
        throw InvalidInput("triangle " + std::to_string(f) + " refers to point " +
          std::to_string(id) + " but the mesh has " + std::to_string(numPts) + " points");
      }
      CheckCoordinates(input.Vertices, id);
    }
  }

  PreparedMesh out;
  std::vector<int> compact(numPts, -1);
  std::vector<int> kept;
  kept.reserve(numTris);
  std::vector<std::array<int, 3>> seen; // sorted corners of the kept triangles
  seen.reserve(numTris);
  for (int f = 0; f < numTris; ++f)
  {
    if (IsDegenerate(input, f))
    {
      ++out.DegenerateTriangles;
      continue;
    }
    std::array<int, 3> corners = { input.Faces(f, 0), input.Faces(f, 1), input.Faces(f, 2) };
    std::sort(corners.begin(), corners.end());
    seen.push_back(corners);
    kept.push_back(f);
  }
  LeaveOutDuplicates(seen, kept, out.DuplicateTriangles);
  for (int f : kept)
  {
    for (int c = 0; c < 3; ++c)
    {
      compact[input.Faces(f, c)] = 0;
    }
  }
  for (int i = 0; i < numPts; ++i)
  {
    if (compact[i] == 0)
    {
      compact[i] = static_cast<int>(out.InputPointIds.size());
      out.InputPointIds.push_back(i);
    }
  }
  out.UnusedPoints = numPts - static_cast<int>(out.InputPointIds.size());

  out.Mesh.Vertices.resize(static_cast<Eigen::Index>(out.InputPointIds.size()), 3);
  for (std::size_t i = 0; i < out.InputPointIds.size(); ++i)
  {
    out.Mesh.Vertices.row(static_cast<Eigen::Index>(i)) = input.Vertices.row(out.InputPointIds[i]);
  }
  out.Mesh.Faces.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t t = 0; t < kept.size(); ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      out.Mesh.Faces(static_cast<Eigen::Index>(t), c) = compact[input.Faces(kept[t], c)];
    }
  }
  return out;
}

//------------------------------------------------------------------------------
void CheckCoordinates(const Points& points, Eigen::Index id)
{
  if (!points.row(id).allFinite())
  {
    throw InvalidInput("point " + std::to_string(id) +
      " has a NaN or infinite coordinate; remove or repair it before computing harmonics");
  }
  const double magnitude = points.row(id).cwiseAbs().maxCoeff();
  if (magnitude > MaxCoordinate)
  {
    char value[32];
    std::snprintf(value, sizeof(value), "%g", magnitude);
    throw InvalidInput("point " + std::to_string(id) + " has a coordinate of magnitude " + value +
      ", beyond 1e75 where triangle areas overflow; rescale the mesh");
  }
}

//------------------------------------------------------------------------------
SparseMatrix CotanStiffness(const TriangleMesh& mesh)
{
  TriangleAssembly assembly(mesh.Vertices.rows(), mesh.Faces.rows(), 12);
  for (int f = 0; f < mesh.Faces.rows(); ++f)
  {
    if (IsDegenerate(mesh, f))
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      // Corner c is opposite the edge (i, j).
      const int k = mesh.Faces(f, c);
      const int i = mesh.Faces(f, (c + 1) % 3);
      const int j = mesh.Faces(f, (c + 2) % 3);
      const Point u = mesh.Vertices.row(i).transpose() - mesh.Vertices.row(k).transpose();
      const Point v = mesh.Vertices.row(j).transpose() - mesh.Vertices.row(k).transpose();
      assembly.AddEdgeWeight(i, j, 0.5 * u.dot(v) / u.cross(v).norm());
    }
  }
  return assembly.Matrix();
}

//------------------------------------------------------------------------------
Vector LumpedMass(const TriangleMesh& mesh)
{
  Vector d = Vector::Zero(mesh.Vertices.rows());
  for (int f = 0; f < mesh.Faces.rows(); ++f)
  {
    const double third = DoubleArea(mesh, f) / 6.0;
    for (int c = 0; c < 3; ++c)
    {
      d[mesh.Faces(f, c)] += third;
    }
  }
  return d;
}

//------------------------------------------------------------------------------
SparseMatrix ConsistentMass(const TriangleMesh& mesh)
{
  TriangleAssembly assembly(mesh.Vertices.rows(), mesh.Faces.rows(), 9);
  for (int f = 0; f < mesh.Faces.rows(); ++f)
  {
    assembly.AddMassBlock(
      mesh.Faces(f, 0), mesh.Faces(f, 1), mesh.Faces(f, 2), 0.5 * DoubleArea(mesh, f));
  }
  return assembly.Matrix();
}

//------------------------------------------------------------------------------
TriangleAssembly::TriangleAssembly(Eigen::Index n, Eigen::Index triangles, int perTriangle)
  : Size(n)
{
  this->Triplets.reserve(static_cast<std::size_t>(triangles * perTriangle + n));
  for (Eigen::Index i = 0; i < n; ++i)
  {
    this->Triplets.emplace_back(static_cast<int>(i), static_cast<int>(i), 0.0);
  }
}

//------------------------------------------------------------------------------
void TriangleAssembly::AddEdgeWeight(int i, int j, double w)
{
  this->Triplets.emplace_back(i, j, -w);
  this->Triplets.emplace_back(j, i, -w);
  this->Triplets.emplace_back(i, i, w);
  this->Triplets.emplace_back(j, j, w);
}

//------------------------------------------------------------------------------
void TriangleAssembly::AddMassBlock(int a, int b, int c, double area)
{
  const int corners[3] = { a, b, c };
  for (int r = 0; r < 3; ++r)
  {
    for (int q = 0; q < 3; ++q)
    {
      this->Triplets.emplace_back(corners[r], corners[q], area * (r == q ? 1.0 / 6.0 : 1.0 / 12.0));
    }
  }
}

//------------------------------------------------------------------------------
SparseMatrix TriangleAssembly::Matrix() const
{
  SparseMatrix A(this->Size, this->Size);
  A.setFromTriplets(this->Triplets.begin(), this->Triplets.end());
  A.makeCompressed();
  return A;
}

//------------------------------------------------------------------------------
SparseMatrix Diagonal(const Vector& d)
{
  SparseMatrix D(d.size(), d.size());
  D.reserve(Eigen::VectorXi::Ones(d.size()));
  for (Eigen::Index i = 0; i < d.size(); ++i)
  {
    D.insert(i, i) = d[i];
  }
  D.makeCompressed();
  return D;
}

//------------------------------------------------------------------------------
double SurfaceArea(const TriangleMesh& mesh)
{
  double area = 0.0;
  for (int f = 0; f < mesh.Faces.rows(); ++f)
  {
    area += 0.5 * DoubleArea(mesh, f);
  }
  return area;
}

//------------------------------------------------------------------------------
double BoundingBoxDiagonal(const Points& points)
{
  if (points.rows() == 0)
  {
    return 0.0;
  }
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
}

//------------------------------------------------------------------------------
ComponentLabels LabelComponents(const TriangleMesh& mesh)
{
  const int n = static_cast<int>(mesh.Vertices.rows());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (int f = 0; f < mesh.Faces.rows(); ++f)
  {
    const int r0 = Root(parent, mesh.Faces(f, 0));
    parent[Root(parent, mesh.Faces(f, 1))] = r0;
    parent[Root(parent, mesh.Faces(f, 2))] = r0;
  }
  ComponentLabels out;
  out.Label.assign(static_cast<std::size_t>(n), -1);
  std::vector<int> labelOfRoot(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i)
  {
    int& label = labelOfRoot[static_cast<std::size_t>(Root(parent, i))];
    if (label < 0)
    {
      label = out.Count++;
    }
    out.Label[static_cast<std::size_t>(i)] = label;
  }
  return out;
}

//------------------------------------------------------------------------------
PreparedMesh LeaveOutSmallComponents(const PreparedMesh& prepared, int minimumPoints)
{
  const ComponentLabels components = LabelComponents(prepared.Mesh);
  std::vector<int> size(static_cast<std::size_t>(components.Count), 0);
  for (int label : components.Label)
  {
    ++size[static_cast<std::size_t>(label)];
  }
  PreparedMesh out = prepared;
  for (int points : size)
  {
    out.SmallComponents += points < minimumPoints ? 1 : 0;
  }
  if (out.SmallComponents == 0)
  {
    return out;
  }
  // The points of the components kept, renumbered in their order.
  const Eigen::Index n = prepared.Mesh.Vertices.rows();
  std::vector<int> compact(static_cast<std::size_t>(n), -1);
  out.InputPointIds.clear();
  for (Eigen::Index i = 0; i < n; ++i)
  {
    if (size[static_cast<std::size_t>(components.Label[static_cast<std::size_t>(i)])] >=
      minimumPoints)
    {
      compact[static_cast<std::size_t>(i)] = static_cast<int>(out.InputPointIds.size());
      out.InputPointIds.push_back(prepared.InputPointIds[static_cast<std::size_t>(i)]);
    }
  }
  out.SmallComponentPoints = static_cast<int>(n) - static_cast<int>(out.InputPointIds.size());
  out.Mesh.Vertices.resize(static_cast<Eigen::Index>(out.InputPointIds.size()), 3);
  for (Eigen::Index i = 0; i < n; ++i)
  {
    if (compact[static_cast<std::size_t>(i)] >= 0)
    {
      out.Mesh.Vertices.row(compact[static_cast<std::size_t>(i)]) = prepared.Mesh.Vertices.row(i);
    }
  }
  std::vector<int> faces;
  for (Eigen::Index f = 0; f < prepared.Mesh.Faces.rows(); ++f)
  {
    if (compact[static_cast<std::size_t>(prepared.Mesh.Faces(f, 0))] >= 0)
    {
      faces.push_back(static_cast<int>(f));
    }
  }
  out.Mesh.Faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t t = 0; t < faces.size(); ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      out.Mesh.Faces(static_cast<Eigen::Index>(t), c) =
        compact[static_cast<std::size_t>(prepared.Mesh.Faces(faces[t], c))];
    }
  }
  return out;
}

//------------------------------------------------------------------------------
int ConnectedComponents(const TriangleMesh& mesh)
{
  return LabelComponents(mesh).Count;
}

//------------------------------------------------------------------------------
double MeanEdgeLength(const TriangleMesh& mesh)
{
  if (mesh.Faces.rows() == 0)
  {
    return 0.0;
  }
  double sum = 0.0;
  for (int f = 0; f < mesh.Faces.rows(); ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      sum += (Corner(mesh, f, (c + 1) % 3) - Corner(mesh, f, c)).norm();
    }
  }
  return sum / (3.0 * static_cast<double>(mesh.Faces.rows()));
}
} // namespace spectral
