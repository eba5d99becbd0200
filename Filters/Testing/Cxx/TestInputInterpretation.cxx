// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Checks that vtkManifoldHarmonicBasis and vtkManifoldHarmonicSmoothing say what they did with
// their input: points without cells solved as a point cloud (with the point count and
// NumberOfNeighbors), vertex and line cells left out beside a surface, and edges that more than
// two of the triangles kept share (non-manifold).

#include "vtkManifoldHarmonicBasis.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkManifoldHarmonicSmoothing.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using ManifoldHarmonicsTest::Check;

//------------------------------------------------------------------------------
// The warnings of one execution of `algorithm` on `input`; false if it failed.
bool Warnings(vtkAlgorithm* algorithm, vtkDataObject* input, std::string& warnings)
{
  const ManifoldHarmonicsTest::Messages messages(algorithm);
  algorithm->SetInputDataObject(input);
  algorithm->Update();
  warnings = messages->GetWarningMessage();
  std::cout << algorithm->GetClassName() << " warnings: " << warnings << std::endl;
  return !messages->GetError();
}

//------------------------------------------------------------------------------
bool Contains(const std::string& text, const std::string& part, const std::string& what)
{
  return Check(text.find(part) != std::string::npos, what + ": no '" + part + "' in the warnings");
}

//------------------------------------------------------------------------------
// The points of a sphere without any cell (a PLY whose reader dropped its faces): solved as a
// point cloud, with a warning that names the point count and NumberOfNeighbors; the smoothing
// says the same.
bool TestPointsWithoutCells()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  sphere->Update();
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(sphere->GetOutput()->GetPoints());
  const std::string count = std::to_string(cloud->GetNumberOfPoints()) + " points and no cells";
  bool ok = true;
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetNumberOfHarmonics(10);
  basis->SetNumberOfNeighbors(12);
  std::string warnings;
  ok &= Check(Warnings(basis, cloud, warnings), "the basis of a point cloud failed");
  ok &= Contains(warnings, count, "basis of a point cloud");
  ok &= Contains(warnings, "point cloud (NumberOfNeighbors = 12", "basis of a point cloud");
  vtkNew<vtkManifoldHarmonicSmoothing> smoothing;
  smoothing->SetNumberOfHarmonics(10);
  ok &= Check(Warnings(smoothing, cloud, warnings), "the smoothing of a point cloud failed");
  ok &= Contains(warnings, count, "smoothing of a point cloud");
  ok &= Contains(warnings,
    "NumberOfNeighbors = " + std::to_string(vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_NEIGHBORS),
    "smoothing of a point cloud");
  // A surface is no point cloud: no such warning.
  ok &= Check(Warnings(basis, sphere->GetOutput(), warnings), "the basis of the sphere failed");
  ok &= Check(warnings.find("point cloud") == std::string::npos,
    "the sphere's surface warns about a point cloud");
  return ok;
}

//------------------------------------------------------------------------------
// 2 vertex cells and a line beside a surface: they are left out, with a warning that counts them
// (on both conversion paths: triangles as they are, and polygons that vtkTriangleFilter splits).
bool TestVerticesAndLinesLeftOut()
{
  bool ok = true;
  for (bool quads : { false, true })
  {
    // Triangles as they are (a sphere), or quadrilaterals that vtkTriangleFilter splits (a plane).
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(16);
    sphere->SetPhiResolution(12);
    vtkNew<vtkPlaneSource> plane;
    plane->SetResolution(8, 8);
    vtkPolyDataAlgorithm* source = quads ? static_cast<vtkPolyDataAlgorithm*>(plane)
                                         : static_cast<vtkPolyDataAlgorithm*>(sphere);
    source->Update();
    vtkNew<vtkPolyData> mesh;
    mesh->DeepCopy(source->GetOutput());
    vtkNew<vtkCellArray> vertices;
    vertices->InsertNextCell({ 0 });
    vertices->InsertNextCell({ 1 });
    mesh->SetVerts(vertices);
    vtkNew<vtkCellArray> lines;
    lines->InsertNextCell({ 2, 3 });
    mesh->SetLines(lines);
    vtkNew<vtkManifoldHarmonicBasis> basis;
    basis->SetNumberOfHarmonics(10);
    std::string warnings;
    const std::string what =
      quads ? "vertices and a line beside quadrilaterals" : "vertices and a line beside triangles";
    ok &= Check(Warnings(basis, mesh, warnings), what + ": the basis failed");
    ok &= Contains(warnings, "Left out 2 vertex and 1 line cells", what);
  }
  return ok;
}

//------------------------------------------------------------------------------
// Three square sheets of 4 x 4 quads (as triangles) that share one side, a "book" of three
// pages: the 4 edges of the spine have three triangles each, and the basis says so.
bool TestNonManifoldEdges()
{
  vtkNew<vtkPoints> points;
  const int n = 4;
  for (int j = 0; j <= n; ++j) // the spine, x = 0
  {
    points->InsertNextPoint(0.0, j, 0.0);
  }
  const double directions[3][3] = { { 1, 0, 0 }, { 0, 0, 1 }, { -1, 0, -1 } };
  vtkNew<vtkCellArray> triangles;
  for (const auto& d : directions)
  {
    // Point (i, j) of this page: the spine for i = 0, new points beyond.
    std::vector<std::vector<vtkIdType>> id(n + 1, std::vector<vtkIdType>(n + 1));
    for (int j = 0; j <= n; ++j)
    {
      id[0][j] = j;
      for (int i = 1; i <= n; ++i)
      {
        id[i][j] = points->InsertNextPoint(i * d[0], j, i * d[2]);
      }
    }
    for (int i = 0; i < n; ++i)
    {
      for (int j = 0; j < n; ++j)
      {
        triangles->InsertNextCell({ id[i][j], id[i + 1][j], id[i + 1][j + 1] });
        triangles->InsertNextCell({ id[i][j], id[i + 1][j + 1], id[i][j + 1] });
      }
    }
  }
  vtkNew<vtkPolyData> book;
  book->SetPoints(points);
  book->SetPolys(triangles);
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetNumberOfHarmonics(10);
  std::string warnings;
  bool ok = Check(Warnings(basis, book, warnings), "the basis of a book of three pages failed");
  ok &= Contains(warnings, std::to_string(n) + " edges are shared by more than two triangles",
    "a book of three pages");
  return ok;
}

//------------------------------------------------------------------------------
// A sphere with one more triangle on an edge (a, b) of it, whose third point is the midpoint of
// a and b: zero area, left out with its own warning, so the edge has two triangles, as on the
// sphere alone, and no non-manifold edge is reported.
bool TestDegenerateTriangleOnAnEdge()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(12);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION); // the midpoint on the chord
  sphere->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->DeepCopy(sphere->GetOutput());
  vtkIdType count = 0;
  const vtkIdType* ids = nullptr;
  mesh->GetPolys()->GetCellAtId(mesh->GetNumberOfCells() / 2, count, ids);
  const vtkIdType a = ids[0];
  const vtkIdType b = ids[1];
  double pa[3], pb[3];
  mesh->GetPoint(a, pa);
  mesh->GetPoint(b, pb);
  const vtkIdType middle = mesh->GetPoints()->InsertNextPoint(
    0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2]));
  mesh->GetPolys()->InsertNextCell({ a, b, middle });
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetNumberOfHarmonics(10);
  std::string warnings;
  const std::string what = "a zero-area triangle on an edge of a sphere";
  bool ok = Check(Warnings(basis, mesh, warnings), what + ": the basis failed");
  ok &= Contains(warnings, "Left out 1 degenerate (zero-area) triangles", what);
  ok &= Check(
    warnings.find("non-manifold") == std::string::npos, what + ": an edge reported non-manifold");
  return ok;
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestInputInterpretation(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "PointsWithoutCells", TestPointsWithoutCells },
      { "VerticesAndLinesLeftOut", TestVerticesAndLinesLeftOut },
      { "NonManifoldEdges", TestNonManifoldEdges },
      { "DegenerateTriangleOnAnEdge", TestDegenerateTriangleOnAnEdge },
    });
}
