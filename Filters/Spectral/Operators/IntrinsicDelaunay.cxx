// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Operators/IntrinsicDelaunay.h"
#include "Operators/Operators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace spectral
{
namespace
{
/// A side of a triangle: side s of face f runs from corner s to corner s+1.
struct Side
{
  int Face = -1;
  int Index = 0;
};

bool operator==(const Side& a, const Side& b)
{
  return a.Face == b.Face && a.Index == b.Index;
}

/// Area of a triangle from its side lengths (Kahan's stable Heron formula); 0 if they violate
/// the triangle inequality.
double HeronArea(double a, double b, double c)
{
  if (a < b)
  {
    std::swap(a, b);
  }
  if (a < c)
  {
    std::swap(a, c);
  }
  if (b < c)
  {
    std::swap(b, c);
  }
  const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return p > 0.0 ? 0.25 * std::sqrt(p) : 0.0;
}

/// True if the triangle is too thin for its cotangents to mean anything: the rule of the
/// extrinsic mesh (DegenerateCellSize, Operators.h) on the intrinsic lengths.
bool IsDegenerate(double a, double b, double c, double area)
{
  const double longest = std::max({ a, b, c });
  return !(2.0 * area > DegenerateCellSize * longest * longest);
}

/// Cotangent of the angle opposite side a; 0 for a degenerate triangle.
double Cot(double a, double b, double c)
{
  const double area = HeronArea(a, b, c);
  if (IsDegenerate(a, b, c, area))
  {
    return 0.0;
  }
  return (b * b + c * c - a * a) / (4.0 * area);
}

/// The working state of the flip algorithm: triangles, lengths and the gluing of their sides.
class Flipper
{
public:
  Flipper(IntrinsicTriangulation& T)
    : T(T)
    , Glue(static_cast<std::size_t>(T.Faces.rows()) * 3)
  {
  }

  /**
   * Glue the sides of a tufted cover: faces [0, F) are the input triangles, faces [F, 2F) the
   * same triangles reversed (face F + f is (a, c, b) for face f = (a, b, c)).
   */
  void ConnectTufted();
  /// Flip until Delaunay or out of budget.
  void Run(const Monitor& monitor);

private:
  /// Reorders the sides around an edge so that copies of one triangle (same opposite corner)
  /// are not neighbours in the cyclic order where another triangle can come between them.
  void InterleaveCopies(std::vector<Side>& sides) const;
  Side& Neighbor(const Side& s) { return this->Glue[3 * s.Face + s.Index]; }
  int Vertex(int f, int c) const { return this->T.Faces(f, c % 3); }
  double Length(int f, int c) const { return this->T.Lengths(f, c % 3); }
  /// cot a + cot b of the angles opposite the side s and its glued twin.
  double CotSum(const Side& s);
  /// Flip the edge of side s (glued); false if the new triangles would be degenerate.
  bool Flip(const Side& s);

  IntrinsicTriangulation& T;
  std::vector<Side> Glue;
};

//------------------------------------------------------------------------------
void Flipper::ConnectTufted()
{
  const int numFaces = static_cast<int>(this->T.Faces.rows()) / 2;
  // The input triangles' sides, sorted by their undirected edge (lower point id in the high
  // bits), then by face and side: each edge's sides in the order of the input.
  std::vector<std::pair<std::uint64_t, Side>> sorted;
  sorted.reserve(static_cast<std::size_t>(numFaces) * 3);
  for (int f = 0; f < numFaces; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      const auto i = static_cast<std::uint32_t>(this->Vertex(f, c));
      const auto j = static_cast<std::uint32_t>(this->Vertex(f, c + 1));
      sorted.emplace_back((std::uint64_t(std::min(i, j)) << 32) | std::max(i, j), Side{ f, c });
    }
  }
  std::sort(sorted.begin(),
    sorted.end(),
    [](const std::pair<std::uint64_t, Side>& a, const std::pair<std::uint64_t, Side>& b)
    {
      return a.first != b.first
        ? a.first < b.first
        : (a.second.Face != b.second.Face ? a.second.Face < b.second.Face
                                          : a.second.Index < b.second.Index);
    });
  // Around an edge i < j, each triangle has one copy whose side runs i -> j (Up) and one whose
  // side runs j -> i (Down); side c of face f is side 2 - c of its reverse F + f. Gluing the Up
  // side of each triangle to the Down side of the next, cyclically, pairs every side with one
  // running the other way: the cover is an oriented closed surface, whatever the input's
  // orientation, boundary or non-manifold edges (one triangle: its two copies are glued).
  std::vector<Side> sides, up, down;
  for (std::size_t first = 0; first < sorted.size();)
  {
    const std::uint64_t key = sorted[first].first;
    const int low = static_cast<int>(key >> 32);
    sides.clear();
    for (; first < sorted.size() && sorted[first].first == key; ++first)
    {
      sides.push_back(sorted[first].second);
    }
    this->InterleaveCopies(sides);
    const std::size_t k = sides.size();
    up.resize(k);
    down.resize(k);
    for (std::size_t a = 0; a < k; ++a)
    {
      const Side front = sides[a];
      const Side back{ front.Face + numFaces, 2 - front.Index };
      const bool forward = this->Vertex(front.Face, front.Index) == low;
      up[a] = forward ? front : back;
      down[a] = forward ? back : front;
    }
    for (std::size_t a = 0; a < k; ++a)
    {
      this->Neighbor(up[a]) = down[(a + 1) % k];
      this->Neighbor(down[(a + 1) % k]) = up[a];
    }
  }
}

//------------------------------------------------------------------------------
void Flipper::InterleaveCopies(std::vector<Side>& sides) const
{
  // The triangles around the edge (told apart by their opposite corner) in the order of their
  // first copies, and the copies of each in their order.
  std::vector<int> opposite;
  std::vector<std::vector<Side>> copies;
  for (const Side& s : sides)
  {
    const int corner = this->Vertex(s.Face, s.Index + 2);
    const auto it = std::find(opposite.begin(), opposite.end(), corner);
    if (it == opposite.end())
    {
      opposite.push_back(corner);
      copies.push_back({ s });
    }
    else
    {
      copies[static_cast<std::size_t>(it - opposite.begin())].push_back(s);
    }
  }
  if (copies.size() == sides.size())
  {
    return; // no copies: the order is kept
  }
  // One copy of each triangle per round, always in the same order of triangles.
  const std::size_t k = sides.size();
  sides.clear();
  for (std::size_t round = 0; sides.size() < k; ++round)
  {
    for (const std::vector<Side>& group : copies)
    {
      if (round < group.size())
      {
        sides.push_back(group[round]);
      }
    }
  }
}

//------------------------------------------------------------------------------
double Flipper::CotSum(const Side& s)
{
  const Side t = this->Neighbor(s);
  const int f = s.Face, c = s.Index, g = t.Face, d = t.Index;
  return Cot(this->Length(f, c), this->Length(f, c + 1), this->Length(f, c + 2)) +
    Cot(this->Length(g, d), this->Length(g, d + 1), this->Length(g, d + 2));
}

//------------------------------------------------------------------------------
bool Flipper::Flip(const Side& s)
{
  // f = (i, j, k) with side c = (i, j); g = (j, i, l) with side d = (j, i).
  const Side t = this->Neighbor(s);
  const int f = s.Face, c = s.Index, g = t.Face, d = t.Index;
  const int i = this->Vertex(f, c), j = this->Vertex(f, c + 1), k = this->Vertex(f, c + 2);
  const int l = this->Vertex(g, d + 2);
  const double lij = this->Length(f, c), ljk = this->Length(f, c + 1), lki = this->Length(f, c + 2);
  const double lil = this->Length(g, d + 1), llj = this->Length(g, d + 2);

  // Lay the quad out in the plane: i at the origin, j on the positive x axis, k above, l below.
  const double areaF = HeronArea(lij, ljk, lki);
  const double areaG = HeronArea(lij, lil, llj);
  if (IsDegenerate(lij, ljk, lki, areaF) || IsDegenerate(lij, lil, llj, areaG))
  {
    return false;
  }
  const double xk = (lki * lki - ljk * ljk + lij * lij) / (2.0 * lij);
  const double yk = 2.0 * areaF / lij;
  const double xl = (lil * lil - llj * llj + lij * lij) / (2.0 * lij);
  const double yl = -2.0 * areaG / lij;
  const double lkl = std::hypot(xk - xl, yk - yl);
  // The new triangles (k, i, l) and (l, j, k) must both be proper: the quad is convex.
  const double areaKIL = HeronArea(lki, lil, lkl);
  const double areaLJK = HeronArea(llj, ljk, lkl);
  if (IsDegenerate(lki, lil, lkl, areaKIL) || IsDegenerate(llj, ljk, lkl, areaLJK))
  {
    return false;
  }

  // The four outer sides, where they go, and what they are glued to.
  const std::array<Side, 4> oldSides = {
    Side{ f, (c + 2) % 3 }, Side{ g, (d + 1) % 3 }, Side{ g, (d + 2) % 3 }, Side{ f, (c + 1) % 3 }
  };
  const std::array<Side, 4> newSides = { Side{ f, 0 }, Side{ f, 1 }, Side{ g, 0 }, Side{ g, 1 } };
  std::array<Side, 4> outer;
  for (int e = 0; e < 4; ++e)
  {
    outer[e] = this->Neighbor(oldSides[e]);
    for (int o = 0; o < 4; ++o)
    {
      if (outer[e] == oldSides[o])
      {
        outer[e] = newSides[o]; // an outer side glued to another side of the same quad
      }
    }
  }

  // f' = (k, i, l) with sides (ki, il, lk); g' = (l, j, k) with sides (lj, jk, kl).
  this->T.Faces.row(f) << k, i, l;
  this->T.Lengths.row(f) << lki, lil, lkl;
  this->T.Faces.row(g) << l, j, k;
  this->T.Lengths.row(g) << llj, ljk, lkl;
  for (int e = 0; e < 4; ++e)
  {
    this->Neighbor(newSides[e]) = outer[e];
    if (outer[e].Face >= 0)
    {
      this->Neighbor(outer[e]) = newSides[e];
    }
  }
  this->Neighbor(Side{ f, 2 }) = Side{ g, 2 };
  this->Neighbor(Side{ g, 2 }) = Side{ f, 2 };
  return true;
}

//------------------------------------------------------------------------------
void Flipper::Run(const Monitor& monitor)
{
  constexpr double Tolerance = 1e-10;
  const int numFaces = static_cast<int>(this->T.Faces.rows());
  const long long budget = 50LL * numFaces + 1000;
  std::vector<Side> stack;
  stack.reserve(static_cast<std::size_t>(numFaces) * 3);
  for (int f = 0; f < numFaces; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (this->Neighbor(Side{ f, c }).Face > f)
      {
        stack.push_back({ f, c });
      }
    }
  }
  long long flips = 0;
  while (!stack.empty() && flips < budget)
  {
    const Side s = stack.back();
    stack.pop_back();
    const Side t = this->Neighbor(s);
    if (t.Face < 0 || !(this->CotSum(s) < -Tolerance) || !this->Flip(s))
    {
      continue;
    }
    ++flips;
    if (flips % 4096 == 0)
    {
      monitor.ThrowIfCancelled();
    }
    // The four outer sides of the quad may have stopped being Delaunay.
    stack.push_back({ s.Face, 0 });
    stack.push_back({ s.Face, 1 });
    stack.push_back({ t.Face, 0 });
    stack.push_back({ t.Face, 1 });
  }
  this->T.Flips = static_cast<int>(flips);
  for (int f = 0; f < numFaces; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      const Side t = this->Neighbor(Side{ f, c });
      if (t.Face > f && this->CotSum(Side{ f, c }) < -Tolerance)
      {
        ++this->T.NonDelaunayEdges;
      }
    }
  }
}
} // namespace

//------------------------------------------------------------------------------
IntrinsicTriangulation IntrinsicTriangulationOf(const TriangleMesh& mesh)
{
  IntrinsicTriangulation T;
  T.NumberOfPoints = static_cast<int>(mesh.Vertices.rows());
  T.Faces = mesh.Faces;
  T.Lengths.resize(mesh.Faces.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.Faces.rows(); ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      T.Lengths(f, c) =
        (mesh.Vertices.row(mesh.Faces(f, (c + 1) % 3)) - mesh.Vertices.row(mesh.Faces(f, c)))
          .norm();
    }
  }
  return T;
}

//------------------------------------------------------------------------------
double Mollify(EdgeLengths& lengths, double factor)
{
  if (lengths.rows() == 0)
  {
    return 0.0;
  }
  const double epsilon = factor * lengths.mean();
  double delta = 0.0;
  for (Eigen::Index f = 0; f < lengths.rows(); ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double margin = lengths(f, (c + 1) % 3) + lengths(f, (c + 2) % 3) - lengths(f, c);
      delta = std::max(delta, epsilon - margin);
    }
  }
  lengths.array() += delta;
  return delta;
}

//------------------------------------------------------------------------------
IntrinsicTriangulation TuftedCover(const TriangleMesh& mesh)
{
  const IntrinsicTriangulation input = IntrinsicTriangulationOf(mesh);
  const Eigen::Index F = input.Faces.rows();
  IntrinsicTriangulation T;
  T.NumberOfPoints = input.NumberOfPoints;
  T.Weight = 0.5;
  T.Faces.resize(2 * F, 3);
  T.Lengths.resize(2 * F, 3);
  T.Faces.topRows(F) = input.Faces;
  T.Lengths.topRows(F) = input.Lengths;
  for (Eigen::Index f = 0; f < F; ++f)
  {
    // (a, b, c) with sides (ab, bc, ca) reversed: (a, c, b) with sides (ac, cb, ba).
    T.Faces.row(F + f) << input.Faces(f, 0), input.Faces(f, 2), input.Faces(f, 1);
    T.Lengths.row(F + f) << input.Lengths(f, 2), input.Lengths(f, 1), input.Lengths(f, 0);
  }
  return T;
}

//------------------------------------------------------------------------------
IntrinsicTriangulation IntrinsicDelaunay(const TriangleMesh& mesh, const Monitor& monitor)
{
  IntrinsicTriangulation T = TuftedCover(mesh);
  T.Mollification = Mollify(T.Lengths, MollificationFactor);
  Flipper flipper(T);
  flipper.ConnectTufted();
  monitor.ThrowIfCancelled();
  flipper.Run(monitor);
  return T;
}

//------------------------------------------------------------------------------
std::vector<std::string> IntrinsicDelaunayWarnings(const IntrinsicTriangulation& T)
{
  if (T.NonDelaunayEdges == 0)
  {
    return {};
  }
  return { "Intrinsic Delaunay: " + std::to_string(T.NonDelaunayEdges) +
    " edges are still not Delaunay after the flip budget; their cotangent weights may be "
    "negative." };
}

//------------------------------------------------------------------------------
SparseMatrix IntrinsicCotanStiffness(const IntrinsicTriangulation& T)
{
  TriangleAssembly assembly(T.NumberOfPoints, T.Faces.rows(), 12);
  for (Eigen::Index f = 0; f < T.Faces.rows(); ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      // Side c = (i, j) is opposite corner c+2.
      assembly.AddEdgeWeight(T.Faces(f, c),
        T.Faces(f, (c + 1) % 3),
        0.5 * T.Weight *
          Cot(T.Lengths(f, c), T.Lengths(f, (c + 1) % 3), T.Lengths(f, (c + 2) % 3)));
    }
  }
  return assembly.Matrix();
}

//------------------------------------------------------------------------------
Vector IntrinsicLumpedMass(const IntrinsicTriangulation& T)
{
  Vector d = Vector::Zero(T.NumberOfPoints);
  for (Eigen::Index f = 0; f < T.Faces.rows(); ++f)
  {
    const double third =
      T.Weight * HeronArea(T.Lengths(f, 0), T.Lengths(f, 1), T.Lengths(f, 2)) / 3.0;
    for (int c = 0; c < 3; ++c)
    {
      d[T.Faces(f, c)] += third;
    }
  }
  return d;
}

//------------------------------------------------------------------------------
SparseMatrix IntrinsicConsistentMass(const IntrinsicTriangulation& T)
{
  TriangleAssembly assembly(T.NumberOfPoints, T.Faces.rows(), 9);
  for (Eigen::Index f = 0; f < T.Faces.rows(); ++f)
  {
    assembly.AddMassBlock(T.Faces(f, 0),
      T.Faces(f, 1),
      T.Faces(f, 2),
      T.Weight * HeronArea(T.Lengths(f, 0), T.Lengths(f, 1), T.Lengths(f, 2)));
  }
  return assembly.Matrix();
}
} // namespace spectral
