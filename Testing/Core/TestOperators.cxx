// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Properties of the cotan stiffness and the mass matrices (Filters/Spectral/Operators/Operators.h).
#include "Checks.h"
#include "Meshes.h"
#include "Operators/Operators.h"

#include <Eigen/Geometry>

#include <limits>
#include <random>

using namespace spectral;
using namespace spectral::testing;

namespace
{
const double Pi = 3.14159265358979323846;

/// Closed and open test meshes: a sphere, a torus and a flat rectangle.
struct Named
{
  const char* Name;
  TriangleMesh Mesh;
};

std::vector<Named> Meshes()
{
  return { { "icosphere(3)", Icosphere(3) }, { "torus(2, 0.5, 40, 16)", Torus(2.0, 0.5, 40, 16) },
    { "rectangle(2, 1, 20, 10)", Rectangle(2.0, 1.0, 20, 10) } };
}

double MaxAbs(const SparseMatrix& A)
{
  double out = 0.0;
  for (int k = 0; k < A.outerSize(); ++k)
  {
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
    {
      out = std::max(out, std::abs(it.value()));
    }
  }
  return out;
}

bool AllFinite(const SparseMatrix& A)
{
  for (int k = 0; k < A.outerSize(); ++k)
  {
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
    {
      if (!std::isfinite(it.value()))
      {
        return false;
      }
    }
  }
  return true;
}

/// A planar mesh with irregular triangles: a jittered rectangle, rotated and moved off the origin.
TriangleMesh TiltedIrregularPlane(int nx, int ny)
{
  TriangleMesh mesh = Rectangle(2.0, 1.0, nx, ny);
  std::mt19937 generator(7u);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double jitter = 0.25 * std::min(2.0 / nx, 1.0 / ny);
  for (int j = 1; j < ny; ++j)
  {
    for (int i = 1; i < nx; ++i)
    {
      mesh.Vertices(j * (nx + 1) + i, 0) += jitter * uniform(generator);
      mesh.Vertices(j * (nx + 1) + i, 1) += jitter * uniform(generator);
    }
  }
  const Eigen::Matrix3d R =
    (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized())).toRotationMatrix();
  for (Eigen::Index p = 0; p < mesh.Vertices.rows(); ++p)
  {
    mesh.Vertices.row(p) = (R * mesh.Vertices.row(p).transpose()).transpose();
    mesh.Vertices.row(p) += Eigen::RowVector3d(0.3, -1.2, 2.5);
  }
  return mesh;
}

//------------------------------------------------------------------------------
void StiffnessSymmetric()
{
  for (const Named& m : Meshes())
  {
    const SparseMatrix L = CotanStiffness(m.Mesh);
    const SparseMatrix transposed = L.transpose();
    CheckBelow(MaxAbs(L - transposed), 1e-14 * MaxAbs(L), std::string(m.Name) + " max |L - L^T|");
  }
}

//------------------------------------------------------------------------------
void StiffnessConstantsInKernel()
{
  for (const Named& m : Meshes())
  {
    const SparseMatrix L = CotanStiffness(m.Mesh);
    const Vector ones = Vector::Ones(L.rows());
    CheckBelow((L * ones).cwiseAbs().maxCoeff(), 1e-12 * MaxAbs(L),
      std::string(m.Name) + " max |L 1|");
    // Positive semi-definite: x^T L x >= 0 for random x (the energy of a P1 function).
    std::mt19937 generator(3u);
    std::normal_distribution<double> normal;
    double worst = std::numeric_limits<double>::infinity();
    for (int trial = 0; trial < 20; ++trial)
    {
      Vector x(L.rows());
      for (Eigen::Index i = 0; i < x.size(); ++i)
      {
        x[i] = normal(generator);
      }
      worst = std::min(worst, x.dot(L * x) / x.squaredNorm());
    }
    Check(worst > 0.0, std::string(m.Name) + " x^T L x / x^T x > 0 for 20 random x (min " +
        std::to_string(worst) + ")");
  }
}

//------------------------------------------------------------------------------
void MassEqualsArea()
{
  for (const Named& m : Meshes())
  {
    const double area = SurfaceArea(m.Mesh);
    CheckNear(LumpedMass(m.Mesh).sum(), area, 1e-12 * area,
      std::string(m.Name) + " sum(lumped mass) = surface area");
    const Vector ones = Vector::Ones(m.Mesh.Vertices.rows());
    CheckNear(ones.dot(ConsistentMass(m.Mesh) * ones), area, 1e-12 * area,
      std::string(m.Name) + " 1^T B 1 = surface area");
  }
  CheckNear(SurfaceArea(Rectangle(2.0, 1.0, 20, 10)), 2.0, 1e-13, "rectangle 2 x 1 area");
  // Inscribed polyhedra approach the smooth area from below, with error O(h^2).
  const double sphere = 4.0 * Pi;
  const double e3 = sphere - SurfaceArea(Icosphere(3));
  const double e4 = sphere - SurfaceArea(Icosphere(4));
  Check(e3 > 0.0 && e4 > 0.0 && e4 < 0.3 * e3,
    "icosphere area deficit shrinks ~4x per level: " + std::to_string(e3) + " -> " +
      std::to_string(e4));
  const double torus = 4.0 * Pi * Pi * 2.0 * 0.5;
  const double t1 = torus - SurfaceArea(Torus(2.0, 0.5, 40, 16));
  const double t2 = torus - SurfaceArea(Torus(2.0, 0.5, 80, 32));
  Check(t1 > 0.0 && t2 > 0.0 && t2 < 0.3 * t1,
    "torus area deficit shrinks ~4x per refinement: " + std::to_string(t1) + " -> " +
      std::to_string(t2));
}

//------------------------------------------------------------------------------
void ConsistentRowSums()
{
  for (const Named& m : Meshes())
  {
    const SparseMatrix B = ConsistentMass(m.Mesh);
    const Vector d = LumpedMass(m.Mesh);
    const SparseMatrix transposed = B.transpose();
    CheckBelow(((B * Vector::Ones(B.cols())) - d).cwiseAbs().maxCoeff(), 1e-14 * d.maxCoeff(),
      std::string(m.Name) + " max |B 1 - lumped|");
    CheckBelow(MaxAbs(B - transposed), 0.0, std::string(m.Name) + " max |B - B^T|");
  }
}

//------------------------------------------------------------------------------
void LinearPrecision()
{
  const int nx = 16;
  const int ny = 9;
  const TriangleMesh mesh = TiltedIrregularPlane(nx, ny);
  const SparseMatrix L = CotanStiffness(mesh);
  // Any affine function of the coordinates is linear on the plane.
  const Vector f = 1.5 * mesh.Vertices.col(0) - 0.7 * mesh.Vertices.col(1) +
    0.2 * mesh.Vertices.col(2) + Vector::Constant(mesh.Vertices.rows(), 4.0);
  const Vector Lf = L * f;
  double interior = 0.0;
  double boundary = 0.0;
  for (int j = 0; j <= ny; ++j)
  {
    for (int i = 0; i <= nx; ++i)
    {
      const bool onBoundary = (i == 0 || i == nx || j == 0 || j == ny);
      double& worst = onBoundary ? boundary : interior;
      worst = std::max(worst, std::abs(Lf[j * (nx + 1) + i]));
    }
  }
  const double scale = MaxAbs(L) * f.cwiseAbs().maxCoeff();
  CheckBelow(interior, 1e-12 * scale, "irregular tilted plane: max |L f| at interior points");
  // The Dirichlet energy of a linear function is exact: f^T L f = |in-plane gradient|^2 area.
  const Eigen::Vector3d g(1.5, -0.7, 0.2);
  const Eigen::Vector3d normal =
    (mesh.Vertices.row(1) - mesh.Vertices.row(0))
      .cross(mesh.Vertices.row(nx + 1) - mesh.Vertices.row(0))
      .normalized()
      .transpose();
  const double energy = (g - g.dot(normal) * normal).squaredNorm() * SurfaceArea(mesh);
  CheckNear(f.dot(Lf), energy, 1e-12 * energy, "f^T L f = |grad f|^2 area");
  CheckNear(SurfaceArea(mesh), 2.0, 1e-13, "the jittered plane keeps its area");
  // The natural boundary condition: L f is the outward flux there, not zero.
  Check(boundary > 1e-3 * scale, "... while L f != 0 on the free boundary (" +
      std::to_string(boundary) + ")");
}

/// Points 0-3 span two good triangles; the others make every kind of degenerate triangle.
TriangleMesh DegenerateMesh()
{
  TriangleMesh mesh;
  mesh.Vertices.resize(7, 3);
  mesh.Vertices << 0, 0, 0, //
    1, 0, 0,                //
    0, 1, 0,                //
    1, 1, 0,                //
    2, 0, 0,                // collinear with 0 and 1
    1, 0, 0,                // same position as 1
    5, 5, 5;                // used by no triangle
  mesh.Faces.resize(6, 3);
  mesh.Faces << 0, 1, 2, //
    1, 3, 2,             //
    0, 1, 4,             // zero area, distinct points
    1, 1, 3,             // repeated index
    1, 5, 3,             // repeated position
    2, 2, 2;             // a single point
  return mesh;
}

//------------------------------------------------------------------------------
void DegenerateTrianglesFinite()
{
  const TriangleMesh mesh = DegenerateMesh();
  const SparseMatrix L = CotanStiffness(mesh);
  Check(AllFinite(L), "cotan stiffness finite with degenerate triangles");
  Check(LumpedMass(mesh).allFinite(), "lumped mass finite with degenerate triangles");
  Check(AllFinite(ConsistentMass(mesh)), "consistent mass finite with degenerate triangles");
  CheckBelow((L * Vector::Ones(L.cols())).cwiseAbs().maxCoeff(), 1e-15,
    "max |L 1| with degenerate triangles");
  // Only the two good triangles (the unit square) contribute.
  CheckNear(SurfaceArea(mesh), 1.0, 1e-15, "area of the degenerate mesh");
  Check(std::isfinite(MeanEdgeLength(mesh)), "mean edge length finite");
}

//------------------------------------------------------------------------------
void PrepareMeshDropsDegenerate()
{
  const PreparedMesh prepared = PrepareMesh(DegenerateMesh());
  Check(prepared.DegenerateTriangles == 4,
    "4 degenerate triangles dropped (got " + std::to_string(prepared.DegenerateTriangles) + ")");
  Check(prepared.Mesh.Faces.rows() == 2,
    "2 triangles kept (got " + std::to_string(prepared.Mesh.Faces.rows()) + ")");
  Check(prepared.UnusedPoints == 3,
    "3 points unused (got " + std::to_string(prepared.UnusedPoints) + ")");
  Check(
    prepared.InputPointIds == std::vector<int>({ 0, 1, 2, 3 }), "kept points map to 0, 1, 2, 3");
  bool sameGeometry = prepared.Mesh.Vertices.rows() == 4;
  for (Eigen::Index t = 0; sameGeometry && t < prepared.Mesh.Faces.rows(); ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      const int local = prepared.Mesh.Faces(t, c);
      sameGeometry = sameGeometry && local >= 0 && local < 4 &&
        prepared.Mesh.Vertices.row(local) ==
          DegenerateMesh().Vertices.row(prepared.InputPointIds[local]);
    }
  }
  Check(sameGeometry, "kept triangles index the kept points at their input positions");
  const SparseMatrix L = CotanStiffness(prepared.Mesh);
  const Vector d = LumpedMass(prepared.Mesh);
  Check(d.minCoeff() > 0.0, "every kept point has positive mass");
  CheckBelow((L * Vector::Ones(4)).cwiseAbs().maxCoeff(), 1e-15, "max |L 1| on the kept mesh");

  // A clean mesh passes through unchanged.
  const TriangleMesh sphere = Icosphere(2);
  const PreparedMesh same = PrepareMesh(sphere);
  Check(same.DegenerateTriangles == 0 && same.UnusedPoints == 0 &&
      same.Mesh.Vertices == sphere.Vertices && same.Mesh.Faces == sphere.Faces,
    "a clean icosphere is unchanged");
}

//------------------------------------------------------------------------------
void PrepareMeshRejectsBadInput()
{
  TriangleMesh nan = DegenerateMesh();
  nan.Vertices(3, 1) = std::numeric_limits<double>::quiet_NaN();
  CheckThrows<InvalidInput>([&nan]() { PrepareMesh(nan); }, "NaN coordinate on a used point");
  TriangleMesh inf = DegenerateMesh();
  inf.Vertices(0, 2) = std::numeric_limits<double>::infinity();
  CheckThrows<InvalidInput>([&inf]() { PrepareMesh(inf); }, "infinite coordinate");
  // Found by FuzzCore: edges of 1e150 overflow the cross product to an infinite area.
  TriangleMesh huge = DegenerateMesh();
  huge.Vertices.row(0) << 1e150, 1e150, 1e150;
  CheckThrows<InvalidInput>([&huge]() { PrepareMesh(huge); }, "coordinate of magnitude 1e150");
  TriangleMesh unusedNan = DegenerateMesh();
  unusedNan.Vertices(6, 0) = std::numeric_limits<double>::quiet_NaN();
  bool accepted = true;
  try
  {
    accepted = PrepareMesh(unusedNan).UnusedPoints == 3;
  }
  catch (const InvalidInput&)
  {
    accepted = false;
  }
  Check(accepted, "NaN on a point no triangle uses is accepted (the point is dropped)");
  TriangleMesh negative = DegenerateMesh();
  negative.Faces(1, 2) = -1;
  CheckThrows<InvalidInput>([&negative]() { PrepareMesh(negative); }, "negative point index");
  TriangleMesh tooLarge = DegenerateMesh();
  tooLarge.Faces(0, 1) = 7;
  CheckThrows<InvalidInput>([&tooLarge]() { PrepareMesh(tooLarge); }, "point index = #points");
}

//------------------------------------------------------------------------------
void MeshMeasures()
{
  const double hx = 2.0 / 20;
  const double hy = 1.0 / 10;
  CheckNear(MeanEdgeLength(Rectangle(2.0, 1.0, 20, 10)), (hx + hy + std::hypot(hx, hy)) / 3.0,
    1e-14, "mean edge length of the 20 x 10 grid of a 2 x 1 rectangle");
  Check(MeanEdgeLength(TriangleMesh()) == 0.0, "mean edge length of an empty mesh is 0");
  Check(ConnectedComponents(Icosphere(2)) == 1, "one component in an icosphere");
  Check(ConnectedComponents(Join(Icosphere(1), Translated(Icosphere(1), 3.0))) == 2,
    "two components in two disjoint spheres");
  Check(ConnectedComponents(DegenerateMesh()) == 2, "isolated point counts as a component");
}

/// The torus of Torus(2, 0.5, nu, nv) cut open along its ring u = 0: the triangles of the last
/// strip use copies of that ring's points, moved by `gap` times the bounding box diagonal along y.
TriangleMesh TorusWithOpenSeam(int nu, int nv, double gap)
{
  TriangleMesh mesh = Torus(2.0, 0.5, nu, nv);
  const double diagonal = BoundingBoxDiagonal(mesh.Vertices);
  mesh.Vertices.conservativeResize(nu * nv + nv, 3);
  for (int j = 0; j < nv; ++j)
  {
    mesh.Vertices.row(nu * nv + j) = mesh.Vertices.row(j);
    mesh.Vertices(nu * nv + j, 1) += gap * diagonal;
  }
  for (int f = 2 * (nu - 1) * nv; f < 2 * nu * nv; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      mesh.Faces(f, c) += mesh.Faces(f, c) < nv ? nu * nv : 0;
    }
  }
  return mesh;
}

/// FindOpenSeams: a seam left open by 1e-9 or 1e-5 of the diagonal is found, each of its nv
/// point pairs once, with its gap; closed surfaces, a rectangle's boundary, a scan's defects
/// (near-coincident points joined by their tiny edges, needles, zero-area triangles, whose
/// edges to their midpoint are boundary edges) and a seam opened by more than OpenSeamGap edge
/// lengths are not. (Not the scan model's islands: two of them may overlap by chance, and two
/// pieces of surface nearly on top of each other are what the warning is for.)
void OpenSeamsFound()
{
  const int nu = 40;
  const int nv = 16;
  for (const double gap : { 1e-9, 1e-5 })
  {
    const OpenSeams open = FindOpenSeams(TorusWithOpenSeam(nu, nv, gap));
    Check(open.Pairs == nv,
      "a seam opened by " + std::to_string(gap) + ": " + std::to_string(open.Pairs) +
        " pairs found, not " + std::to_string(nv));
    Check(std::abs(open.LargestGap - gap) <= 1e-3 * gap,
      "a seam opened by " + std::to_string(gap) + ": largest gap " +
        std::to_string(open.LargestGap));
  }
  const TriangleMesh wide = TorusWithOpenSeam(nu, nv, 0.0);
  const double edge = MeanEdgeLength(wide) / BoundingBoxDiagonal(wide.Vertices);
  Check(FindOpenSeams(TorusWithOpenSeam(nu, nv, 2.0 * OpenSeamGap * edge)).Pairs == 0,
    "a gap of twice OpenSeamGap edge lengths is no seam");
  for (const Named& named : Meshes())
  {
    Check(FindOpenSeams(named.Mesh).Pairs == 0, std::string(named.Name) + " has an open seam");
  }
  ScanDefects defects;
  defects.NearCoincident = 40;
  defects.Needles = 40;
  defects.ZeroArea = 30;
  const OpenSeams scan = FindOpenSeams(WithScanDefects(NoisyTorusOfSize(20000, 0.02), defects));
  Check(
    scan.Pairs == 0, "a scan's defects taken for " + std::to_string(scan.Pairs) + " open seams");
  Check(FindOpenSeams(TriangleMesh()).Pairs == 0, "an empty mesh has an open seam");
}

const Case Cases[] = {
  { "StiffnessSymmetric", StiffnessSymmetric },
  { "StiffnessConstantsInKernel", StiffnessConstantsInKernel },
  { "MassEqualsArea", MassEqualsArea },
  { "ConsistentRowSums", ConsistentRowSums },
  { "LinearPrecision", LinearPrecision },
  { "DegenerateTrianglesFinite", DegenerateTrianglesFinite },
  { "PrepareMeshDropsDegenerate", PrepareMeshDropsDegenerate },
  { "PrepareMeshRejectsBadInput", PrepareMeshRejectsBadInput },
  { "MeshMeasures", MeshMeasures },
  { "OpenSeamsFound", OpenSeamsFound },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
