// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Volumes and unstructured grids through the filters: the basis, the transform, the spectral
// filter, the smoothing and the descriptors take any vtkPointSet and give its type; tetrahedra
// give the harmonics of the solid (analytic eigenvalues of the cube), hexahedra, voxels, wedges
// and pyramids are split into conforming tetrahedra (with a warning), Dirichlet boundary points
// pass through the filters unchanged, a mix of 2-D and 3-D cells and unsupported cells are
// errors; point clouds (no cells, or vertex cells) get the point-cloud Laplacian's harmonics.
#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCellType.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataArraySelection.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicSmoothing.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkMath.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSpectralDescriptors.h"
#include "vtkSpectralFilter.h"
#include "vtkTable.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <string>
#include <vector>

namespace
{
using ManifoldHarmonicsTest::Check;
const double Pi = 3.14159265358979323846;

//------------------------------------------------------------------------------
// The unit cube of n^3 hexahedra (or voxels) as an unstructured grid, its points numbered in a
// shuffled order (so that the split of each cell depends on ids that differ from cell to cell).
vtkSmartPointer<vtkUnstructuredGrid> HexahedralCube(int n, int type)
{
  const int side = n + 1;
  std::vector<vtkIdType> order(static_cast<std::size_t>(side * side * side));
  std::iota(order.begin(), order.end(), 0);
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(5);
  for (std::size_t i = order.size() - 1; i > 0; --i)
  {
    random->Next();
    std::swap(order[i], order[static_cast<std::size_t>(random->GetValue() * (i + 1)) % (i + 1)]);
  }
  const auto id = [&order, side](int i, int j, int k)
  { return order[static_cast<std::size_t>((k * side + j) * side + i)]; };
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(side * side * side);
  for (int k = 0; k < side; ++k)
  {
    for (int j = 0; j < side; ++j)
    {
      for (int i = 0; i < side; ++i)
      {
        points->SetPoint(id(i, j, k), double(i) / n, double(j) / n, double(k) / n);
      }
    }
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const vtkIdType hexahedron[8] = { id(i, j, k),
          id(i + 1, j, k),
          id(i + 1, j + 1, k),
          id(i, j + 1, k),
          id(i, j, k + 1),
          id(i + 1, j, k + 1),
          id(i + 1, j + 1, k + 1),
          id(i, j + 1, k + 1) };
        const vtkIdType voxel[8] = { hexahedron[0],
          hexahedron[1],
          hexahedron[3],
          hexahedron[2],
          hexahedron[4],
          hexahedron[5],
          hexahedron[7],
          hexahedron[6] };
        grid->InsertNextCell(type, 8, type == VTK_VOXEL ? voxel : hexahedron);
      }
    }
  }
  return grid;
}

//------------------------------------------------------------------------------
// The cube of n^3 hexahedra, each split into Kuhn's six tetrahedra (every other one with two
// corners swapped: both orientations), with a smooth scalar field "Field".
vtkSmartPointer<vtkUnstructuredGrid> TetrahedralCube(int n)
{
  vtkSmartPointer<vtkUnstructuredGrid> hexahedra = HexahedralCube(n, VTK_HEXAHEDRON);
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(hexahedra->GetPoints());
  // Kuhn's split of a hexahedron (0..7 in VTK order): paths from corner 0 to corner 6.
  const int paths[6][4] = {
    { 0, 1, 2, 6 }, { 0, 1, 5, 6 }, { 0, 3, 2, 6 }, { 0, 3, 7, 6 }, { 0, 4, 5, 6 }, { 0, 4, 7, 6 }
  };
  vtkNew<vtkIdList> corners;
  for (vtkIdType c = 0; c < hexahedra->GetNumberOfCells(); ++c)
  {
    hexahedra->GetCellPoints(c, corners);
    for (int t = 0; t < 6; ++t)
    {
      vtkIdType tet[4];
      for (int v = 0; v < 4; ++v)
      {
        tet[v] = corners->GetId(paths[t][v]);
      }
      if (t % 2)
      {
        std::swap(tet[0], tet[1]);
      }
      grid->InsertNextCell(VTK_TETRA, 4, tet);
    }
  }
  vtkNew<vtkDoubleArray> field;
  field->SetName("Field");
  field->SetNumberOfTuples(grid->GetNumberOfPoints());
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    double p[3];
    grid->GetPoint(i, p);
    field->SetValue(i, std::cos(Pi * p[0]) + p[1] * p[2] + (i % 7) * 0.01);
  }
  grid->GetPointData()->AddArray(field);
  return grid;
}

//------------------------------------------------------------------------------
// pi^2 (a^2 + b^2 + c^2), a, b, c >= first, the `count` smallest.
std::vector<double> CubeSpectrum(int first, int count)
{
  std::vector<double> lambda;
  for (int a = first; a < first + 6; ++a)
  {
    for (int b = first; b < first + 6; ++b)
    {
      for (int c = first; c < first + 6; ++c)
      {
        lambda.push_back(Pi * Pi * (a * a + b * b + c * c));
      }
    }
  }
  std::sort(lambda.begin(), lambda.end());
  lambda.resize(static_cast<std::size_t>(count));
  return lambda;
}

//------------------------------------------------------------------------------
// The largest relative difference of the output eigenvalues from the analytic ones (the zero
// eigenvalue against the first non-zero one).
double SpectrumError(vtkDataSet* output, const std::vector<double>& exact)
{
  vtkDataArray* lambda =
    output->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  if (!lambda || lambda->GetNumberOfTuples() != static_cast<vtkIdType>(exact.size()))
  {
    return 1.0;
  }
  double worst = 0.0;
  for (std::size_t k = 0; k < exact.size(); ++k)
  {
    const double scale = exact[k] > 0.0 ? exact[k] : exact[1];
    worst =
      std::max(worst, std::abs(lambda->GetTuple1(static_cast<vtkIdType>(k)) - exact[k]) / scale);
  }
  return worst;
}

//------------------------------------------------------------------------------
// Tetrahedra in an unstructured grid: the output is an unstructured grid with the harmonics of
// the solid (analytic eigenvalues), Neumann and Dirichlet; through the transform and the
// spectral filter, Dirichlet boundary points keep their values and positions.
bool TestTetrahedra()
{
  bool ok = true;
  vtkSmartPointer<vtkUnstructuredGrid> cube = TetrahedralCube(10);
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(cube);
  basis->SetNumberOfHarmonics(8);
  basis->Update();
  vtkUnstructuredGrid* neumann = vtkUnstructuredGrid::SafeDownCast(basis->GetOutputDataObject(0));
  ok &= Check(neumann != nullptr, "an unstructured grid in gives an unstructured grid out");
  if (!neumann)
  {
    return false;
  }
  double error = SpectrumError(neumann, CubeSpectrum(0, 8));
  std::cout << "Neumann cube of tetrahedra (11^3 points): eigenvalues within " << error
            << std::endl;
  ok &= Check(error < 0.03, "Neumann eigenvalues of the cube pi^2 (a^2 + b^2 + c^2)");

  basis->SetBoundaryConditionToDirichlet();
  basis->Update();
  vtkDataSet* dirichlet = vtkDataSet::SafeDownCast(basis->GetOutputDataObject(0));
  error = SpectrumError(dirichlet, CubeSpectrum(1, 8));
  std::cout << "Dirichlet cube: eigenvalues within " << error << std::endl;
  // 11^3 points: the 8th eigenvalue, 9 pi^2, has about 6% error at this size (second order:
  // Testing/Core/TestVolumes.cxx reaches 2% at 21^3 points).
  ok &= Check(error < 0.08, "Dirichlet eigenvalues of the cube, a, b, c >= 1");
  vtkDataArray* mass =
    dirichlet->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName());
  vtkIdType massless = 0;
  for (vtkIdType i = 0; i < mass->GetNumberOfTuples(); ++i)
  {
    massless += mass->GetTuple1(i) == 0.0 ? 1 : 0;
  }
  ok &= Check(massless == 11 * 11 * 11 - 9 * 9 * 9,
    "Dirichlet: the boundary points have zero mass (" + std::to_string(massless) + ")");

  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputConnection(basis->GetOutputPort());
  transform->GetPointDataArraySelection()->EnableArray("Field");
  vtkNew<vtkSpectralFilter> filter;
  filter->SetInputConnection(transform->GetOutputPort());
  filter->SetFilterKindToLowPass();
  filter->SetCutoffUnitsToAbsoluteFrequency();
  filter->SetCutoff(std::sqrt(CubeSpectrum(1, 4).back()));
  filter->Update();
  vtkUnstructuredGrid* filtered = vtkUnstructuredGrid::SafeDownCast(filter->GetOutputDataObject(0));
  ok &= Check(filtered && vtkUnstructuredGrid::SafeDownCast(transform->GetOutputDataObject(0)),
    "the transform and the filter give unstructured grids");
  ok &= Check(vtkTable::SafeDownCast(filter->GetOutputDataObject(1)) != nullptr,
    "the spectrum stays a table");
  if (!filtered)
  {
    return false;
  }
  vtkDataArray* in = cube->GetPointData()->GetArray("Field");
  vtkDataArray* out = filtered->GetPointData()->GetArray(
    (std::string("Field") + vtkSpectralFilter::FilteredSuffix()).c_str());
  double boundaryChange = 0.0;
  double interiorChange = 0.0;
  for (vtkIdType i = 0; out && i < in->GetNumberOfTuples(); ++i)
  {
    double before[3];
    double after[3];
    cube->GetPoint(i, before);
    filtered->GetPoint(i, after);
    const double change = std::abs(out->GetTuple1(i) - in->GetTuple1(i)) +
      std::abs(after[0] - before[0]) + std::abs(after[1] - before[1]) +
      std::abs(after[2] - before[2]);
    (mass->GetTuple1(i) == 0.0 ? boundaryChange : interiorChange) += change;
  }
  ok &= Check(out != nullptr && boundaryChange == 0.0 && interiorChange > 0.0,
    "Dirichlet boundary points pass through the filter unchanged, interior ones move (" +
      std::to_string(boundaryChange) + ", " + std::to_string(interiorChange) + ")");

  vtkNew<vtkSpectralDescriptors> descriptors;
  descriptors->SetInputConnection(basis->GetOutputPort());
  descriptors->Update();
  ok &= Check(vtkUnstructuredGrid::SafeDownCast(descriptors->GetOutputDataObject(0)) != nullptr,
    "the descriptors give an unstructured grid");
  vtkTable* dna = descriptors->GetShapeDNAOutput();
  vtkDataArray* scaled =
    dna ? vtkArrayDownCast<vtkDataArray>(dna->GetColumnByName("ScaledEigenvalue")) : nullptr;
  vtkDataArray* lambda =
    dirichlet->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  double measure = 0.0;
  for (vtkIdType i = 0; i < mass->GetNumberOfTuples(); ++i)
  {
    measure += mass->GetTuple1(i);
  }
  ok &= Check(scaled &&
      std::abs(scaled->GetTuple1(0) - lambda->GetTuple1(0) * std::cbrt(measure * measure)) <=
        1e-12 * scaled->GetTuple1(0),
    "ShapeDNA of a volume scales by V^(2/3)");
  return ok;
}

//------------------------------------------------------------------------------
// Hexahedra and voxels are split into tetrahedra that conform (no interior face is taken for a
// boundary face: the Dirichlet boundary is the cube's surface), with a warning.
bool TestSplitCells()
{
  bool ok = true;
  for (int type : { VTK_HEXAHEDRON, VTK_VOXEL })
  {
    const std::string name = type == VTK_VOXEL ? "voxels" : "hexahedra";
    vtkNew<vtkManifoldHarmonicBasis> basis;
    vtkNew<vtkTest::ErrorObserver> warnings;
    basis->AddObserver(vtkCommand::WarningEvent, warnings);
    basis->SetInputData(HexahedralCube(6, type));
    basis->SetNumberOfHarmonics(4);
    basis->SetBoundaryConditionToDirichlet();
    basis->Update();
    ok &= Check(
      warnings->CheckWarningMessage("Split 216 hexahedra") == 0, name + ": the split is announced");
    vtkDataSet* output = vtkDataSet::SafeDownCast(basis->GetOutputDataObject(0));
    vtkDataArray* mass =
      output->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName());
    vtkIdType interior = 0;
    for (vtkIdType i = 0; mass && i < mass->GetNumberOfTuples(); ++i)
    {
      interior += mass->GetTuple1(i) > 0.0 ? 1 : 0;
    }
    ok &= Check(interior == 5 * 5 * 5,
      name + ": the tetrahedra conform (5^3 interior points, got " + std::to_string(interior) +
        ")");
    const double error = SpectrumError(output, CubeSpectrum(1, 4));
    std::cout << name << ": Dirichlet eigenvalues within " << error << std::endl;
    ok &= Check(error < 0.15, name + ": Dirichlet eigenvalues of the cube (coarse, 7^3 points)");
  }

  // One wedge and one pyramid: the split keeps their volumes (the sum of the lumped mass).
  vtkNew<vtkPoints> points;
  const double corners[11][3] = { { 0, 0, 0 },
    { 2, 0, 0 },
    { 0, 1, 0 },
    { 0, 0, 3 },
    { 2, 0, 3 },
    { 0, 1, 3 },
    { 5, 0, 0 },
    { 7, 0, 0 },
    { 7, 2, 0 },
    { 5, 2, 0 },
    { 6, 1, 1.5 } };
  for (const auto& p : corners)
  {
    points->InsertNextPoint(p);
  }
  for (int type : { VTK_WEDGE, VTK_PYRAMID })
  {
    vtkNew<vtkUnstructuredGrid> cell;
    cell->SetPoints(points);
    const vtkIdType wedge[6] = { 0, 1, 2, 3, 4, 5 };
    const vtkIdType pyramid[5] = { 9, 6, 7, 8, 10 };
    if (type == VTK_WEDGE)
    {
      cell->InsertNextCell(VTK_WEDGE, 6, wedge);
    }
    else
    {
      cell->InsertNextCell(VTK_PYRAMID, 5, pyramid);
    }
    vtkNew<vtkManifoldHarmonicBasis> basis;
    vtkNew<vtkTest::ErrorObserver> warnings;
    basis->AddObserver(vtkCommand::WarningEvent, warnings);
    basis->SetInputData(cell);
    basis->SetNumberOfHarmonics(2);
    basis->Update();
    vtkDataArray* mass = vtkDataSet::SafeDownCast(basis->GetOutputDataObject(0))
                           ->GetPointData()
                           ->GetArray(vtkManifoldHarmonicBasis::MassArrayName());
    double volume = 0.0;
    for (vtkIdType i = 0; mass && i < mass->GetNumberOfTuples(); ++i)
    {
      volume += mass->GetTuple1(i);
    }
    // The wedge: a right triangle of legs 2 and 1 swept by 3; the pyramid: base 2 x 2, height 1.5.
    const double expected = type == VTK_WEDGE ? 0.5 * 2 * 1 * 3 : 2.0 * 2.0 * 1.5 / 3.0;
    ok &= Check(std::abs(volume - expected) < 1e-12,
      std::string(type == VTK_WEDGE ? "wedge" : "pyramid") + ": the tetrahedra fill its volume (" +
        std::to_string(volume) + ")");
  }
  return ok;
}

//------------------------------------------------------------------------------
// Errors: 2-D and 3-D cells mixed (the counts named), an unsupported cell, a point cloud.
bool TestErrors()
{
  bool ok = true;
  vtkSmartPointer<vtkUnstructuredGrid> mixed = TetrahedralCube(2);
  const vtkIdType triangle[3] = { 0, 1, 2 };
  mixed->InsertNextCell(VTK_TRIANGLE, 3, triangle);
  const auto expectError = [](vtkDataObject* input, const std::string& text)
  {
    vtkNew<vtkManifoldHarmonicBasis> basis;
    const ManifoldHarmonicsTest::Messages errors(basis);
    basis->SetInputData(input);
    basis->Update();
    // The message without its "ERROR: In file, line" prefix (which would fail the test).
    const std::string message = errors->GetErrorMessage();
    std::cout << "Expected error:" << message.substr(message.find('\n') + 1) << std::endl;
    return errors->CheckErrorMessage(text) == 0;
  };
  ok &= Check(expectError(mixed, "The input mixes 1 2-D cells (triangles, polygons) and 48 3-D"),
    "a mix of 2-D and 3-D cells is an error naming the counts");

  vtkNew<vtkUnstructuredGrid> quadratic;
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 10; ++i)
  {
    points->InsertNextPoint(i % 2, (i / 2) % 2, i / 4);
  }
  quadratic->SetPoints(points);
  const vtkIdType ids[10] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9 };
  quadratic->InsertNextCell(VTK_QUADRATIC_TETRA, 10, ids);
  ok &=
    Check(expectError(quadratic, "vtkQuadraticTetra"), "a quadratic cell is an error naming it");
  return ok;
}

//------------------------------------------------------------------------------
// Point clouds: the unit sphere's spectrum from points alone (in a vtkPolyData without cells
// and in an unstructured grid of vertex cells, alike), and noisy points low-passed back towards
// the sphere by the filter and by the smoothing, which keep the input's type.
bool TestPointClouds()
{
  const int n = 4000;
  const double golden = vtkMath::Pi() * (3.0 - std::sqrt(5.0));
  vtkNew<vtkPoints> clean;
  vtkNew<vtkPoints> noisy;
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(5);
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double r = std::sqrt(1.0 - z * z);
    const double p[3] = { r * std::cos(golden * i), r * std::sin(golden * i), z };
    clean->InsertNextPoint(p);
    random->Next();
    const double scale = 1.0 + 0.02 * (2.0 * random->GetValue() - 1.0);
    noisy->InsertNextPoint(scale * p[0], scale * p[1], scale * p[2]);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(clean);
  vtkNew<vtkUnstructuredGrid> vertices;
  vertices->SetPoints(clean);
  for (vtkIdType i = 0; i < n; ++i)
  {
    vertices->InsertNextCell(VTK_VERTEX, 1, &i);
  }
  std::vector<std::vector<double>> spectra;
  bool ok = true;
  for (vtkPointSet* input :
    { static_cast<vtkPointSet*>(cloud), static_cast<vtkPointSet*>(vertices) })
  {
    vtkNew<vtkManifoldHarmonicBasis> basis;
    basis->SetInputData(input);
    basis->SetNumberOfHarmonics(16);
    basis->Update();
    vtkDataArray* lambda = basis->GetOutput()->GetFieldData()->GetArray(
      vtkManifoldHarmonicBasis::EigenvaluesArrayName());
    ok &= Check(lambda && lambda->GetNumberOfTuples() == 16 &&
        std::string(basis->GetOutput()->GetClassName()) == input->GetClassName(),
      std::string("a ") + input->GetClassName() + " cloud: 16 eigenvalues, the input's type");
    if (!lambda || lambda->GetNumberOfTuples() != 16)
    {
      return false;
    }
    std::vector<double> values;
    double worst = 0.0;
    for (int l = 1; l <= 3; ++l)
    {
      for (int k = l * l; k < (l + 1) * (l + 1); ++k)
      {
        worst = std::max(worst, std::abs(lambda->GetTuple1(k) - l * (l + 1.0)) / (l * (l + 1.0)));
      }
    }
    for (int k = 0; k < 16; ++k)
    {
      values.push_back(lambda->GetTuple1(k));
    }
    spectra.push_back(values);
    std::cout << input->GetClassName()
              << " cloud: worst |lambda - l(l+1)| / l(l+1), l <= 3: " << worst << std::endl;
    ok &= Check(worst < 0.03, "the sphere's eigenvalues l(l+1) within 3%");
  }
  double spread = 0.0;
  for (std::size_t k = 1; k < spectra[0].size(); ++k)
  {
    spread = std::max(spread, std::abs(spectra[0][k] - spectra[1][k]) / spectra[0][k]);
  }
  // The same solve up to rounding (1e-15 relative between two runs in one process).
  ok &= Check(spectra[0][0] == 0.0 && spectra[1][0] == 0.0 && spread <= 1e-12,
    "vertex cells or none: the same spectrum");

  // Radial RMS error of the noisy cloud, then low-passed (cutoff omega = 4: l <= 3).
  const auto radialError = [](vtkPoints* points)
  {
    double sum = 0.0;
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    {
      double p[3];
      points->GetPoint(i, p);
      sum += std::pow(vtkMath::Norm(p) - 1.0, 2);
    }
    return std::sqrt(sum / points->GetNumberOfPoints());
  };
  vtkNew<vtkPolyData> noisyCloud;
  noisyCloud->SetPoints(noisy);
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(noisyCloud);
  basis->SetNumberOfHarmonics(100);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputConnection(basis->GetOutputPort());
  vtkNew<vtkSpectralFilter> filter;
  filter->SetInputConnection(transform->GetOutputPort());
  filter->SetFilterKindToLowPass();
  filter->SetCutoffUnitsToAbsoluteFrequency();
  filter->SetCutoff(4.0);
  filter->Update();
  const double before = radialError(noisy);
  const double after = radialError(filter->GetPolyDataOutput()->GetPoints());
  std::cout << "noisy cloud: radial RMS " << before << " -> " << after << " (filter, Nyquist "
            << filter->GetNyquistFrequency() << ")" << std::endl;
  ok &= Check(after < 0.2 * before && filter->GetNyquistFrequency() > 10.0,
    "the low-passed cloud is at least 5 times closer to the sphere, with a Nyquist frequency");
  vtkNew<vtkManifoldHarmonicSmoothing> smoothing;
  smoothing->SetInputData(noisyCloud);
  smoothing->SetNumberOfHarmonics(100);
  smoothing->Update();
  const double smoothed = radialError(smoothing->GetPolyDataOutput()->GetPoints());
  std::cout << "noisy cloud: radial RMS " << before << " -> " << smoothed << " (smoothing)"
            << std::endl;
  ok &= Check(smoothed < 0.5 * before, "the smoothing of a cloud brings it closer to the sphere");
  return ok;
}

//------------------------------------------------------------------------------
// The smoothing of an unstructured grid gives an unstructured grid; with Dirichlet conditions
// its boundary stays in place.
bool TestSmoothing()
{
  vtkSmartPointer<vtkUnstructuredGrid> cube = TetrahedralCube(6);
  vtkNew<vtkMinimalStandardRandomSequence> random;
  for (vtkIdType i = 0; i < cube->GetNumberOfPoints(); ++i)
  {
    double p[3];
    cube->GetPoint(i, p);
    for (double& x : p)
    {
      random->Next();
      x += 0.01 * (random->GetValue() - 0.5);
    }
    cube->GetPoints()->SetPoint(i, p);
  }
  vtkNew<vtkManifoldHarmonicSmoothing> smoothing;
  smoothing->SetInputData(cube);
  smoothing->SetNumberOfHarmonics(20);
  smoothing->SetBoundaryCondition(vtkManifoldHarmonicBasis::DIRICHLET);
  smoothing->Update();
  vtkUnstructuredGrid* output =
    vtkUnstructuredGrid::SafeDownCast(smoothing->GetOutputDataObject(0));
  bool ok = Check(output && output->GetNumberOfPoints() == cube->GetNumberOfPoints() &&
      output->GetNumberOfCells() == cube->GetNumberOfCells(),
    "the smoothing gives the unstructured grid");
  if (!output)
  {
    return false;
  }
  int fixed = 0;
  int moved = 0;
  for (vtkIdType i = 0; i < cube->GetNumberOfPoints(); ++i)
  {
    double before[3];
    double after[3];
    cube->GetPoint(i, before);
    output->GetPoint(i, after);
    const bool same = before[0] == after[0] && before[1] == after[1] && before[2] == after[2];
    (same ? fixed : moved) += 1;
  }
  return ok &
    Check(fixed == 7 * 7 * 7 - 5 * 5 * 5 && moved == 5 * 5 * 5,
      "Dirichlet smoothing keeps the boundary points, moves the interior ones (" +
        std::to_string(fixed) + " fixed, " + std::to_string(moved) + " moved)");
}
} // anonymous namespace

int TestVolumeHarmonics(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "Tetrahedra", TestTetrahedra },
      { "SplitCells", TestSplitCells },
      { "Errors", TestErrors },
      { "PointClouds", TestPointClouds },
      { "Smoothing", TestSmoothing },
    });
}
