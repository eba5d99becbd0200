// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Operators/Operators.h"
#include "Common/Seams.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace spectral
{
namespace
{
using Point = Eigen::Vector3d;

Point Corner(const TriangleMesh& mesh, int f, int c)
{
  return mesh.Vertices.row(mesh.Faces(f, c)).transpose();
}

Point TetCorner(const TriangleMesh& mesh, int t, int c)
{
  return mesh.Vertices.row(mesh.Tets(t, c)).transpose();
}

/// Twice the area of triangle f.
double DoubleArea(const TriangleMesh& mesh, int f)
{
  const Point a = Corner(mesh, f, 0);
  return (Corner(mesh, f, 1) - a).cross(Corner(mesh, f, 2) - a).norm();
}

/// Six times the unsigned volume of tetrahedron t.
double SixVolume(const TriangleMesh& mesh, int t)
{
  const Point a = TetCorner(mesh, t, 0);
  return std::abs(
    (TetCorner(mesh, t, 1) - a).dot((TetCorner(mesh, t, 2) - a).cross(TetCorner(mesh, t, 3) - a)));
}

/// The longest edge squared of the K corners `p`.
template<int K>
double LongestEdgeSquared(const std::array<Point, K>& p)
{
  double longest = 0.0;
  for (int i = 0; i < K; ++i)
  {
    for (int j = i + 1; j < K; ++j)
    {
      longest = std::max(longest, (p[i] - p[j]).squaredNorm());
    }
  }
  return longest;
}

bool IsDegenerate(const TriangleMesh& mesh, int f)
{
  const std::array<Point, 3> p = { Corner(mesh, f, 0), Corner(mesh, f, 1), Corner(mesh, f, 2) };
  return !(DoubleArea(mesh, f) > DegenerateCellSize * LongestEdgeSquared<3>(p));
}

bool IsDegenerateTet(const TriangleMesh& mesh, int t)
{
  const std::array<Point, 4> p = {
    TetCorner(mesh, t, 0), TetCorner(mesh, t, 1), TetCorner(mesh, t, 2), TetCorner(mesh, t, 3)
  };
  const double longest = LongestEdgeSquared<4>(p);
  return !(SixVolume(mesh, t) > DegenerateCellSize * longest * std::sqrt(longest));
}

/// The cells of a mesh with K corners: its triangles (K = 3) or tetrahedra (K = 4).
template<int K>
struct CellsOf;
template<>
struct CellsOf<3>
{
  static const Triangles& Get(const TriangleMesh& mesh) { return mesh.Faces; }
  static Triangles& Get(TriangleMesh& mesh) { return mesh.Faces; }
  static bool Degenerate(const TriangleMesh& mesh, int f) { return IsDegenerate(mesh, f); }
  static constexpr const char* Name = "triangle";
};
template<>
struct CellsOf<4>
{
  static const Tetrahedra& Get(const TriangleMesh& mesh) { return mesh.Tets; }
  static Tetrahedra& Get(TriangleMesh& mesh) { return mesh.Tets; }
  static bool Degenerate(const TriangleMesh& mesh, int t) { return IsDegenerateTet(mesh, t); }
  static constexpr const char* Name = "tetrahedron";
};

/**
 * Keeps the first of cells with the same K corners (either orientation): `corners` holds the
 * sorted corners of each cell of `kept`, in the same order; both are reduced to the cells kept,
 * in their input order, and `duplicates` counts the others.
 */
template<int K>
void LeaveOutDuplicates(std::vector<std::array<int, K>>& corners,
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
      keep[order[i]] = 0; // stable: the earlier input cell stays
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

/// Labels from a union-find forest: components numbered in the order of their first points.
ComponentLabels Labels(std::vector<int>& parent)
{
  const int n = static_cast<int>(parent.size());
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
// Checks the indices and the coordinates of the points that the cells use.
template<int K>
void CheckCells(const TriangleMesh& input)
{
  const auto& cells = CellsOf<K>::Get(input);
  const int numPts = static_cast<int>(input.Vertices.rows());
  for (int f = 0; f < static_cast<int>(cells.rows()); ++f)
  {
    for (int c = 0; c < K; ++c)
    {
      const int id = cells(f, c);
      if (id < 0 || id >= numPts)
      {
        throw InvalidInput(std::string(CellsOf<K>::Name) + " " + std::to_string(f) +
          " refers to point " + std::to_string(id) + " but the mesh has " + std::to_string(numPts) +
          " points");
      }
      CheckCoordinates(input.Vertices, id);
    }
  }
}

//------------------------------------------------------------------------------
// The cells `kept` of `cells` with their points renumbered by `compact`, into `mesh`.
template<int K, typename Cells>
void CopyCells(const Cells& cells,
  const std::vector<int>& kept,
  const std::vector<int>& compact,
  TriangleMesh& mesh)
{
  auto& out = CellsOf<K>::Get(mesh);
  out.resize(static_cast<Eigen::Index>(kept.size()), K);
  for (std::size_t t = 0; t < kept.size(); ++t)
  {
    for (int c = 0; c < K; ++c)
    {
      out(static_cast<Eigen::Index>(t), c) = compact[static_cast<std::size_t>(cells(kept[t], c))];
    }
  }
}

//------------------------------------------------------------------------------
// PrepareMesh for the cells with K corners.
template<int K>
PreparedMesh PrepareCells(const TriangleMesh& input)
{
  CheckCells<K>(input);
  const auto& cells = CellsOf<K>::Get(input);
  const int numPts = static_cast<int>(input.Vertices.rows());
  const int numCells = static_cast<int>(cells.rows());
  PreparedMesh out;
  out.Volume = K == 4;
  std::vector<int> compact(static_cast<std::size_t>(numPts), -1);
  std::vector<int> kept;
  kept.reserve(static_cast<std::size_t>(numCells));
  std::vector<std::array<int, K>> seen; // sorted corners of the kept cells
  seen.reserve(static_cast<std::size_t>(numCells));
  for (int f = 0; f < numCells; ++f)
  {
    if (CellsOf<K>::Degenerate(input, f))
    {
      ++out.DegenerateTriangles;
      continue;
    }
    std::array<int, K> corners;
    for (int c = 0; c < K; ++c)
    {
      corners[static_cast<std::size_t>(c)] = cells(f, c);
    }
    std::sort(corners.begin(), corners.end());
    seen.push_back(corners);
    kept.push_back(f);
  }
  LeaveOutDuplicates<K>(seen, kept, out.DuplicateTriangles);
  for (int f : kept)
  {
    for (int c = 0; c < K; ++c)
    {
      compact[static_cast<std::size_t>(cells(f, c))] = 0;
    }
  }
  for (int i = 0; i < numPts; ++i)
  {
    if (compact[static_cast<std::size_t>(i)] == 0)
    {
      compact[static_cast<std::size_t>(i)] = static_cast<int>(out.InputPointIds.size());
      out.InputPointIds.push_back(i);
    }
  }
  out.UnusedPoints = numPts - static_cast<int>(out.InputPointIds.size());

  out.Mesh.Vertices.resize(static_cast<Eigen::Index>(out.InputPointIds.size()), 3);
  for (std::size_t i = 0; i < out.InputPointIds.size(); ++i)
  {
    out.Mesh.Vertices.row(static_cast<Eigen::Index>(i)) = input.Vertices.row(out.InputPointIds[i]);
  }
  CopyCells<K>(cells, kept, compact, out.Mesh);
  return out;
}

//------------------------------------------------------------------------------
// The cells of `prepared` whose points `compact` keeps (>= 0), renumbered.
template<int K>
void KeepCells(const PreparedMesh& prepared, const std::vector<int>& compact, PreparedMesh& out)
{
  const auto& cells = CellsOf<K>::Get(prepared.Mesh);
  std::vector<int> kept;
  for (Eigen::Index f = 0; f < cells.rows(); ++f)
  {
    if (compact[static_cast<std::size_t>(cells(f, 0))] >= 0)
    {
      kept.push_back(static_cast<int>(f));
    }
  }
  CopyCells<K>(cells, kept, compact, out.Mesh);
}

//------------------------------------------------------------------------------
// The P1 stiffness of the tetrahedra: |T| G G^T with G the 4 by 3 gradients of the hat
// functions (rows of the inverse edge matrix; the first is minus their sum).
SparseMatrix TetStiffness(const TriangleMesh& mesh)
{
  TriangleAssembly assembly(mesh.Vertices.rows(), mesh.Tets.rows(), 24);
  for (int t = 0; t < mesh.Tets.rows(); ++t)
  {
    if (IsDegenerateTet(mesh, t))
    {
      continue;
    }
    const Point a = TetCorner(mesh, t, 0);
    Eigen::Matrix3d edges;
    edges << TetCorner(mesh, t, 1) - a, TetCorner(mesh, t, 2) - a, TetCorner(mesh, t, 3) - a;
    const Eigen::Matrix3d inverse = edges.inverse();
    Eigen::Matrix<double, 4, 3> G;
    G.bottomRows<3>() = inverse;
    G.row(0) = -inverse.colwise().sum();
    const double volume = std::abs(edges.determinant()) / 6.0;
    const Eigen::Matrix4d K = volume * G * G.transpose();
    for (int i = 0; i < 4; ++i)
    {
      for (int j = i + 1; j < 4; ++j)
      {
        assembly.AddEdgeWeight(mesh.Tets(t, i), mesh.Tets(t, j), -K(i, j));
      }
    }
  }
  return assembly.Matrix();
}
} // namespace

//------------------------------------------------------------------------------
bool IsDegenerateTriangle(const TriangleMesh& mesh, int f)
{
  return IsDegenerate(mesh, f);
}

//------------------------------------------------------------------------------
PreparedMesh PrepareMesh(const TriangleMesh& input)
{
  if (input.Faces.rows() > 0 && input.Tets.rows() > 0)
  {
    throw InvalidInput("the mesh has " + std::to_string(input.Faces.rows()) + " triangles and " +
      std::to_string(input.Tets.rows()) +
      " tetrahedra: a mesh is a surface or a volume, not both; extract one of them first");
  }
  return input.IsVolume() ? PrepareCells<4>(input) : PrepareCells<3>(input);
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
  if (mesh.IsVolume())
  {
    return TetStiffness(mesh);
  }
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
  for (int t = 0; t < mesh.Tets.rows(); ++t)
  {
    const double quarter = SixVolume(mesh, t) / 24.0;
    for (int c = 0; c < 4; ++c)
    {
      d[mesh.Tets(t, c)] += quarter;
    }
  }
  return d;
}

//------------------------------------------------------------------------------
SparseMatrix ConsistentMass(const TriangleMesh& mesh)
{
  TriangleAssembly assembly(
    mesh.Vertices.rows(), mesh.Faces.rows() + 2 * mesh.Tets.rows(), mesh.IsVolume() ? 8 : 9);
  for (int f = 0; f < mesh.Faces.rows(); ++f)
  {
    assembly.AddMassBlock(
      mesh.Faces(f, 0), mesh.Faces(f, 1), mesh.Faces(f, 2), 0.5 * DoubleArea(mesh, f));
  }
  for (int t = 0; t < mesh.Tets.rows(); ++t)
  {
    const int corners[4] = { mesh.Tets(t, 0), mesh.Tets(t, 1), mesh.Tets(t, 2), mesh.Tets(t, 3) };
    assembly.AddMassBlock(corners, SixVolume(mesh, t) / 6.0);
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
void TriangleAssembly::AddMassBlock(const int (&corners)[4], double volume)
{
  for (int r = 0; r < 4; ++r)
  {
    for (int q = 0; q < 4; ++q)
    {
      this->Triplets.emplace_back(
        corners[r], corners[q], volume * (r == q ? 1.0 / 10.0 : 1.0 / 20.0));
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
double Measure(const TriangleMesh& mesh)
{
  if (!mesh.IsVolume())
  {
    return SurfaceArea(mesh);
  }
  double volume = 0.0;
  for (int t = 0; t < mesh.Tets.rows(); ++t)
  {
    volume += SixVolume(mesh, t) / 6.0;
  }
  return volume;
}

//------------------------------------------------------------------------------
std::vector<char> FacetPoints(const TriangleMesh& mesh, bool (*marked)(std::size_t cells))
{
  // The sorted corners of every facet (edge of a triangle, face of a tetrahedron), padded with
  // -1 for edges, once per cell that uses it.
  std::vector<std::array<int, 3>> facets;
  facets.reserve(static_cast<std::size_t>(3 * mesh.Faces.rows() + 4 * mesh.Tets.rows()));
  for (int f = 0; f < mesh.Faces.rows(); ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      const int i = mesh.Faces(f, c);
      const int j = mesh.Faces(f, (c + 1) % 3);
      facets.push_back({ -1, std::min(i, j), std::max(i, j) });
    }
  }
  for (int t = 0; t < mesh.Tets.rows(); ++t)
  {
    for (int c = 0; c < 4; ++c)
    {
      std::array<int, 3> face = {
        mesh.Tets(t, (c + 1) % 4), mesh.Tets(t, (c + 2) % 4), mesh.Tets(t, (c + 3) % 4)
      };
      std::sort(face.begin(), face.end());
      facets.push_back(face);
    }
  }
  std::sort(facets.begin(), facets.end());
  std::vector<char> points(static_cast<std::size_t>(mesh.Vertices.rows()), 0);
  for (std::size_t i = 0; i < facets.size();)
  {
    std::size_t end = i + 1;
    while (end < facets.size() && facets[end] == facets[i])
    {
      ++end;
    }
    if (marked(end - i))
    {
      for (int id : facets[i])
      {
        if (id >= 0)
        {
          points[static_cast<std::size_t>(id)] = 1;
        }
      }
    }
    i = end;
  }
  return points;
}

//------------------------------------------------------------------------------
std::vector<char> BoundaryPoints(const TriangleMesh& mesh)
{
  return FacetPoints(mesh, [](std::size_t cells) { return cells == 1; });
}

//------------------------------------------------------------------------------
std::vector<char> BorderPoints(const TriangleMesh& mesh)
{
  return FacetPoints(mesh, [](std::size_t cells) { return cells != 2; });
}

//------------------------------------------------------------------------------
ComponentLabels LabelComponents(const TriangleMesh& mesh)
{
  const int n = static_cast<int>(mesh.Vertices.rows());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  for (int f = 0; f < mesh.Faces.rows(); ++f)
  {
    const int r0 = Root(parent, mesh.Faces(f, 0));
    parent[Root(parent, mesh.Faces(f, 1))] = r0;
    parent[Root(parent, mesh.Faces(f, 2))] = r0;
  }
  for (int t = 0; t < mesh.Tets.rows(); ++t)
  {
    for (int c = 1; c < 4; ++c)
    {
      parent[Root(parent, mesh.Tets(t, c))] = Root(parent, mesh.Tets(t, 0));
    }
  }
  return Labels(parent);
}

//------------------------------------------------------------------------------
ComponentLabels LabelComponents(const SparseMatrix& pattern)
{
  std::vector<int> parent(static_cast<std::size_t>(pattern.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  for (int j = 0; j < pattern.outerSize(); ++j)
  {
    for (SparseMatrix::InnerIterator it(pattern, j); it; ++it)
    {
      parent[Root(parent, static_cast<int>(it.row()))] = Root(parent, j);
    }
  }
  return Labels(parent);
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
  KeepCells<3>(prepared, compact, out);
  KeepCells<4>(prepared, compact, out);
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
  const double edges = EdgeCount(mesh);
  if (edges == 0.0)
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
  for (int t = 0; t < mesh.Tets.rows(); ++t)
  {
    for (int i = 0; i < 4; ++i)
    {
      for (int j = i + 1; j < 4; ++j)
      {
        sum += (TetCorner(mesh, t, j) - TetCorner(mesh, t, i)).norm();
      }
    }
  }
  return sum / edges;
}

//------------------------------------------------------------------------------
double EdgeCount(const TriangleMesh& mesh)
{
  return 3.0 * static_cast<double>(mesh.Faces.rows()) + 6.0 * static_cast<double>(mesh.Tets.rows());
}

//------------------------------------------------------------------------------
OpenSeams FindOpenSeams(const TriangleMesh& mesh)
{
  OpenSeams found;
  const Triangles& faces = mesh.Faces;
  const Eigen::Index n = mesh.Vertices.rows();
  // A point id out of range: the core refuses the mesh (PrepareMesh), nothing to look for.
  if (faces.rows() == 0 || faces.minCoeff() < 0 || faces.maxCoeff() >= n)
  {
    return found;
  }
  const double radius = OpenSeamGap * MeanEdgeLength(mesh);
  if (!(radius > 0.0) || !std::isfinite(radius))
  {
    return found;
  }
  // Every edge (smaller id first) once per triangle; an edge met once is on the boundary.
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(3 * faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      const int a = faces(f, c);
      const int b = faces(f, (c + 1) % 3);
      if (a != b)
      {
        edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<int> ids; // the boundary points
  std::vector<char> boundary(static_cast<std::size_t>(n), 0);
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i])
    {
      ++j;
    }
    if (j - i == 1)
    {
      boundary[static_cast<std::size_t>(edges[i].first)] = 1;
      boundary[static_cast<std::size_t>(edges[i].second)] = 1;
    }
    i = j;
  }
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> xyz;
  for (Eigen::Index i = 0; i < n; ++i)
  {
    if (boundary[static_cast<std::size_t>(i)])
    {
      ids.push_back(static_cast<int>(i));
      xyz.insert(xyz.end(), mesh.Vertices.data() + 3 * i, mesh.Vertices.data() + 3 * i + 3);
    }
  }
  // The boundary points welded within the radius (a fraction of the diagonal of the mesh's box,
  // which WeldPoints takes): each later copy against the first copy of its group, unless an
  // edge joins them.
  double box[6];
  for (int d = 0; d < 3; ++d)
  {
    box[2 * d] = mesh.Vertices.col(d).minCoeff();
    box[2 * d + 1] = mesh.Vertices.col(d).maxCoeff();
  }
  const double diagonal = BoundingBoxDiagonal(mesh.Vertices);
  if (ids.size() < 2 || !(diagonal > 0.0) || !std::isfinite(diagonal))
  {
    return found;
  }
  const Welding near =
    WeldPoints(xyz.data(), static_cast<long long>(ids.size()), box, radius / diagonal);
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    const auto first = static_cast<std::size_t>(near.First[static_cast<std::size_t>(near.Map[k])]);
    const std::pair<int, int> edge = { std::min(ids[k], ids[first]), std::max(ids[k], ids[first]) };
    if (first == k || std::binary_search(edges.begin(), edges.end(), edge))
    {
      continue;
    }
    ++found.Pairs;
    const double gap = (mesh.Vertices.row(ids[k]) - mesh.Vertices.row(ids[first])).norm();
    found.LargestGap = std::max(found.LargestGap, gap / diagonal);
  }
  return found;
}

//------------------------------------------------------------------------------
long long OrientationConflicts(const Triangles& faces)
{
  std::vector<std::pair<int, int>> directed;
  directed.reserve(static_cast<std::size_t>(3 * faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      const int a = faces(f, c);
      const int b = faces(f, (c + 1) % 3);
      if (a != b && a >= 0 && b >= 0)
      {
        directed.emplace_back(a, b);
      }
    }
  }
  std::sort(directed.begin(), directed.end());
  long long conflicts = 0;
  for (std::size_t i = 1; i < directed.size(); ++i)
  {
    // Each edge once, however many triangles repeat its direction.
    conflicts +=
      directed[i] == directed[i - 1] && (i < 2 || directed[i - 2] != directed[i]) ? 1 : 0;
  }
  return conflicts;
}
} // namespace spectral
