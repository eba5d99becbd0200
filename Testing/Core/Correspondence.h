// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Pairs of shapes with a known correspondence for the functional-map tests
// (TestFunctionalMap.cxx): a convex planar quadrilateral, triangulated from a jittered grid of
// any resolution (so two meshes of it have different points), optionally rolled onto a
// cylinder, which is an isometry of the plane. Every point keeps its parameter (its position in
// the plane), so the true correspondence of two meshes is known through barycentric
// coordinates, and since the domain is convex the geodesic distance on the rolled surface is the
// Euclidean distance of the parameters.
#ifndef spectral_Testing_Correspondence_h
#define spectral_Testing_Correspondence_h

#include "Basis.h"
#include "Filtering/FunctionalMap.h"
#include "Meshes.h"

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace spectral
{
namespace testing
{
/// Parameters (x, y) in the plane, one point a row.
using PlanePoints = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;

/// A convex quadrilateral by its corners, counter-clockwise: p00, p10, p11, p01.
struct Quadrilateral
{
  std::array<Eigen::Vector2d, 4> Corners;
  /// The bilinear map of the unit square.
  Eigen::Vector2d At(double s, double t) const
  {
    return (1 - s) * (1 - t) * this->Corners[0] + s * (1 - t) * this->Corners[1] +
      s * t * this->Corners[2] + (1 - s) * t * this->Corners[3];
  }
  /// The largest distance between two points of the (convex) domain: between two corners.
  double Diameter() const
  {
    double d = 0.0;
    for (const auto& a : this->Corners)
    {
      for (const auto& b : this->Corners)
      {
        d = std::max(d, (a - b).norm());
      }
    }
    return d;
  }
};

/// A quadrilateral without symmetry: sides 3, 2.14, 2.26, 1.65 and four different angles.
inline Quadrilateral IrregularQuadrilateral()
{
  Quadrilateral q;
  q.Corners = { Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(3.0, 0.0), Eigen::Vector2d(2.6, 2.1),
    Eigen::Vector2d(0.4, 1.6) };
  return q;
}

/// The a by b rectangle: two reflection symmetries.
inline Quadrilateral RectangleDomain(double a, double b)
{
  Quadrilateral q;
  q.Corners = { Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(a, 0.0), Eigen::Vector2d(a, b),
    Eigen::Vector2d(0.0, b) };
  return q;
}

/// A mesh of a planar domain with the parameter of each point.
struct PlanarMesh
{
  TriangleMesh Mesh;
  PlanePoints Plane;
};

/**
 * The quadrilateral meshed from an nu by nv grid of the unit square whose interior points are
 * moved at random (uniformly by up to `jitter` cells in each direction, seeded), each cell
 * split along its shorter diagonal in the plane. Flat (z = 0).
 */
inline PlanarMesh JitteredQuadrilateral(
  const Quadrilateral& domain, int nu, int nv, double jitter, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  PlanarMesh result;
  result.Plane.resize((nu + 1) * (nv + 1), 2);
  for (int j = 0; j <= nv; ++j)
  {
    for (int i = 0; i <= nu; ++i)
    {
      double s = static_cast<double>(i) / nu;
      double t = static_cast<double>(j) / nv;
      const double ds = offset(random) / nu;
      const double dt = offset(random) / nv;
      if (i > 0 && i < nu)
      {
        s += ds;
      }
      if (j > 0 && j < nv)
      {
        t += dt;
      }
      result.Plane.row(j * (nu + 1) + i) = domain.At(s, t).transpose();
    }
  }
  const PlanePoints& plane = result.Plane;
  result.Mesh.Faces = GridTriangles(nu, nv,
    [&plane](int, int, int p00, int p10, int p01, int p11)
    { return (plane.row(p00) - plane.row(p11)).norm() <= (plane.row(p10) - plane.row(p01)).norm(); });
  result.Mesh.Vertices = Points::Zero(plane.rows(), 3);
  result.Mesh.Vertices.leftCols(2) = plane;
  return result;
}

/// The mesh rolled onto a cylinder of radius R around an axis parallel to y:
/// (x, y) -> (R sin(x / R), y, R (1 - cos(x / R))), an isometry of the plane.
inline PlanarMesh Rolled(PlanarMesh mesh, double R)
{
  for (Eigen::Index i = 0; i < mesh.Plane.rows(); ++i)
  {
    const double x = mesh.Plane(i, 0);
    mesh.Mesh.Vertices.row(i) << R * std::sin(x / R), mesh.Plane(i, 1), R * (1 - std::cos(x / R));
  }
  return mesh;
}

/// A shape of the functional-map core from the basis of m harmonics of a mesh.
inline SpectralShape ShapeOf(const TriangleMesh& mesh, int m)
{
  BasisOptions options;
  options.NumberOfHarmonics = m;
  options.CheckMemory = false;
  const BasisResult basis = ComputeBasis(mesh, options);
  const Eigen::Index n = mesh.Vertices.rows();
  SpectralShape shape;
  shape.Harmonics = RowMatrix::Zero(n, m);
  shape.Mass = Vector::Zero(n);
  for (std::size_t r = 0; r < basis.InputPointIds.size(); ++r)
  {
    const Eigen::Index i = basis.InputPointIds[r];
    shape.Harmonics.row(i) = basis.Pairs.Eigenvectors.row(static_cast<Eigen::Index>(r));
    shape.Mass[i] = basis.LumpedMass[static_cast<Eigen::Index>(r)];
  }
  shape.Eigenvalues = basis.Pairs.Eigenvalues;
  shape.Vertices = mesh.Vertices;
  shape.Faces = mesh.Faces;
  return shape;
}

/// Where a point of the plane lies in a planar mesh: a triangle and barycentric weights.
struct Location
{
  std::array<int, 3> Points;
  Eigen::Vector3d Weights;
};

/**
 * The triangle of `mesh` that holds each point of `plane` (the one of the largest smallest
 * barycentric weight, so points on edges and, by round-off, just outside are placed too).
 * Brute force over the triangles with a bounding-box test.
 */
inline std::vector<Location> Locate(const PlanarMesh& mesh, const PlanePoints& plane)
{
  const Triangles& faces = mesh.Mesh.Faces;
  std::vector<Location> result(static_cast<std::size_t>(plane.rows()));
  for (Eigen::Index p = 0; p < plane.rows(); ++p)
  {
    const Eigen::Vector2d x = plane.row(p).transpose();
    double best = -std::numeric_limits<double>::infinity();
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
    {
      const Eigen::Vector2d a = mesh.Plane.row(faces(f, 0)).transpose();
      const Eigen::Vector2d b = mesh.Plane.row(faces(f, 1)).transpose();
      const Eigen::Vector2d c = mesh.Plane.row(faces(f, 2)).transpose();
      const double margin = 1e-9 + (b - a).norm();
      if (x.x() < std::min({ a.x(), b.x(), c.x() }) - margin ||
        x.x() > std::max({ a.x(), b.x(), c.x() }) + margin ||
        x.y() < std::min({ a.y(), b.y(), c.y() }) - margin ||
        x.y() > std::max({ a.y(), b.y(), c.y() }) + margin)
      {
        continue;
      }
      const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v)
      { return u.x() * v.y() - u.y() * v.x(); };
      const Eigen::Vector3d w(cross(b - x, c - x) / area, cross(c - x, a - x) / area,
        cross(a - x, b - x) / area);
      if (w.minCoeff() > best)
      {
        best = w.minCoeff();
        result[static_cast<std::size_t>(p)] = { { faces(f, 0), faces(f, 1), faces(f, 2) }, w };
      }
    }
  }
  return result;
}

/// Values at the located points: the barycentric interpolation of the rows of `values`.
inline RowMatrix Interpolate(const std::vector<Location>& locations, const RowMatrix& values)
{
  RowMatrix result(static_cast<Eigen::Index>(locations.size()), values.cols());
  for (std::size_t p = 0; p < locations.size(); ++p)
  {
    const Location& l = locations[p];
    result.row(static_cast<Eigen::Index>(p)) = l.Weights[0] * values.row(l.Points[0]) +
      l.Weights[1] * values.row(l.Points[1]) + l.Weights[2] * values.row(l.Points[2]);
  }
  return result;
}

/**
 * The mean geodesic error of a point map (source point per target point) against the truth
 * target point j -> `truth` (a point of the plane, row j): the mean over the target points of
 * the distance in the plane between the parameter of the matched source point and the true
 * one, which on a convex domain is the geodesic distance.
 */
inline double MeanGeodesicError(
  const PlanarMesh& source, const PlanePoints& truth, const std::vector<int>& ids)
{
  double sum = 0.0;
  for (std::size_t j = 0; j < ids.size(); ++j)
  {
    sum += (source.Plane.row(ids[j]) - truth.row(static_cast<Eigen::Index>(j))).norm();
  }
  return sum / static_cast<double>(ids.size());
}
} // namespace testing
} // namespace spectral

#endif
