// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// One polygon rule (ToCoreMesh): quadrilaterals and polygons are split alike whatever holds them
// and whichever filter reads them. On a grid of sheared quadrilaterals (parallelograms, whose
// two diagonals differ in length, so that the split matters):
// - the basis of the quadrilaterals as vtkPolyData and as vtkUnstructuredGrid cells is the same;
// - the spectral filter's Nyquist frequency on the quadrilaterals is that of the triangles
//   vtkTriangleFilter makes of them (the triangles the basis solved on).
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSpectralFilter.h"
#include "vtkTriangleFilter.h"
#include "vtkUnstructuredGrid.h"

#include "ManifoldHarmonicsTestUtilities.h"

#include <functional>
#include <string>

namespace
{
using ManifoldHarmonicsTest::Check;

//------------------------------------------------------------------------------
// An n by n grid of parallelograms (sheared by half a cell per row), as quadrilaterals.
vtkSmartPointer<vtkPolyData> ShearedQuads(int n)
{
  vtkNew<vtkPoints> points;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      points->InsertNextPoint(i + 0.5 * j, j, 0.0);
    }
  }
  vtkNew<vtkCellArray> quads;
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const vtkIdType a = j * (n + 1) + i;
      const vtkIdType quad[4] = { a, a + 1, a + n + 2, a + n + 1 };
      quads->InsertNextCell(4, quad);
    }
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(quads);
  return mesh;
}

//------------------------------------------------------------------------------
// The eigenvalues of the basis of `mesh`.
vtkSmartPointer<vtkDataArray> Eigenvalues(vtkPointSet* mesh)
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(mesh);
  basis->SetNumberOfHarmonics(20);
  basis->Update();
  return basis->GetOutput()->GetFieldData()->GetArray(
    vtkManifoldHarmonicBasis::EigenvaluesArrayName());
}

//------------------------------------------------------------------------------
bool SameSplitInEveryPointSet()
{
  vtkSmartPointer<vtkPolyData> quads = ShearedQuads(10);
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(quads->GetPoints());
  grid->SetCells(VTK_QUAD, quads->GetPolys());
  const double difference =
    ManifoldHarmonicsTest::RelativeDifference(Eigenvalues(grid), Eigenvalues(quads));
  std::cout << "quadrilaterals as an unstructured grid vs as polygons: " << difference << std::endl;
  return Check(difference < 1e-12,
    "the quadrilaterals of an unstructured grid are split as those of a vtkPolyData");
}

//------------------------------------------------------------------------------
// The Nyquist frequency the spectral filter finds on `mesh` (with its own basis).
double FilterNyquist(vtkPolyData* mesh)
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(mesh);
  basis->SetNumberOfHarmonics(20);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputConnection(basis->GetOutputPort());
  vtkNew<vtkSpectralFilter> filter;
  filter->SetInputConnection(transform->GetOutputPort());
  filter->Update();
  return filter->GetNyquistFrequency();
}

//------------------------------------------------------------------------------
bool NyquistOfTheSolvedTriangles()
{
  vtkSmartPointer<vtkPolyData> quads = ShearedQuads(10);
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(quads);
  triangulate->Update();
  const double ofQuads = FilterNyquist(quads);
  const double ofTriangles = FilterNyquist(triangulate->GetOutput());
  std::cout << "Nyquist frequency of the quadrilaterals " << ofQuads << ", of their triangles "
            << ofTriangles << std::endl;
  return Check(std::abs(ofQuads - ofTriangles) <= 1e-14 * ofTriangles,
    "the filter's Nyquist frequency is that of the triangles the basis solved on");
}

} // anonymous namespace

//------------------------------------------------------------------------------
int TestPolygonRule(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "SameSplitInEveryPointSet", SameSplitInEveryPointSet },
      { "NyquistOfTheSolvedTriangles", NyquistOfTheSolvedTriangles },
    });
}
