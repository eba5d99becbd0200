// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The ghost rules of the filters (vtkManifoldHarmonicsGhosts.h) in a serial run, where a piece
// with ghost cells is modelled by a sphere plus a layer of ghost copies:
// - ghost cells (DUPLICATECELL, HIDDENCELL) are left out: the basis, the Nyquist frequency of the
//   spectral filter, the filtered points and ShapeDNA equal those of the sphere alone, while a
//   cell flagged EXTERIORCELL (a real cell on the boundary) still counts;
// - a point flagged DUPLICATEPOINT counts zero times in the transform: its coefficients equal
//   the sum over the other points, computed here independently.
// The distributed case: Testing/ParaView/TestParallelGhostCells.py.in.

#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkSpectralDescriptors.h"
#include "vtkSpectralFilter.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>

namespace
{
using ManifoldHarmonicsTest::Check;

// Whole clusters of the sphere's eigenvalues (l <= 3), whose subspaces are well defined.
constexpr int Harmonics = 16;

//------------------------------------------------------------------------------
// A unit sphere with double points: the real cells of the piece.
vtkSmartPointer<vtkPolyData> MakeSphere()
{
  return ManifoldHarmonicsTest::UnitSphere(20, 14);
}

//------------------------------------------------------------------------------
// The sphere as a piece of a larger surface: a vertex cell first (so that the ids of the
// polygons start at 1), the sphere's triangles (one flagged EXTERIORCELL), then ghost copies of
// its first 30 triangles on copies of their points (DUPLICATECELL, the points DUPLICATEPOINT),
// and a triangle across the sphere flagged HIDDENCELL. Unflagged, the copies would make a second
// component and the hidden triangle a fold.
vtkSmartPointer<vtkPolyData> MakePiece(vtkPolyData* sphere)
{
  const vtkIdType n = sphere->GetNumberOfPoints();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->DeepCopy(sphere->GetPoints());
  vtkNew<vtkUnsignedCharArray> pointGhosts;
  pointGhosts->SetName(vtkDataSetAttributes::GhostArrayName());
  pointGhosts->SetNumberOfTuples(n);
  pointGhosts->FillValue(0);
  vtkNew<vtkUnsignedCharArray> cellGhosts;
  cellGhosts->SetName(vtkDataSetAttributes::GhostArrayName());

  vtkNew<vtkCellArray> verts;
  const vtkIdType vertex = 0;
  verts->InsertNextCell(1, &vertex);
  cellGhosts->InsertNextValue(0);
  vtkNew<vtkCellArray> polys;
  polys->DeepCopy(sphere->GetPolys());
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    cellGhosts->InsertNextValue(c == 5 ? vtkDataSetAttributes::EXTERIORCELL : 0);
  }
  for (vtkIdType c = 0; c < 30; ++c)
  {
    vtkNew<vtkIdList> ids;
    sphere->GetCellPoints(c, ids);
    vtkIdType copies[3];
    for (int k = 0; k < 3; ++k)
    {
      copies[k] = points->InsertNextPoint(sphere->GetPoint(ids->GetId(k)));
      pointGhosts->InsertNextValue(vtkDataSetAttributes::DUPLICATEPOINT);
    }
    polys->InsertNextCell(3, copies);
    cellGhosts->InsertNextValue(vtkDataSetAttributes::DUPLICATECELL);
  }
  const vtkIdType across[3] = { 0, n / 2, n - 1 };
  polys->InsertNextCell(3, across);
  cellGhosts->InsertNextValue(vtkDataSetAttributes::HIDDENCELL);

  auto piece = vtkSmartPointer<vtkPolyData>::New();
  piece->SetPoints(points);
  piece->SetVerts(verts);
  piece->SetPolys(polys);
  piece->GetPointData()->AddArray(pointGhosts);
  piece->GetCellData()->AddArray(cellGhosts);
  return piece;
}

//------------------------------------------------------------------------------
// Basis, transform, low-pass filter and descriptors of one mesh.
struct Pipeline
{
  vtkNew<vtkManifoldHarmonicBasis> Basis;
  vtkNew<vtkManifoldHarmonicTransform> Transform;
  vtkNew<vtkSpectralFilter> Filter;
  vtkNew<vtkSpectralDescriptors> Descriptors;

  explicit Pipeline(vtkPolyData* mesh)
  {
    this->Basis->SetInputData(mesh);
    this->Basis->SetNumberOfHarmonics(Harmonics);
    this->Transform->SetInputConnection(this->Basis->GetOutputPort());
    this->Filter->SetInputConnection(this->Transform->GetOutputPort());
    this->Filter->SetCutoffUnitsToAbsoluteFrequency();
    this->Filter->SetCutoff(3.0);
    this->Descriptors->SetInputConnection(this->Basis->GetOutputPort());
    this->Filter->Update();
    this->Descriptors->Update();
  }

  vtkDataArray* Eigenvalues()
  {
    return this->Basis->GetOutput()->GetFieldData()->GetArray(
      vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  }
};

//------------------------------------------------------------------------------
// max_i |a_i - b_i| / max_i |b_i| over the first `count` tuples of two arrays; infinite when
// one is missing or shorter.
double Difference(vtkAbstractArray* first, vtkAbstractArray* second, vtkIdType count)
{
  vtkDataArray* a = vtkArrayDownCast<vtkDataArray>(first);
  vtkDataArray* b = vtkArrayDownCast<vtkDataArray>(second);
  if (!a || !b || a->GetNumberOfTuples() < count || b->GetNumberOfTuples() < count ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents())
  {
    return std::numeric_limits<double>::infinity();
  }
  double difference = 0.0;
  double scale = 0.0;
  for (vtkIdType i = 0; i < count; ++i)
  {
    for (int c = 0; c < b->GetNumberOfComponents(); ++c)
    {
      difference = std::max(difference, std::abs(a->GetComponent(i, c) - b->GetComponent(i, c)));
      scale = std::max(scale, std::abs(b->GetComponent(i, c)));
    }
  }
  return difference / std::max(scale, 1e-300);
}

//------------------------------------------------------------------------------
bool TestGhostCellsLeftOut(vtkPolyData* sphere)
{
  Pipeline alone(sphere);
  Pipeline piece(MakePiece(sphere));
  const vtkIdType n = sphere->GetNumberOfPoints();
  const double eigenvalues = Difference(piece.Eigenvalues(), alone.Eigenvalues(), Harmonics);
  const double nyquist =
    std::abs(piece.Filter->GetNyquistFrequency() - alone.Filter->GetNyquistFrequency()) /
    alone.Filter->GetNyquistFrequency();
  const double filtered = Difference(piece.Filter->GetOutput()->GetPoints()->GetData(),
    alone.Filter->GetOutput()->GetPoints()->GetData(),
    n);
  const char* scaled = vtkSpectralDescriptors::ScaledEigenvalueColumnName();
  const double shapeDNA =
    Difference(piece.Descriptors->GetShapeDNAOutput()->GetColumnByName(scaled),
      alone.Descriptors->GetShapeDNAOutput()->GetColumnByName(scaled),
      Harmonics);
  std::cout << "piece with ghost cells vs the sphere alone: eigenvalues " << eigenvalues
            << ", Nyquist frequency " << nyquist << ", filtered points " << filtered
            << ", ShapeDNA " << shapeDNA << std::endl;
  bool ok = Check(eigenvalues < 1e-9, "ghost cells change the eigenvalues");
  ok &= Check(nyquist < 1e-12, "ghost cells change the Nyquist frequency");
  ok &= Check(filtered < 1e-9, "ghost cells change the filtered points");
  ok &= Check(shapeDNA < 1e-9, "ghost cells change ShapeDNA");
  vtkPolyData* output = piece.Filter->GetPolyDataOutput();
  ok &= Check(output->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName()) &&
      output->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()),
    "the outputs lost the input's ghost arrays");
  return ok;
}

//------------------------------------------------------------------------------
// Points with z > 0.4 flagged DUPLICATEPOINT on a basis output: the transform's coefficients
// are sum_i m_i H_ik x_i over the other points.
bool TestDuplicatePointsCountedOnce(vtkPolyData* sphere)
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(sphere);
  basis->SetNumberOfHarmonics(Harmonics);
  basis->Update();
  vtkNew<vtkPolyData> flagged;
  flagged->ShallowCopy(basis->GetOutput());
  const vtkIdType n = flagged->GetNumberOfPoints();
  vtkNew<vtkUnsignedCharArray> ghosts;
  ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
  ghosts->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    ghosts->SetValue(i, flagged->GetPoint(i)[2] > 0.4 ? vtkDataSetAttributes::DUPLICATEPOINT : 0);
  }
  flagged->GetPointData()->AddArray(ghosts);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputData(flagged);
  transform->Update();
  vtkDataArray* coefficients = transform->GetOutput()->GetFieldData()->GetArray(
    (std::string(vtkManifoldHarmonicTransform::PointsName()) +
      vtkManifoldHarmonicTransform::CoefficientsSuffix())
      .c_str());

  vtkDataArray* H =
    flagged->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName());
  vtkDataArray* mass = flagged->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName());
  vtkNew<vtkDoubleArray> expected;
  expected->SetNumberOfComponents(3);
  expected->SetNumberOfTuples(Harmonics);
  expected->FillValue(0.0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int k = 0; ghosts->GetValue(i) == 0 && k < Harmonics; ++k)
    {
      for (int c = 0; c < 3; ++c)
      {
        expected->SetComponent(k,
          c,
          expected->GetComponent(k, c) +
            mass->GetTuple1(i) * H->GetComponent(i, k) * flagged->GetPoint(i)[c]);
      }
    }
  }
  const double difference = Difference(coefficients, expected, Harmonics);
  std::cout << "coefficients with DUPLICATEPOINT points vs the sum over the others: " << difference
            << std::endl;
  return Check(difference < 1e-12, "DUPLICATEPOINT points are not counted zero times");
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestGhostCells(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "GhostCellsLeftOut", [] { return TestGhostCellsLeftOut(MakeSphere()); } },
      { "DuplicatePointsCountedOnce", [] { return TestDuplicatePointsCountedOnce(MakeSphere()); } },
    });
}
