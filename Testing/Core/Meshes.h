// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Meshes built in code for the core tests and the benchmark (bench/): icospheres, flat rectangles,
// tori, noisy tori of any size. Each generator's points carry the rounding-level perturbation of
// Perturbation.h when MANIFOLDHARMONICS_TEST_PERTURBATION is set (meshes built from them, such as
// WithScanDefects, Disc or TetrahedralBall, inherit it).
#ifndef spectral_Testing_Meshes_h
#define spectral_Testing_Meshes_h

#include "Common/Mesh.h"
#include "Operators/Operators.h"
#include "Perturbation.h"

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace spectral
{
namespace testing
{
/// The points of a generated mesh, with the perturbation of the environment (Perturbation.h).
inline void Perturbed(Points& vertices)
{
  RoundingPerturbation factor;
  if (!factor.Active())
  {
    return;
  }
  for (Eigen::Index i = 0; i < vertices.rows(); ++i)
  {
    for (Eigen::Index c = 0; c < vertices.cols(); ++c)
    {
      vertices(i, c) *= factor();
    }
  }
}

/// Unit icosphere: the icosahedron split `level` times, points projected to the sphere.
/// 10 * 4^level + 2 points.
inline TriangleMesh Icosphere(int level)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> v = { { -1, t, 0 },
    { 1, t, 0 },
    { -1, -t, 0 },
    { 1, -t, 0 },
    { 0, -1, t },
    { 0, 1, t },
    { 0, -1, -t },
    { 0, 1, -t },
    { t, 0, -1 },
    { t, 0, 1 },
    { -t, 0, -1 },
    { -t, 0, 1 } };
  std::vector<std::array<int, 3>> f = { { 0, 11, 5 },
    { 0, 5, 1 },
    { 0, 1, 7 },
    { 0, 7, 10 },
    { 0, 10, 11 },
    { 1, 5, 9 },
    { 5, 11, 4 },
    { 11, 10, 2 },
    { 10, 7, 6 },
    { 7, 1, 8 },
    { 3, 9, 4 },
    { 3, 4, 2 },
    { 3, 2, 6 },
    { 3, 6, 8 },
    { 3, 8, 9 },
    { 4, 9, 5 },
    { 2, 4, 11 },
    { 6, 2, 10 },
    { 8, 6, 7 },
    { 9, 8, 1 } };
  auto normalize = [](std::array<double, 3> p)
  {
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{ p[0] / r, p[1] / r, p[2] / r };
  };
  for (auto& p : v)
  {
    p = normalize(p);
  }
  for (int l = 0; l < level; ++l)
  {
    std::map<std::pair<int, int>, int> midpoints;
    auto midpoint = [&](int a, int b)
    {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = midpoints.find(key);
      if (it != midpoints.end())
      {
        return it->second;
      }
      v.push_back(normalize({ v[a][0] + v[b][0], v[a][1] + v[b][1], v[a][2] + v[b][2] }));
      const int id = static_cast<int>(v.size()) - 1;
      midpoints[key] = id;
      return id;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& tri : f)
    {
      const int a = midpoint(tri[0], tri[1]);
      const int b = midpoint(tri[1], tri[2]);
      const int c = midpoint(tri[2], tri[0]);
      next.push_back({ tri[0], a, c });
      next.push_back({ tri[1], b, a });
      next.push_back({ tri[2], c, b });
      next.push_back({ a, b, c });
    }
    f.swap(next);
  }
  TriangleMesh mesh;
  mesh.Vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    mesh.Vertices.row(static_cast<Eigen::Index>(i)) << v[i][0], v[i][1], v[i][2];
  }
  mesh.Faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
  {
    mesh.Faces.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
  }
  Perturbed(mesh.Vertices);
  return mesh;
}

/**
 * The triangles of an nx by ny grid of cells whose (nx + 1) (ny + 1) points are numbered row by
 * row (point (i, j) is j (nx + 1) + i). Cell (i, j) with corners p00, p10, p01, p11 is split
 * along the diagonal p00-p11 where splitMain(i, j, p00, p10, p01, p11) is true, along p10-p01
 * otherwise.
 */
template<typename Split>
inline Triangles GridTriangles(int nx, int ny, const Split& splitMain)
{
  Triangles faces(2 * nx * ny, 3);
  int t = 0;
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      const int p00 = j * (nx + 1) + i;
      const int p10 = p00 + 1;
      const int p01 = p00 + nx + 1;
      const int p11 = p01 + 1;
      if (splitMain(i, j, p00, p10, p01, p11))
      {
        faces.row(t++) << p00, p10, p11;
        faces.row(t++) << p00, p11, p01;
      }
      else
      {
        faces.row(t++) << p00, p10, p01;
        faces.row(t++) << p10, p11, p01;
      }
    }
  }
  return faces;
}

/// Flat a by b rectangle in the z = 0 plane, nx by ny cells, each split into two triangles
/// along alternating diagonals.
inline TriangleMesh Rectangle(double a, double b, int nx, int ny)
{
  TriangleMesh mesh;
  mesh.Vertices.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
  {
    for (int i = 0; i <= nx; ++i)
    {
      mesh.Vertices.row(j * (nx + 1) + i) << a * i / nx, b * j / ny, 0.0;
    }
  }
  mesh.Faces =
    GridTriangles(nx, ny, [](int i, int j, int, int, int, int) { return (i + j) % 2 == 0; });
  Perturbed(mesh.Vertices);
  return mesh;
}

/// Torus around the z axis with radii R (of the centre circle) and r (of the tube), nu by nv
/// quads split into two triangles. Closed, genus one, area 4 pi^2 R r in the limit.
inline TriangleMesh Torus(double R, double r, int nu, int nv)
{
  const double pi = 3.14159265358979323846;
  TriangleMesh mesh;
  mesh.Vertices.resize(nu * nv, 3);
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      const double u = 2.0 * pi * i / nu;
      const double v = 2.0 * pi * j / nv;
      mesh.Vertices.row(i * nv + j) << (R + r * std::cos(v)) * std::cos(u),
        (R + r * std::cos(v)) * std::sin(u), r * std::sin(v);
    }
  }
  mesh.Faces.resize(2 * nu * nv, 3);
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      const int p00 = i * nv + j;
      const int p10 = ((i + 1) % nu) * nv + j;
      const int p01 = i * nv + (j + 1) % nv;
      const int p11 = ((i + 1) % nu) * nv + (j + 1) % nv;
      mesh.Faces.row(2 * p00) << p00, p10, p11;
      mesh.Faces.row(2 * p00 + 1) << p00, p11, p01;
    }
  }
  Perturbed(mesh.Vertices);
  return mesh;
}

/// The union of two meshes (points and triangles of b appended to those of a).
inline TriangleMesh Join(const TriangleMesh& a, const TriangleMesh& b)
{
  TriangleMesh out;
  out.Vertices.resize(a.Vertices.rows() + b.Vertices.rows(), 3);
  out.Vertices << a.Vertices, b.Vertices;
  out.Faces.resize(a.Faces.rows() + b.Faces.rows(), 3);
  out.Faces << a.Faces, (b.Faces.array() + static_cast<int>(a.Vertices.rows())).matrix();
  return out;
}

/// The mesh moved by `offset` along x.
inline TriangleMesh Translated(TriangleMesh mesh, double offset)
{
  mesh.Vertices.col(0).array() += offset;
  return mesh;
}

/**
 * Torus with major radius 1 and minor radius 0.35, nu by nv quads split into triangles, each point
 * moved along the tube normal by uniform noise of `noise` times the minor radius (fixed seed).
 * nu * nv points.
 */
inline TriangleMesh NoisyTorus(int nu, int nv, double noise)
{
  const double pi = 3.14159265358979323846;
  const double R = 1.0;
  const double r = 0.35;
  std::mt19937 generator(7u);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  TriangleMesh mesh;
  mesh.Vertices.resize(static_cast<Eigen::Index>(nu) * nv, 3);
  for (int i = 0; i < nu; ++i)
  {
    const double u = 2.0 * pi * i / nu;
    for (int j = 0; j < nv; ++j)
    {
      const double v = 2.0 * pi * j / nv;
      const double rr = r * (1.0 + noise * uniform(generator));
      mesh.Vertices.row(static_cast<Eigen::Index>(i) * nv + j)
        << (R + rr * std::cos(v)) * std::cos(u),
        (R + rr * std::cos(v)) * std::sin(u), rr * std::sin(v);
    }
  }
  mesh.Faces.resize(2 * static_cast<Eigen::Index>(nu) * nv, 3);
  Eigen::Index t = 0;
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      const int a = i * nv + j;
      const int b = ((i + 1) % nu) * nv + j;
      const int c = ((i + 1) % nu) * nv + (j + 1) % nv;
      const int d = i * nv + (j + 1) % nv;
      mesh.Faces.row(t++) << a, b, c;
      mesh.Faces.row(t++) << a, c, d;
    }
  }
  Perturbed(mesh.Vertices);
  return mesh;
}

/// A noisy torus of about n points with a tube resolution proportional to the ring's.
inline TriangleMesh NoisyTorusOfSize(int n, double noise)
{
  // Points are spaced evenly when nv / nu = r / R = 0.35.
  const int nu = static_cast<int>(std::lround(std::sqrt(n / 0.35)));
  const int nv = std::max(3, static_cast<int>(std::lround(static_cast<double>(n) / nu)));
  return NoisyTorus(nu, nv, noise);
}

/// The defects of a real range scan that WithScanDefects sprinkles over a mesh.
struct ScanDefects
{
  /// Triangles split 1-to-3 at a point very close to a corner: edges of 1e-4 to 1e-8 times the
  /// triangle's (log-uniform), tiny lumped masses, near-degenerate (but not zero-area)
  /// triangles.
  int NearCoincident = 0;
  /// Edges split at a point pushed off the edge by 5e-5 of its length: angles within 1e-4 of pi,
  /// cotangent weights of about -1e4.
  int Needles = 0;
  /// Triangles of exactly zero area appended (an edge and its midpoint, a new point).
  int ZeroArea = 0;
  /// Small components (debris) beside the surface: flat grids of 3 to 80 points.
  int Islands = 0;
  /// Seed of the random choices.
  unsigned Seed = 11u;
};

/**
 * The mesh with the defects of a real range scan (see ScanDefects), at random places (fixed
 * seed). The islands lie within the bounding box grown by 10%, a few mean edge lengths across.
 */
inline TriangleMesh WithScanDefects(const TriangleMesh& input, const ScanDefects& defects)
{
  std::mt19937 random(defects.Seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Eigen::RowVector3d> points(static_cast<std::size_t>(input.Vertices.rows()));
  for (Eigen::Index i = 0; i < input.Vertices.rows(); ++i)
  {
    points[static_cast<std::size_t>(i)] = input.Vertices.row(i);
  }
  std::vector<std::array<int, 3>> faces(static_cast<std::size_t>(input.Faces.rows()));
  for (Eigen::Index f = 0; f < input.Faces.rows(); ++f)
  {
    faces[static_cast<std::size_t>(f)] = {
      input.Faces(f, 0), input.Faces(f, 1), input.Faces(f, 2)
    };
  }
  const auto randomFace = [&]()
  {
    return static_cast<std::size_t>(uniform(random) * static_cast<double>(faces.size())) %
      faces.size();
  };
  const auto add = [&points](const Eigen::RowVector3d& p)
  {
    points.push_back(p);
    return static_cast<int>(points.size()) - 1;
  };
  for (int k = 0; k < defects.NearCoincident; ++k)
  {
    const std::size_t f = randomFace();
    const std::array<int, 3> t = faces[f];
    const double ratio = std::pow(10.0, -4.0 - 4.0 * uniform(random));
    const Eigen::RowVector3d a = points[static_cast<std::size_t>(t[0])];
    const int p = add(a +
      ratio * 0.5 *
        (points[static_cast<std::size_t>(t[1])] - a + points[static_cast<std::size_t>(t[2])] - a));
    faces[f] = { t[0], t[1], p };
    faces.push_back({ t[1], t[2], p });
    faces.push_back({ t[2], t[0], p });
  }
  // Directed edges -> face, for the needles' neighbours.
  std::map<std::pair<int, int>, std::size_t> owner;
  for (std::size_t f = 0; f < faces.size(); ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      owner[{ faces[f][c], faces[f][(c + 1) % 3] }] = f;
    }
  }
  for (int k = 0; k < defects.Needles; ++k)
  {
    const std::size_t f1 = randomFace();
    const std::array<int, 3> t = faces[f1];
    const auto twin = owner.find({ t[1], t[0] });
    if (twin == owner.end() || faces[twin->second][0] < 0)
    {
      continue;
    }
    const std::size_t f2 = twin->second;
    int d = -1;
    for (int c = 0; c < 3; ++c)
    {
      d = (faces[f2][c] != t[0] && faces[f2][c] != t[1]) ? faces[f2][c] : d;
    }
    const Eigen::RowVector3d a = points[t[0]], b = points[t[1]], c = points[t[2]];
    const Eigen::RowVector3d middle = 0.5 * (a + b);
    const Eigen::RowVector3d toward = (c - middle).normalized();
    const int m = add(middle + 5e-5 * (b - a).norm() * toward);
    faces[f1] = { t[0], m, t[2] };
    faces[f2] = { t[1], m, d };
    faces.push_back({ m, t[1], t[2] });
    faces.push_back({ m, t[0], d });
    for (const std::size_t g : { f1, f2, faces.size() - 2, faces.size() - 1 })
    {
      for (int e = 0; e < 3; ++e)
      {
        owner[{ faces[g][e], faces[g][(e + 1) % 3] }] = g;
      }
    }
    owner.erase({ t[0], t[1] });
    owner.erase({ t[1], t[0] });
  }
  for (int k = 0; k < defects.ZeroArea; ++k)
  {
    const std::array<int, 3> t = faces[randomFace()];
    const int m = add(0.5 * (points[t[0]] + points[t[1]]));
    faces.push_back({ t[0], t[1], m });
  }
  Eigen::RowVector3d low = input.Vertices.colwise().minCoeff();
  Eigen::RowVector3d high = input.Vertices.colwise().maxCoeff();
  const Eigen::RowVector3d grow = 0.1 * (high - low);
  low -= grow;
  high += grow;
  const double h = MeanEdgeLength(input);
  for (int k = 0; k < defects.Islands; ++k)
  {
    // 3 points (one triangle) or an nx by ny grid of up to 80 points.
    const int nx = 1 + static_cast<int>(uniform(random) * 9.0);
    const int ny = 1 + static_cast<int>(uniform(random) * 7.0);
    const Eigen::RowVector3d origin = low.array() + uniform(random) * (high - low).array();
    if (nx * ny == 1 || uniform(random) < 0.25)
    {
      const int a = add(origin);
      const int b = add(origin + Eigen::RowVector3d(h, 0.0, 0.0));
      const int c = add(origin + Eigen::RowVector3d(0.0, h, 0.2 * h));
      faces.push_back({ a, b, c });
      continue;
    }
    const TriangleMesh grid = Rectangle(nx * h, ny * h, nx, ny);
    const int first = static_cast<int>(points.size());
    for (Eigen::Index i = 0; i < grid.Vertices.rows(); ++i)
    {
      add(origin + grid.Vertices.row(i));
    }
    for (Eigen::Index f = 0; f < grid.Faces.rows(); ++f)
    {
      faces.push_back(
        { first + grid.Faces(f, 0), first + grid.Faces(f, 1), first + grid.Faces(f, 2) });
    }
  }
  TriangleMesh mesh;
  mesh.Vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    mesh.Vertices.row(static_cast<Eigen::Index>(i)) = points[i];
  }
  mesh.Faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
  {
    mesh.Faces.row(static_cast<Eigen::Index>(f)) << faces[f][0], faces[f][1], faces[f][2];
  }
  return mesh;
}

/**
 * The box [0, a] x [0, b] x [0, c] of nx by ny by nz cubes, each split into the six tetrahedra
 * of its main diagonal (Kuhn's split: one for each order of the three axes along the path from
 * the cube's low corner to its high corner), so neighbouring cubes share their faces' diagonals
 * (a conforming mesh). Half of the tetrahedra are positively oriented, half negatively. Point
 * (i, j, k) is (k (ny + 1) + j) (nx + 1) + i.
 */
inline TriangleMesh TetrahedralBox(double a, double b, double c, int nx, int ny, int nz)
{
  TriangleMesh mesh;
  const auto id = [nx, ny](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  mesh.Vertices.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
  {
    for (int j = 0; j <= ny; ++j)
    {
      for (int i = 0; i <= nx; ++i)
      {
        mesh.Vertices.row(id(i, j, k)) << a * i / nx, b * j / ny, c * k / nz;
      }
    }
  }
  const int orders[6][3] = {
    { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 }, { 2, 1, 0 }
  };
  mesh.Tets.resize(6 * nx * ny * nz, 4);
  int t = 0;
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        for (const auto& order : orders)
        {
          int step[3] = { i, j, k };
          mesh.Tets(t, 0) = id(step[0], step[1], step[2]);
          for (int s = 0; s < 3; ++s)
          {
            ++step[order[s]];
            mesh.Tets(t, s + 1) = id(step[0], step[1], step[2]);
          }
          ++t;
        }
      }
    }
  }
  Perturbed(mesh.Vertices);
  return mesh;
}

/// Scales p by |p|_inf / |p|_2: the cube [-1, 1]^d onto the unit ball (or the square onto the
/// unit disc), radially.
inline void CubeToBall(Points& points)
{
  for (Eigen::Index i = 0; i < points.rows(); ++i)
  {
    const double norm = points.row(i).norm();
    if (norm > 0.0)
    {
      points.row(i) *= points.row(i).cwiseAbs().maxCoeff() / norm;
    }
  }
}

/// The unit ball: TetrahedralBox of the cube [-1, 1]^3 (n cubes a side) mapped radially.
inline TriangleMesh TetrahedralBall(int n)
{
  TriangleMesh mesh = TetrahedralBox(2.0, 2.0, 2.0, n, n, n);
  mesh.Vertices.array() -= 1.0;
  CubeToBall(mesh.Vertices);
  return mesh;
}

/// The unit disc in the z = 0 plane: Rectangle of the square [-1, 1]^2 (n cells a side)
/// mapped radially.
inline TriangleMesh Disc(int n)
{
  TriangleMesh mesh = Rectangle(2.0, 2.0, n, n);
  mesh.Vertices.leftCols(2).array() -= 1.0;
  CubeToBall(mesh.Vertices);
  return mesh;
}
} // namespace testing
} // namespace spectral

#endif
