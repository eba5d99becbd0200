// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// A corpus of bad and real-world-like meshes, built in code, through vtkManifoldHarmonicBasis
// with both Laplacians, then through vtkManifoldHarmonicTransform and vtkSpectralFilter. Every
// case ends in one of three expected ways: a valid basis (finite, M-orthonormal, eigenvalues
// ascending, lambda_0 = 0), possibly with a warning naming what was repaired or ignored; the
// input passed through with a warning; or an error naming the problem. Expected errors and
// warnings are caught by observers and their text is checked. A table of outcomes per Laplacian
// is printed. Last, an abort requested from another thread during the eigensolve on a ~60K
// point sphere must stop the filter at its next polls (no more than a step's progress reports
// after the request, where the solve would report hundreds), with an empty output.

#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkPointSetAlgorithm.h"
#include "vtkSpectralFilter.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkStripper.h"
#include "vtkTestErrorObserver.h"
#include "vtkTriangleFilter.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <thread>
#include <vector>

namespace
{
using ManifoldHarmonicsTest::Check;
using ManifoldHarmonicsTest::Perturb;

//------------------------------------------------------------------------------
// The text of a VTK message without its "ERROR: In file, line" prefix, which the test harness
// would take for a failure.
std::string AfterLocation(const std::string& message)
{
  // Each message reads "ERROR: In <file>, line <n>\n<class> (<address>): <text>\n\n".
  std::string out;
  std::size_t start = 0;
  while (start < message.size())
  {
    std::size_t end = message.find('\n', start);
    end = end == std::string::npos ? message.size() : end;
    const std::string line = message.substr(start, end - start);
    const std::size_t text = line.find("): ");
    if (!line.empty() && line.rfind("ERROR: In ", 0) != 0 && line.rfind("Warning: In ", 0) != 0)
    {
      out += " |" + (text == std::string::npos ? " " + line : line.substr(text + 2));
    }
    start = end + 1;
  }
  return out;
}

//==============================================================================
// Mesh builders.

//------------------------------------------------------------------------------
// A closed UV sphere of the given radius with double coordinates, triangles only.
vtkSmartPointer<vtkPolyData> Sphere(int resolution, double radius = 1.0)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(resolution);
  source->SetPhiResolution(resolution);
  source->SetRadius(radius);
  source->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  source->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(source->GetOutput());
  out->GetPointData()->Initialize();
  Perturb(out->GetPoints());
  return out;
}

//------------------------------------------------------------------------------
// A flat n by n grid of triangles on [0, 1]^2 with double coordinates.
vtkSmartPointer<vtkPolyData> Plane(int n)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(n, n);
  plane->SetOrigin(0, 0, 0);
  plane->SetPoint1(1, 0, 0);
  plane->SetPoint2(0, 1, 0);
  plane->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(triangles->GetOutput());
  out->GetPointData()->Initialize();
  Perturb(out->GetPoints());
  return out;
}

//------------------------------------------------------------------------------
// Points and triangles given as lists.
vtkSmartPointer<vtkPolyData> Soup(const std::vector<std::array<double, 3>>& xyz,
  const std::vector<std::vector<vtkIdType>>& cells)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const auto& p : xyz)
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& c : cells)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(c.size()), c.data());
  }
  Perturb(points);
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(points);
  out->SetPolys(polys);
  return out;
}

//------------------------------------------------------------------------------
// Appends the points and the polygons of b to a (b's point ids shifted).
void Append(vtkPolyData* a, vtkPolyData* b)
{
  const vtkIdType offset = a->GetNumberOfPoints();
  for (vtkIdType i = 0; i < b->GetNumberOfPoints(); ++i)
  {
    a->GetPoints()->InsertNextPoint(b->GetPoint(i));
  }
  vtkCellArray* polys = b->GetPolys();
  vtkIdType npts;
  const vtkIdType* pts;
  for (polys->InitTraversal(); polys->GetNextCell(npts, pts);)
  {
    std::vector<vtkIdType> shifted(pts, pts + npts);
    for (auto& id : shifted)
    {
      id += offset;
    }
    a->GetPolys()->InsertNextCell(npts, shifted.data());
  }
  a->Modified();
}

//------------------------------------------------------------------------------
// Adds one triangle and returns a.
vtkPolyData* AddTriangle(vtkPolyData* a, vtkIdType p, vtkIdType q, vtkIdType r)
{
  const vtkIdType ids[3] = { p, q, r };
  a->GetPolys()->InsertNextCell(3, ids);
  return a;
}

//------------------------------------------------------------------------------
// The end points of the first edge of the first triangle.
void FirstEdge(vtkPolyData* mesh, vtkIdType& p, vtkIdType& q, vtkIdType& r)
{
  vtkIdType npts;
  const vtkIdType* pts;
  mesh->GetPolys()->InitTraversal();
  mesh->GetPolys()->GetNextCell(npts, pts);
  p = pts[0];
  q = pts[1];
  r = pts[2];
}

//------------------------------------------------------------------------------
// The polygons of a mesh with some of them replaced or dropped by `edit` (return false to drop).
vtkSmartPointer<vtkPolyData> EditCells(vtkPolyData* mesh,
  const std::function<bool(vtkIdType, std::vector<vtkIdType>&)>& edit)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(mesh->GetPoints());
  vtkNew<vtkCellArray> polys;
  vtkIdType npts;
  const vtkIdType* pts;
  vtkIdType cell = 0;
  for (mesh->GetPolys()->InitTraversal(); mesh->GetPolys()->GetNextCell(npts, pts); ++cell)
  {
    std::vector<vtkIdType> ids(pts, pts + npts);
    if (edit(cell, ids))
    {
      polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    }
  }
  out->SetPolys(polys);
  return out;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> Scaled(vtkPolyData* mesh, double s)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(mesh);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    out->GetPoints()->SetPoint(i, s * p[0], s * p[1], s * p[2]);
  }
  return out;
}

//==============================================================================
// Running the basis and judging its output.

enum class Expect
{
  Valid,       // a valid basis
  PassThrough, // a warning, the input passes without basis arrays
  Error        // an error naming the problem
};

struct Outcome
{
  bool Valid = false;
  bool Error = false;
  bool PassedThrough = false;
  std::string Errors;
  std::string Warnings;
  std::string Why; // what makes the basis invalid
  std::vector<double> Eigenvalues;
  vtkSmartPointer<vtkPolyData> Output;
};

//------------------------------------------------------------------------------
// Checks the basis arrays of `output`; returns an empty string if they form a valid basis.
std::string JudgeBasis(vtkPolyData* output, int m, std::vector<double>& lambda)
{
  auto* H = vtkDoubleArray::SafeDownCast(
    output->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName()));
  vtkDataArray* D = output->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName());
  vtkDataArray* L =
    output->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  if (!H || !D || !L)
  {
    return "missing basis arrays";
  }
  const vtkIdType n = output->GetNumberOfPoints();
  if (H->GetNumberOfTuples() != n || H->GetNumberOfComponents() != m ||
    L->GetNumberOfTuples() != m || D->GetNumberOfTuples() != n)
  {
    return "wrong shapes: " + std::to_string(H->GetNumberOfComponents()) + " harmonics, " +
      std::to_string(L->GetNumberOfTuples()) + " eigenvalues, expected " + std::to_string(m);
  }
  lambda.assign(static_cast<std::size_t>(m), 0.0);
  for (int k = 0; k < m; ++k)
  {
    lambda[k] = L->GetComponent(k, 0);
  }
  const double top = std::max(std::abs(lambda.back()), std::numeric_limits<double>::min());
  for (int k = 0; k < m; ++k)
  {
    if (!std::isfinite(lambda[k]))
    {
      return "non-finite eigenvalue";
    }
    if (k > 0 && lambda[k] < lambda[k - 1] - 1e-9 * top)
    {
      return "eigenvalues not ascending";
    }
  }
  if (m > 1 && std::abs(lambda[0]) > 1e-8 * top)
  {
    return "lambda_0 = " + std::to_string(lambda[0]) + " is not 0";
  }
  // Phi^T D Phi = I with the output mass, each welded point counted once (its copies are flagged
  // DUPLICATEPOINT).
  std::vector<double> gram(static_cast<std::size_t>(m) * m, 0.0);
  const double* h = H->GetPointer(0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double d = D->GetComponent(i, 0) * ManifoldHarmonicsTest::CountedPoint(output, i);
    if (!std::isfinite(d) || d < 0.0)
    {
      return "bad mass";
    }
    for (int a = 0; a < m; ++a)
    {
      if (!std::isfinite(h[i * m + a]))
      {
        return "non-finite harmonic";
      }
      for (int b = 0; b <= a; ++b)
      {
        gram[a * m + b] += d * h[i * m + a] * h[i * m + b];
      }
    }
  }
  double worst = 0.0;
  for (int a = 0; a < m; ++a)
  {
    for (int b = 0; b <= a; ++b)
    {
      worst = std::max(worst, std::abs(gram[a * m + b] - (a == b ? 1.0 : 0.0)));
    }
  }
  if (!(worst < 1e-8))
  {
    return "not M-orthonormal: " + std::to_string(worst);
  }
  return std::string();
}

//------------------------------------------------------------------------------
Outcome RunBasis(vtkPolyData* input, int m, int laplacian, int expectedM = -1)
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  const ManifoldHarmonicsTest::Messages messages(basis);
  basis->SetNumberOfHarmonics(m);
  basis->SetLaplacian(laplacian);
  basis->SetInputData(input);
  basis->Update();
  Outcome out;
  out.Output = basis->GetPolyDataOutput();
  out.Error = messages->GetError();
  out.Errors = messages->GetErrorMessage();
  out.Warnings = messages->GetWarningMessage();
  vtkPolyData* output = basis->GetPolyDataOutput();
  const bool hasHarmonics =
    output->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName()) != nullptr;
  out.PassedThrough =
    !out.Error && !hasHarmonics && output->GetNumberOfPoints() == input->GetNumberOfPoints();
  if (!out.Error && hasHarmonics)
  {
    out.Why = JudgeBasis(
      output, expectedM > 0 ? expectedM : basis->GetNumberOfHarmonics(), out.Eigenvalues);
    out.Valid = out.Why.empty();
  }
  return out;
}

//==============================================================================
// The corpus.

struct Case
{
  std::string Name;
  vtkSmartPointer<vtkPolyData> Mesh;
  int Harmonics;
  Expect Expected;
  std::string Message;   // expected in the warning (Valid, PassThrough) or error text
  int ExpectedHarmonics; // -1: as requested
  /// The robust (tufted, mollified) intrinsic Laplacian gives a valid basis where the cotan
  /// one gives the Expected outcome.
  bool IntrinsicValid = false;
};

std::vector<Case> Corpus()
{
  std::vector<Case> cases;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  cases.push_back({ "closed sphere (reference)", Sphere(16), 20, Expect::Valid, "", -1 });

  {
    // A fin: a third (and fourth) triangle on an edge of the sphere.
    auto mesh = Sphere(16);
    vtkIdType p, q, r;
    FirstEdge(mesh, p, q, r);
    const vtkIdType apex = mesh->GetPoints()->InsertNextPoint(0.3, 0.2, 1.5);
    const vtkIdType apex2 = mesh->GetPoints()->InsertNextPoint(-0.3, 0.4, 1.4);
    AddTriangle(mesh, p, q, apex);
    AddTriangle(mesh, q, p, apex2);
    cases.push_back(
      { "non-manifold edges (4 triangles on an edge)", mesh, 20, Expect::Valid, "", -1 });
  }
  {
    // Two grids that touch at one corner point: a bowtie vertex.
    auto a = Plane(6);
    auto b = Plane(6);
    for (vtkIdType i = 0; i < b->GetNumberOfPoints(); ++i)
    {
      double x[3];
      b->GetPoint(i, x);
      b->GetPoints()->SetPoint(i, -x[0], -x[1], x[0] * x[1]);
    }
    const vtkIdType n = a->GetNumberOfPoints();
    Append(a, b);
    // Point 0 of both grids is the origin: use the first one in b's triangles.
    auto welded = EditCells(a,
      [n](vtkIdType, std::vector<vtkIdType>& ids)
      {
        for (auto& id : ids)
        {
          id = id == n ? 0 : id;
        }
        return true;
      });
    // b's own copy of the origin, which no triangle uses, is welded to it (WeldSeams).
    cases.push_back(
      { "bowtie vertex (two grids share a point)", welded, 20, Expect::Valid, "", -1 });
  }
  {
    // Zero-area triangles: a repeated point, three collinear points.
    auto mesh = Sphere(16);
    vtkIdType p, q, r;
    FirstEdge(mesh, p, q, r);
    AddTriangle(mesh, p, p, q);
    double a[3], b[3];
    mesh->GetPoint(p, a);
    mesh->GetPoint(q, b);
    const vtkIdType mid =
      mesh->GetPoints()->InsertNextPoint((a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2);
    AddTriangle(mesh, p, q, mid);
    cases.push_back({ "zero-area triangles", mesh, 20, Expect::Valid, "degenerate", -1 });
  }
  {
    // Needles inside the surface: the first 40 triangles (p, q, r) split at a point x 1e-4 of
    // the edge length off the midpoint of pq: (p, q, x) has an angle of almost pi at x.
    auto sphere = Sphere(16);
    std::vector<std::array<vtkIdType, 3>> extra;
    auto mesh = EditCells(sphere,
      [&sphere, &extra](vtkIdType cell, std::vector<vtkIdType>& ids)
      {
        if (cell >= 40)
        {
          return true;
        }
        double p[3], q[3], r[3], x[3];
        sphere->GetPoint(ids[0], p);
        sphere->GetPoint(ids[1], q);
        sphere->GetPoint(ids[2], r);
        for (int c = 0; c < 3; ++c)
        {
          const double m = (p[c] + q[c]) / 2;
          x[c] = m + 1e-4 * (r[c] - m);
        }
        const vtkIdType xi = sphere->GetPoints()->InsertNextPoint(x);
        extra.push_back({ ids[1], ids[2], xi });
        extra.push_back({ ids[2], ids[0], xi });
        ids[2] = xi;
        return true;
      });
    for (const auto& t : extra)
    {
      mesh->GetPolys()->InsertNextCell(3, t.data());
    }
    cases.push_back({ "needle triangles inside the surface", mesh, 20, Expect::Valid, "", -1 });
  }
  for (const int resolution : { 16, 40 })
  {
    // A sliver hanging on a non-manifold fin: angle of almost pi at its apex, 3 triangles on
    // its long edge (lambda_max / lambda_1 about 4e14). The dense solve of the small mesh
    // (16: 212 points) missed the backward error test by far (1e-5) until it also solved the
    // inverted pencil (EigenSolver.cxx, DenseEigenpairs); the bands (40: 1522 points) meet it.
    auto mesh = Sphere(resolution);
    vtkIdType p, q, r;
    FirstEdge(mesh, p, q, r);
    double a[3], b[3];
    mesh->GetPoint(p, a);
    mesh->GetPoint(q, b);
    const vtkIdType needle = mesh->GetPoints()->InsertNextPoint(
      (a[0] + b[0]) / 2 + 1e-7, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2 + 1e-7);
    AddTriangle(mesh, q, p, needle);
    cases.push_back({ "sliver on a non-manifold edge, " + std::to_string(resolution) + "^2 sphere",
      mesh,
      20,
      Expect::Valid,
      "",
      -1 });
  }
  {
    // Needle-only surface: a plane whose points are squeezed along y.
    auto mesh = Plane(20);
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double x[3];
      mesh->GetPoint(i, x);
      mesh->GetPoints()->SetPoint(i, x[0], 1e-3 * x[1], 0.0);
    }
    cases.push_back(
      { "needle triangles everywhere (aspect 1000)", mesh, 20, Expect::Valid, "", -1 });
  }
  {
    // A grid cut along x = 0.5 into two halves with duplicated seam points.
    auto mesh = Plane(10);
    const vtkIdType n = mesh->GetNumberOfPoints();
    for (vtkIdType i = 0; i < n; ++i)
    {
      double x[3];
      mesh->GetPoint(i, x);
      mesh->GetPoints()->InsertNextPoint(x);
    }
    auto seamed = EditCells(mesh,
      [&mesh, n](vtkIdType, std::vector<vtkIdType>& ids)
      {
        double c = 0.0;
        for (auto id : ids)
        {
          c += mesh->GetPoint(id)[0] / 3.0;
        }
        if (c > 0.5)
        {
          for (auto& id : ids)
          {
            id += n;
          }
        }
        return true;
      });
    // WeldSeams (default on) welds the seam: one component (TestWeldSeams.cxx keeps it open).
    cases.push_back({ "unwelded seam (duplicate points)", seamed, 20, Expect::Valid, "", -1 });
  }
  {
    auto mesh = Sphere(16);
    for (int i = 0; i < 10; ++i)
    {
      mesh->GetPoints()->InsertNextPoint(5.0 + i, 0.0, 0.0);
    }
    cases.push_back({ "points no triangle uses",
      mesh,
      20,
      Expect::Valid,
      "10 points are used by no triangle",
      -1 });
  }
  cases.push_back({ "inconsistently oriented triangles",
    EditCells(Sphere(16),
      [](vtkIdType cell, std::vector<vtkIdType>& ids)
      {
        if (cell % 2 == 0)
        {
          std::reverse(ids.begin(), ids.end());
        }
        return true;
      }),
    20,
    Expect::Valid,
    "",
    -1 });
  cases.push_back({ "holes (every 7th triangle removed)",
    EditCells(Sphere(16), [](vtkIdType cell, std::vector<vtkIdType>&) { return cell % 7 != 3; }),
    20,
    Expect::Valid,
    "",
    -1 });
  {
    auto mesh = Sphere(16);
    for (int i = 0; i < 50; ++i)
    {
      const double x = 3.0 + 0.1 * i;
      auto tiny = Soup({ { x, 0, 0 }, { x + 0.01, 0, 0 }, { x, 0.01, 0 } }, { { 0, 1, 2 } });
      Append(mesh, tiny);
    }
    cases.push_back(
      { "50 tiny triangles + a sphere", mesh, 60, Expect::Valid, "51 connected components", -1 });
  }
  cases.push_back({ "scale 1e-6", Scaled(Sphere(16), 1e-6), 20, Expect::Valid, "", -1 });
  cases.push_back({ "scale 1e6", Scaled(Sphere(16), 1e6), 20, Expect::Valid, "", -1 });
  {
    auto mesh = Sphere(16);
    mesh->GetPoints()->SetPoint(5, nan, 0.0, 0.0);
    cases.push_back({ "NaN coordinate", mesh, 20, Expect::Error, "NaN", -1 });
  }
  {
    auto mesh = Sphere(16);
    mesh->GetPoints()->SetPoint(5, 0.0, inf, 0.0);
    cases.push_back({ "Inf coordinate", mesh, 20, Expect::Error, "infinite", -1 });
  }
  {
    auto mesh = Sphere(16);
    mesh->GetPoints()->InsertNextPoint(nan, nan, nan);
    cases.push_back(
      { "NaN on an unused point", mesh, 20, Expect::Valid, "used by no triangle", -1 });
  }
  {
    vtkNew<vtkPlaneSource> quads;
    quads->SetResolution(8, 8);
    quads->Update();
    auto mesh = vtkSmartPointer<vtkPolyData>::New();
    mesh->DeepCopy(quads->GetOutput());
    cases.push_back({ "quads", mesh, 20, Expect::Valid, "Triangulating", -1 });
  }
  {
    std::vector<std::array<double, 3>> xyz = { { 0, 0, 0 } };
    std::vector<vtkIdType> ring;
    for (int i = 0; i < 8; ++i)
    {
      xyz.push_back({ std::cos(i * 0.785398), std::sin(i * 0.785398), 0.0 });
      ring.push_back(i + 1);
    }
    cases.push_back(
      { "one octagon polygon", Soup(xyz, { ring }), 5, Expect::Valid, "Triangulating", -1 });
  }
  {
    vtkNew<vtkStripper> stripper;
    stripper->SetInputData(Sphere(16));
    stripper->Update();
    auto mesh = vtkSmartPointer<vtkPolyData>::New();
    mesh->DeepCopy(stripper->GetOutput());
    cases.push_back({ "triangle strips", mesh, 20, Expect::Valid, "Triangulating", -1 });
  }
  {
    auto mesh = Sphere(16);
    vtkNew<vtkCellArray> lines;
    const vtkIdType line[2] = { 0, 1 };
    lines->InsertNextCell(2, line);
    vtkNew<vtkCellArray> verts;
    const vtkIdType vert[1] = { 2 };
    verts->InsertNextCell(1, vert);
    mesh->SetLines(lines);
    mesh->SetVerts(verts);
    cases.push_back({ "sphere with lines and vertices", mesh, 20, Expect::Valid, "", -1 });
  }
  {
    auto mesh = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> points;
    points->InsertNextPoint(0, 0, 0);
    points->InsertNextPoint(1, 0, 0);
    mesh->SetPoints(points);
    vtkNew<vtkCellArray> lines;
    const vtkIdType line[2] = { 0, 1 };
    lines->InsertNextCell(2, line);
    mesh->SetLines(lines);
    cases.push_back({ "lines only", mesh, 20, Expect::PassThrough, "No polygons", -1 });
  }
  cases.push_back({ "empty input",
    vtkSmartPointer<vtkPolyData>::New(),
    20,
    Expect::PassThrough,
    "No polygons",
    -1 });
  cases.push_back({ "single triangle",
    Soup({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 1, 2 } }),
    20,
    Expect::Valid,
    "clamped to 3",
    3 });
  cases.push_back({ "only degenerate triangles",
    Soup({ { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 } }, { { 0, 1, 2 }, { 0, 0, 1 } }),
    20,
    Expect::Error,
    "degenerate",
    -1 });
  cases.push_back({ "triangle with an out-of-range point id",
    Soup({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 1, 2 }, { 0, 1, 7 } }),
    20,
    Expect::Error,
    "refers to point 7",
    -1 });
  cases.push_back(
    { "NumberOfHarmonics = number of points", Sphere(8), 8 * 6 + 2, Expect::Valid, "", -1 });
  cases.push_back({ "NumberOfHarmonics > number of points",
    Sphere(8),
    1000,
    Expect::Valid,
    "clamped to 50",
    50 });
  return cases;
}

//------------------------------------------------------------------------------
// Runs a case with one Laplacian; checks the outcome against the expectation.
bool RunCase(const Case& c, int laplacian, Outcome& out)
{
  out = RunBasis(c.Mesh, c.Harmonics, laplacian, c.ExpectedHarmonics);
  const std::string label =
    c.Name + (laplacian == vtkManifoldHarmonicBasis::COTANGENT ? " [cotan]" : " [intrinsic]");
  std::cout << label << ":" << (out.Valid ? " valid basis" : "")
            << (out.PassedThrough ? " passed through" : "") << (out.Error ? " error" : "")
            << AfterLocation(out.Errors + out.Warnings) << (out.Why.empty() ? "" : " | " + out.Why)
            << "\n";
  bool ok = true;
  const bool intrinsic = laplacian == vtkManifoldHarmonicBasis::INTRINSIC_DELAUNAY;
  switch (intrinsic && c.IntrinsicValid ? Expect::Valid : c.Expected)
  {
    case Expect::Valid:
      ok &= Check(out.Valid, label + ": no valid basis (" + out.Why + ")");
      ok &= Check(c.Message.empty() || c.Expected != Expect::Valid ||
          out.Warnings.find(c.Message) != std::string::npos,
        label + ": no warning containing '" + c.Message + "'");
      break;
    case Expect::PassThrough:
      ok &= Check(out.PassedThrough, label + ": input not passed through");
      ok &= Check(out.Warnings.find(c.Message) != std::string::npos,
        label + ": no warning containing '" + c.Message + "'");
      break;
    case Expect::Error:
      ok &= Check(out.Error && out.Output->GetNumberOfPoints() == 0,
        label + ": no error, or a partial output");
      ok &= Check(out.Errors.find(c.Message) != std::string::npos,
        label + ": no error containing '" + c.Message + "'");
      break;
  }
  return ok;
}

//------------------------------------------------------------------------------
// Runs the corpus with both Laplacians, prints the table, and checks properties that relate
// cases: scaling, orientation, components.
bool TestCorpus()
{
  bool ok = true;
  const std::vector<Case> cases = Corpus();
  std::vector<std::array<std::string, 2>> table;
  int valid[2] = { 0, 0 };
  int asExpected[2] = { 0, 0 };
  std::vector<double> reference[2];
  std::vector<double> scaled[2][2];
  for (const Case& c : cases)
  {
    std::array<std::string, 2> row;
    for (int laplacian = 0; laplacian < 2; ++laplacian)
    {
      Outcome out;
      const bool expected = RunCase(c, laplacian, out);
      ok &= expected;
      valid[laplacian] += out.Valid ? 1 : 0;
      asExpected[laplacian] += expected ? 1 : 0;
      row[laplacian] = std::string(out.Valid   ? "valid"
                           : out.PassedThrough ? "passed"
                           : out.Error         ? "error"
                                               : "BAD") +
        (expected ? "" : " (unexpected)");
      if (c.Name == "closed sphere (reference)")
      {
        reference[laplacian] = out.Eigenvalues;
      }
      if (c.Name == "scale 1e-6")
      {
        scaled[laplacian][0] = out.Eigenvalues;
      }
      if (c.Name == "scale 1e6")
      {
        scaled[laplacian][1] = out.Eigenvalues;
      }
      if (c.Name == "50 tiny triangles + a sphere" && out.Valid)
      {
        ok &= Check(out.Eigenvalues[50] == 0.0 && out.Eigenvalues[51] > 1e-3 * out.Eigenvalues[59],
          "51 components do not give exactly 51 zero eigenvalues");
      }
      if (c.Name == "inconsistently oriented triangles" && out.Valid)
      {
        double worst = 0.0;
        for (std::size_t k = 1; k < out.Eigenvalues.size(); ++k)
        {
          worst = std::max(worst, std::abs(out.Eigenvalues[k] / reference[laplacian][k] - 1.0));
        }
        ok &= Check(worst < 1e-8, "orientation changes the eigenvalues: " + std::to_string(worst));
      }
    }
    table.push_back(row);
  }

  // Eigenvalues scale as 1 / s^2.
  for (int laplacian = 0; laplacian < 2; ++laplacian)
  {
    const double scales[2] = { 1e-6, 1e6 };
    for (int s = 0; s < 2; ++s)
    {
      double worst = 0.0;
      for (std::size_t k = 1; k < reference[laplacian].size() && k < scaled[laplacian][s].size();
           ++k)
      {
        worst = std::max(worst,
          std::abs(
            scaled[laplacian][s][k] * scales[s] * scales[s] / reference[laplacian][k] - 1.0));
      }
      std::printf("Laplacian %d, scale %g: max |lambda_k s^2 / lambda_k(1) - 1| = %.2e\n",
        laplacian,
        scales[s],
        worst);
      ok &= Check(scaled[laplacian][s].size() == reference[laplacian].size() && worst < 1e-6,
        "eigenvalues do not scale as 1 / s^2");
    }
  }

  std::printf("\n%-46s | %-12s | %-12s\n", "case", "Cotangent", "Intrinsic Del.");
  std::printf("%s\n", std::string(76, '-').c_str());
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    std::printf(
      "%-46s | %-12s | %-12s\n", cases[i].Name.c_str(), table[i][0].c_str(), table[i][1].c_str());
  }
  std::printf("%s\n", std::string(76, '-').c_str());
  std::printf("%-46s | %-12d | %-12d\n", "valid bases", valid[0], valid[1]);
  std::printf(
    "%-46s | %-12d | %-12d\n\n", "outcome as expected (of cases)", asExpected[0], asExpected[1]);
  std::printf("%zu cases\n", cases.size());
  return ok;
}

//==============================================================================
// Downstream filters on bad input.

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> BasisOf(vtkPolyData* mesh, int m)
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetNumberOfHarmonics(m);
  basis->SetInputData(mesh);
  basis->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(basis->GetOutput());
  return out;
}

//------------------------------------------------------------------------------
// Runs an algorithm on `input`, expecting an error that contains `words`.
bool ExpectError(vtkPointSetAlgorithm* algorithm,
  vtkPolyData* input,
  const std::string& words,
  const std::string& what)
{
  const ManifoldHarmonicsTest::Messages messages(algorithm);
  algorithm->SetInputData(input);
  algorithm->Update();
  std::cout << what << ":" << AfterLocation(messages->GetErrorMessage()) << "\n";
  return Check(messages->GetError() && messages->GetErrorMessage().find(words) != std::string::npos,
    what + ": no error containing '" + words + "'");
}

//------------------------------------------------------------------------------
bool TestDownstream()
{
  bool ok = true;
  auto sphere = Sphere(16);
  {
    vtkNew<vtkManifoldHarmonicTransform> transform;
    ok &= ExpectError(transform, sphere, "ManifoldHarmonicBasis", "transform without a basis");
  }
  {
    vtkNew<vtkSpectralFilter> filter;
    ok &= ExpectError(filter, sphere, "ManifoldHarmonicBasis", "filter without a basis");
  }
  auto basis = BasisOf(sphere, 10);
  {
    // Eigenvalues of another basis (12 instead of 10).
    auto other = BasisOf(sphere, 12);
    vtkNew<vtkPolyData> mismatched;
    mismatched->ShallowCopy(basis);
    vtkNew<vtkFieldData> fields;
    fields->AddArray(
      other->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName()));
    mismatched->SetFieldData(fields);
    vtkNew<vtkManifoldHarmonicTransform> transform;
    ok &= ExpectError(transform,
      mismatched,
      vtkManifoldHarmonicBasis::EigenvaluesArrayName(),
      "transform with mismatched eigenvalues");
  }
  {
    // The basis of a coarser sphere on a finer one.
    auto coarse = BasisOf(Sphere(8), 10);
    vtkNew<vtkPolyData> mismatched;
    mismatched->ShallowCopy(sphere);
    mismatched->GetPointData()->AddArray(
      coarse->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName()));
    mismatched->GetPointData()->AddArray(
      coarse->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName()));
    mismatched->SetFieldData(coarse->GetFieldData());
    vtkNew<vtkManifoldHarmonicTransform> transform;
    ok &= ExpectError(transform,
      mismatched,
      vtkManifoldHarmonicBasis::HarmonicsArrayName(),
      "transform with the basis of another mesh");
  }
  {
    // Integer point arrays: transformed and filtered, integer type kept, values sensible.
    vtkNew<vtkIntArray> ints;
    ints->SetName("Labels");
    vtkNew<vtkShortArray> shorts;
    shorts->SetName("Shorts");
    shorts->SetNumberOfComponents(2);
    for (vtkIdType i = 0; i < basis->GetNumberOfPoints(); ++i)
    {
      const double z = basis->GetPoint(i)[2];
      ints->InsertNextValue(z > 0 ? 100 : -100);
      shorts->InsertNextTuple2(1000 * z, 7);
    }
    basis->GetPointData()->AddArray(ints);
    basis->GetPointData()->AddArray(shorts);
    vtkNew<vtkManifoldHarmonicTransform> transform;
    transform->SetInputData(basis);
    transform->GetPointDataArraySelection()->EnableArray("Labels");
    transform->GetPointDataArraySelection()->EnableArray("Shorts");
    vtkNew<vtkSpectralFilter> filter;
    filter->SetInputConnection(transform->GetOutputPort());
    filter->SetFilterKindToLowPass();
    filter->SetCutoffUnitsToAbsoluteFrequency();
    filter->SetCutoff(1e9);
    filter->ReplaceInputOff();
    ManifoldHarmonicsTest::Messages messages(filter);
    messages.Observe(transform);
    filter->Update();
    vtkDataArray* labels = filter->GetOutput()->GetPointData()->GetArray("Labels_Filtered");
    vtkDataArray* filteredShorts = filter->GetOutput()->GetPointData()->GetArray("Shorts_Filtered");
    ok &= Check(!messages->GetError(), "integer arrays: " + messages->GetErrorMessage());
    ok &= Check(labels && vtkIntArray::SafeDownCast(labels), "integer array not filtered as int");
    ok &= Check(filteredShorts && vtkShortArray::SafeDownCast(filteredShorts) &&
        filteredShorts->GetNumberOfComponents() == 2,
      "short array with 2 components not filtered as short");
    if (labels && filteredShorts)
    {
      double range[2];
      labels->GetRange(range, 0);
      ok &= Check(range[0] >= -150 && range[1] <= 150, "low-pass integer labels out of range");
      filteredShorts->GetRange(range, 1);
      ok &= Check(range[0] == 7 && range[1] == 7, "the constant component is not kept");
      std::cout << "Integer arrays: Labels_Filtered is a " << labels->GetClassName()
                << ", Shorts_Filtered is a " << filteredShorts->GetClassName() << "\n";
    }
  }
  return ok;
}

//==============================================================================
// Abort during a long solve.

//------------------------------------------------------------------------------
// Records the progress of an algorithm (called on the thread that runs it) and counts the
// reports strictly inside (0, 1) after Requested is set: the work done after an abort request.
class ProgressRecorder : public vtkCommand
{
public:
  static ProgressRecorder* New() { return new ProgressRecorder; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    const double progress = *static_cast<double*>(data);
    this->Progress.store(progress);
    if (this->Requested.load() && progress > 0.0 && progress < 1.0)
    {
      ++this->ReportsAfterRequest;
    }
  }
  std::atomic<double> Progress{ 0.0 };
  std::atomic<bool> Requested{ false };
  std::atomic<int> ReportsAfterRequest{ 0 };
};

//------------------------------------------------------------------------------
bool TestAbortFromAnotherThread(int laplacian)
{
  auto sphere = Sphere(250); // 250 * 248 + 2 = 62002 points
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetNumberOfHarmonics(300);
  basis->SetLaplacian(laplacian);
  basis->SetInputData(sphere);
  vtkNew<ProgressRecorder> progress;
  basis->AddObserver(vtkCommand::ProgressEvent, progress);
  vtkNew<vtkTest::ErrorObserver> messages;
  basis->AddObserver(vtkCommand::ErrorEvent, messages);

  using Clock = std::chrono::steady_clock;
  std::atomic<bool> done{ false };
  Clock::time_point finished;
  const Clock::time_point start = Clock::now();
  std::thread worker(
    [&basis, &done, &finished]()
    {
      basis->Update();
      finished = Clock::now();
      done.store(true);
    });
  // Wait until the eigensolve has started (progress past assembly), then a little more.
  while (!done.load() && progress->Progress.load() < 0.1 &&
    Clock::now() - start < std::chrono::seconds(60))
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const bool solving = !done.load();
  const double progressAtAbort = progress->Progress.load();
  const Clock::time_point requested = Clock::now();
  progress->Requested.store(true);
  basis->SetAbortExecute(1);
  worker.join();
  const double seconds = std::chrono::duration<double>(finished - requested).count();
  const int reports = progress->ReportsAfterRequest.load();
  std::printf("Abort (Laplacian %d, %lld points, 300 harmonics): requested at progress %.3f "
              "after %.2f s, returned %.3f s and %d progress reports later\n",
    laplacian,
    static_cast<long long>(sphere->GetNumberOfPoints()),
    progressAtAbort,
    std::chrono::duration<double>(requested - start).count(),
    seconds,
    reports);
  bool ok = Check(solving, "the solve ended before the abort was requested");
  // Work, not time: the eigensolver polls the abort flag before each step and reports progress
  // after it (Solver/BlockLanczos.cxx, Solver/Bands.cxx), so the step in flight and the band
  // around it report at most once each before the next poll stops the solve; 3 leaves one more.
  // A solve that went on would report after each of its remaining steps.
  ok &= Check(reports <= 3,
    "the abort stopped the solve at its next polls: " + std::to_string(reports) +
      " progress reports after the request (at most 3)");
  ok &= Check(basis->GetOutput()->GetNumberOfPoints() == 0 &&
      !basis->GetOutput()->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName()),
    "an aborted execution left a partial output");
  ok &= Check(!messages->GetError(), "abort raised an error");
  return ok;
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestRobustness(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "Corpus", TestCorpus },
      { "Downstream", TestDownstream },
      { "AbortFromAnotherThreadCotangent",
        [] { return TestAbortFromAnotherThread(vtkManifoldHarmonicBasis::COTANGENT); } },
      { "AbortFromAnotherThreadIntrinsicDelaunay",
        [] { return TestAbortFromAnotherThread(vtkManifoldHarmonicBasis::INTRINSIC_DELAUNAY); } },
    });
}
