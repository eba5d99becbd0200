// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Checks of vtkManifoldHarmonicBasis: output arrays, the spectrum of the unit sphere and of the
// unit square, M-orthonormality, float/double inputs, abort, triangulation, unused points, the
// float basis (BasisPrecision) and the memory guard (MemoryLimit).

#include "vtkManifoldHarmonicBasis.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr double Pi = 3.14159265358979323846;

using ManifoldHarmonicsTest::Check;
using ManifoldHarmonicsTest::Perturb;

//------------------------------------------------------------------------------
// Unit icosphere: the icosahedron with each triangle split in four `levels` times, points
// projected onto the sphere (10 * 4^levels + 2 points).
vtkSmartPointer<vtkPolyData> MakeIcosphere(int levels, int dataType)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  // clang-format off
  std::vector<std::vector<double>> xyz = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 },
    { 0, -1, t }, { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 },
    { -t, 0, -1 }, { -t, 0, 1 } };
  std::vector<std::vector<vtkIdType>> faces = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 },
    { 0, 7, 10 }, { 0, 10, 11 }, { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 },
    { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 },
    { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };
  // clang-format on
  for (int level = 0; level < levels; ++level)
  {
    std::map<std::pair<vtkIdType, vtkIdType>, vtkIdType> midpoints;
    auto midpoint = [&xyz, &midpoints](vtkIdType a, vtkIdType b)
    {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto found = midpoints.emplace(key, static_cast<vtkIdType>(xyz.size()));
      if (found.second)
      {
        xyz.push_back({ (xyz[a][0] + xyz[b][0]) / 2,
          (xyz[a][1] + xyz[b][1]) / 2,
          (xyz[a][2] + xyz[b][2]) / 2 });
      }
      return found.first->second;
    };
    std::vector<std::vector<vtkIdType>> finer;
    for (const auto& f : faces)
    {
      const vtkIdType ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]),
                      ca = midpoint(f[2], f[0]);
      finer.insert(
        finer.end(), { { f[0], ab, ca }, { f[1], bc, ab }, { f[2], ca, bc }, { ab, bc, ca } });
    }
    faces.swap(finer);
  }

  vtkNew<vtkPoints> points;
  points->SetDataType(dataType);
  for (const auto& p : xyz)
  {
    const double norm = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    points->InsertNextPoint(p[0] / norm, p[1] / norm, p[2] / norm);
  }
  Perturb(points);
  vtkNew<vtkCellArray> polys;
  for (const auto& f : faces)
  {
    polys->InsertNextCell({ f[0], f[1], f[2] });
  }
  auto sphere = vtkSmartPointer<vtkPolyData>::New();
  sphere->SetPoints(points);
  sphere->SetPolys(polys);
  return sphere;
}

//------------------------------------------------------------------------------
// Runs the filter with m harmonics and returns its output.
vtkSmartPointer<vtkPolyData> Run(vtkPolyData* input, int m, vtkTest::ErrorObserver* observer)
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetNumberOfHarmonics(m);
  basis->SetInputData(input);
  if (observer)
  {
    basis->AddObserver(vtkCommand::WarningEvent, observer);
    basis->AddObserver(vtkCommand::ErrorEvent, observer);
  }
  basis->Update();
  return basis->GetPolyDataOutput();
}

//------------------------------------------------------------------------------
vtkDoubleArray* Harmonics(vtkDataSet* output)
{
  return vtkDoubleArray::SafeDownCast(
    output->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName()));
}

//------------------------------------------------------------------------------
vtkDoubleArray* Mass(vtkDataSet* output)
{
  return vtkDoubleArray::SafeDownCast(
    output->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName()));
}

//------------------------------------------------------------------------------
vtkDoubleArray* Eigenvalues(vtkDataSet* output)
{
  return vtkDoubleArray::SafeDownCast(
    output->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName()));
}

//------------------------------------------------------------------------------
bool TestArraysAndSphereSpectrum()
{
  auto sphere = MakeIcosphere(4, VTK_DOUBLE);
  const int m = 12;
  auto output = Run(sphere, m, nullptr);
  vtkDoubleArray* H = Harmonics(output);
  vtkDoubleArray* D = Mass(output);
  vtkDoubleArray* lambda = Eigenvalues(output);
  bool ok = Check(H && D && lambda, "the three output arrays exist with type double");
  if (!ok)
  {
    return false;
  }
  const vtkIdType n = sphere->GetNumberOfPoints();
  ok &= Check(H->GetNumberOfComponents() == m && H->GetNumberOfTuples() == n, "harmonics n x m");
  ok &= Check(std::string(H->GetComponentName(0)) == "Phi_0" &&
      std::string(H->GetComponentName(m - 1)) == "Phi_11",
    "components named Phi_k");
  ok &= Check(D->GetNumberOfComponents() == 1 && D->GetNumberOfTuples() == n, "mass n x 1");
  ok &= Check(
    lambda->GetNumberOfComponents() == 1 && lambda->GetNumberOfTuples() == m, "eigenvalues m x 1");
  for (int k = 1; k < m; ++k)
  {
    ok &= Check(lambda->GetValue(k - 1) <= lambda->GetValue(k), "eigenvalues ascending");
  }
  ok &= Check(lambda->GetValue(0) == 0.0, "lambda_0 is exactly 0");
  // Unit sphere: l(l+1) with multiplicity 2l+1 (the discretization error is below 1%).
  for (int k = 1; k <= 3; ++k)
  {
    ok &= Check(std::abs(lambda->GetValue(k) - 2.0) < 0.02 * 2.0, "lambda_1..3 = 2");
  }
  for (int k = 4; k <= 8; ++k)
  {
    ok &= Check(std::abs(lambda->GetValue(k) - 6.0) < 0.02 * 6.0, "lambda_4..8 = 6");
  }
  ok &= Check(std::abs(lambda->GetValue(9) - 12.0) < 0.02 * 12.0, "lambda_9 = 12");
  double area = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    area += D->GetValue(i);
  }
  ok &= Check(std::abs(area - 4.0 * Pi) < 0.01 * 4.0 * Pi, "sum of mass = sphere area");

  // H^T D H = I, from the output arrays alone.
  double worst = 0.0;
  for (int k = 0; k < m; ++k)
  {
    for (int l = 0; l <= k; ++l)
    {
      double dot = 0.0;
      for (vtkIdType i = 0; i < n; ++i)
      {
        dot += H->GetComponent(i, k) * D->GetValue(i) * H->GetComponent(i, l);
      }
      worst = std::max(worst, std::abs(dot - (k == l ? 1.0 : 0.0)));
    }
  }
  ok &= Check(worst < 1e-10, "harmonics are orthonormal in the lumped mass");
  if (!ok)
  {
    std::cerr << "Orthonormality error " << worst << "; eigenvalues:";
    for (int k = 0; k < m; ++k)
    {
      std::cerr << ' ' << lambda->GetValue(k);
    }
    std::cerr << std::endl;
  }
  return ok;
}

//------------------------------------------------------------------------------
// Float points and the same values as doubles describe the same mesh: same eigenvalues.
bool TestFloatAndDoublePoints()
{
  auto floatSphere = MakeIcosphere(3, VTK_FLOAT);
  auto doubleSphere = vtkSmartPointer<vtkPolyData>::New();
  doubleSphere->DeepCopy(floatSphere);
  vtkNew<vtkPoints> doublePoints;
  doublePoints->SetDataTypeToDouble();
  doublePoints->DeepCopy(floatSphere->GetPoints());
  doubleSphere->SetPoints(doublePoints);
  bool ok = Check(vtkFloatArray::SafeDownCast(floatSphere->GetPoints()->GetData()) &&
      vtkDoubleArray::SafeDownCast(doubleSphere->GetPoints()->GetData()),
    "float and double inputs");

  const int m = 10;
  auto floatOutput = Run(floatSphere, m, nullptr);
  auto doubleOutput = Run(doubleSphere, m, nullptr);
  vtkDoubleArray* a = Eigenvalues(floatOutput);
  vtkDoubleArray* b = Eigenvalues(doubleOutput);
  ok &= Check(a && b, "eigenvalues for float and double points");
  for (int k = 0; ok && k < m; ++k)
  {
    ok &= Check(std::abs(a->GetValue(k) - b->GetValue(k)) < 1e-10 * (1.0 + b->GetValue(k)),
      "float and double points give the same eigenvalues");
  }
  return ok;
}

//------------------------------------------------------------------------------
// The consistent mass gives the same sphere spectrum.
bool TestConsistentMass()
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetNumberOfHarmonics(9);
  basis->SetMassMatrixToConsistent();
  basis->SetInputData(MakeIcosphere(3, VTK_DOUBLE));
  basis->Update();
  vtkDoubleArray* lambda = Eigenvalues(basis->GetOutput());
  bool ok = Check(lambda && lambda->GetNumberOfTuples() == 9, "consistent mass: eigenvalues");
  if (!ok)
  {
    return false;
  }
  ok &= Check(lambda->GetValue(0) == 0.0, "consistent mass: lambda_0 is exactly 0");
  for (int k = 1; k <= 3; ++k)
  {
    ok &= Check(std::abs(lambda->GetValue(k) - 2.0) < 0.03 * 2.0, "consistent mass: lambda = 2");
  }
  for (int k = 4; k <= 8; ++k)
  {
    ok &= Check(std::abs(lambda->GetValue(k) - 6.0) < 0.03 * 6.0, "consistent mass: lambda = 6");
  }
  return ok;
}

//------------------------------------------------------------------------------
// Sets AbortExecute on the filter once progress passes a threshold.
class AbortAt : public vtkCommand
{
public:
  static AbortAt* New() { return new AbortAt; }
  void Execute(vtkObject* caller, unsigned long, void* callData) override
  {
    const double progress = *static_cast<double*>(callData);
    if (progress >= this->Threshold)
    {
      vtkAlgorithm::SafeDownCast(caller)->AbortExecuteOn();
      ++this->Aborts;
    }
  }
  double Threshold = 0.0;
  int Aborts = 0;
};

//------------------------------------------------------------------------------
bool TestAbort()
{
  bool ok = true;
  for (double threshold : { 0.0, 0.05, 0.2 })
  {
    vtkNew<vtkManifoldHarmonicBasis> basis;
    basis->SetNumberOfHarmonics(20);
    basis->SetInputData(MakeIcosphere(4, VTK_DOUBLE));
    vtkNew<AbortAt> abort;
    abort->Threshold = threshold;
    basis->AddObserver(vtkCommand::ProgressEvent, abort);
    vtkNew<vtkTest::ErrorObserver> errors;
    basis->AddObserver(vtkCommand::ErrorEvent, errors);
    basis->Update();
    vtkPolyData* output = basis->GetPolyDataOutput();
    ok &= Check(abort->Aborts > 0, "the progress observer was called");
    ok &= Check(!errors->GetError(), "abort is not an error");
    ok &= Check(output->GetNumberOfPoints() == 0 && !Harmonics(output),
      "an aborted execution leaves the output empty");
  }
  return ok;
}

//------------------------------------------------------------------------------
// A plane source makes quads: they are triangulated with a warning. The Neumann spectrum of the
// unit square is pi^2 (a^2 + b^2): 0, pi^2, pi^2, 2 pi^2, 4 pi^2, ...
bool TestQuads()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(30, 30);
  plane->Update();
  vtkNew<vtkTest::ErrorObserver> warnings;
  auto output = Run(plane->GetOutput(), 6, warnings);
  bool ok = Check(warnings->CheckWarningMessage("Triangulating") == 0, "warned about quads");
  vtkDoubleArray* lambda = output ? Eigenvalues(output) : nullptr;
  ok &= Check(lambda && lambda->GetNumberOfTuples() == 6, "quads give eigenvalues");
  if (!lambda)
  {
    return false;
  }
  const double pi2 = Pi * Pi;
  ok &= Check(lambda->GetValue(0) == 0.0, "square: lambda_0 is exactly 0");
  ok &= Check(std::abs(lambda->GetValue(1) - pi2) < 0.01 * pi2 &&
      std::abs(lambda->GetValue(2) - pi2) < 0.01 * pi2,
    "square: lambda_1,2 = pi^2");
  ok &= Check(std::abs(lambda->GetValue(3) - 2 * pi2) < 0.01 * 2 * pi2, "square: lambda_3 = 2pi^2");
  ok &= Check(output->GetNumberOfPolys() == plane->GetOutput()->GetNumberOfPolys(),
    "the output keeps the input quads");
  return ok;
}

//------------------------------------------------------------------------------
// Points that no triangle uses (a free point, a vertex cell) get zero harmonics and mass.
bool TestUnusedPoints()
{
  auto sphere = MakeIcosphere(2, VTK_DOUBLE);
  const vtkIdType free = sphere->GetPoints()->InsertNextPoint(3.0, 0.0, 0.0);
  const vtkIdType vertex = sphere->GetPoints()->InsertNextPoint(0.0, 3.0, 0.0);
  vtkNew<vtkCellArray> verts;
  verts->InsertNextCell({ vertex });
  sphere->SetVerts(verts);

  vtkNew<vtkTest::ErrorObserver> warnings;
  auto output = Run(sphere, 5, warnings);
  bool ok =
    Check(warnings->CheckWarningMessage("used by no triangle") == 0, "warned about unused points");
  vtkDoubleArray* H = output ? Harmonics(output) : nullptr;
  vtkDoubleArray* D = output ? Mass(output) : nullptr;
  ok &= Check(H && D && H->GetNumberOfTuples() == sphere->GetNumberOfPoints(),
    "harmonics on every input point");
  if (!ok)
  {
    return false;
  }
  for (vtkIdType id : { free, vertex })
  {
    ok &= Check(D->GetValue(id) == 0.0, "unused point: zero mass");
    for (int k = 0; k < 5; ++k)
    {
      ok &= Check(H->GetComponent(id, k) == 0.0, "unused point: zero harmonics");
    }
  }
  ok &= Check(std::abs(H->GetComponent(0, 0)) > 0.1, "used point: constant harmonic");
  return ok;
}

//------------------------------------------------------------------------------
// A sphere and a stray triangle (debris): MinimumComponentSize 4 leaves the triangle out (zero
// harmonics and mass, one zero eigenvalue only); 0 keeps it (two zero eigenvalues).
bool TestMinimumComponentSize()
{
  auto mesh = MakeIcosphere(2, VTK_DOUBLE);
  const vtkIdType a = mesh->GetPoints()->InsertNextPoint(3.0, 0.0, 0.0);
  const vtkIdType b = mesh->GetPoints()->InsertNextPoint(3.1, 0.0, 0.0);
  const vtkIdType c = mesh->GetPoints()->InsertNextPoint(3.0, 0.1, 0.0);
  mesh->GetPolys()->InsertNextCell({ a, b, c });
  bool ok = true;
  for (int minimum : { 0, 4 })
  {
    vtkNew<vtkManifoldHarmonicBasis> basis;
    basis->SetInputData(mesh);
    basis->SetNumberOfHarmonics(6);
    basis->SetMinimumComponentSize(minimum);
    vtkNew<vtkTest::ErrorObserver> warnings;
    basis->AddObserver(vtkCommand::WarningEvent, warnings);
    basis->Update();
    vtkPolyData* output = basis->GetPolyDataOutput();
    vtkDoubleArray* lambda = Eigenvalues(output);
    vtkDoubleArray* D = Mass(output);
    ok &= Check(lambda && D && lambda->GetNumberOfTuples() == 6, "a basis of 6 harmonics");
    if (!lambda || !D)
    {
      return false;
    }
    const int zeros = (lambda->GetValue(0) == 0.0 ? 1 : 0) + (lambda->GetValue(1) == 0.0 ? 1 : 0);
    const std::string name = "MinimumComponentSize " + std::to_string(minimum) + ": ";
    ok &= Check(zeros == (minimum == 0 ? 2 : 1), name + "one zero eigenvalue per component kept");
    ok &= Check((D->GetValue(a) == 0.0) == (minimum == 4), name + "the debris' mass");
    ok &= Check((minimum == 4) ==
        (warnings->GetWarningMessage().find("Left out 1 connected component smaller") !=
          std::string::npos),
      name + "the debris left out is named");
  }
  return ok;
}

//------------------------------------------------------------------------------
// EigenvaluesOnly: the spectrum and the mass without the harmonics array. FrequencyWindow: the
// harmonics of l = 2 on the unit sphere (omega = sqrt(6)), after the 4 below.
bool TestSpectrumOptions()
{
  auto sphere = MakeIcosphere(3, VTK_DOUBLE);
  vtkNew<vtkManifoldHarmonicBasis> full;
  full->SetInputData(sphere);
  full->SetNumberOfHarmonics(9);
  full->Update();
  vtkNew<vtkManifoldHarmonicBasis> spectrum;
  spectrum->SetInputData(sphere);
  spectrum->SetNumberOfHarmonics(9);
  spectrum->EigenvaluesOnlyOn();
  spectrum->Update();
  vtkDoubleArray* all = Eigenvalues(full->GetOutput());
  vtkDoubleArray* only = Eigenvalues(spectrum->GetOutput());
  bool ok = Check(all && only && !Harmonics(spectrum->GetOutput()) && Mass(spectrum->GetOutput()),
    "EigenvaluesOnly: eigenvalues and mass, no harmonics");
  double difference = 0.0;
  for (vtkIdType k = 0; all && only && k < 9; ++k)
  {
    difference = std::max(
      difference, std::abs(all->GetValue(k) - only->GetValue(k)) / std::max(all->GetValue(k), 1.0));
  }
  // The same solve up to rounding (1e-15 relative between two runs in one process).
  ok &= Check(difference <= 1e-12, "EigenvaluesOnly: the same eigenvalues");
  for (const char* name : { "ManifoldHarmonicsBackwardError", "ManifoldHarmonicsResidual" })
  {
    vtkDataArray* figure = full->GetOutput()->GetFieldData()->GetArray(name);
    ok &= Check(figure && figure->GetNumberOfTuples() == 1 && figure->GetTuple1(0) >= 0.0 &&
        figure->GetTuple1(0) <= 1e-8,
      std::string(name) + ": one value, within the acceptance tolerance 1e-8");
  }

  vtkNew<vtkManifoldHarmonicBasis> window;
  window->SetInputData(sphere);
  window->SetFrequencyWindow(2.0, 3.2);
  window->Update();
  vtkDoubleArray* inside = Eigenvalues(window->GetOutput());
  vtkDataArray* H = window->GetOutput()->GetPointData()->GetArray("ManifoldHarmonics");
  ok &= Check(inside && inside->GetNumberOfTuples() == 5 && H && H->GetNumberOfComponents() == 5,
    "FrequencyWindow [2, 3.2): the 5 harmonics of l = 2");
  for (vtkIdType k = 0; inside && all && k < 5 && inside->GetNumberOfTuples() == 5; ++k)
  {
    ok &=
      Check(std::abs(inside->GetValue(k) - all->GetValue(4 + k)) <= 1e-12 * all->GetValue(4 + k),
        "FrequencyWindow: pair " + std::to_string(k) + " is pair " + std::to_string(4 + k));
  }
  const ManifoldHarmonicsTest::Messages errors(window);
  window->SetFrequencyWindow(2.5, 2.6);
  window->Update();
  ok &= Check(errors->GetError() && window->GetOutput()->GetNumberOfPoints() == 0 &&
      errors->GetErrorMessage().find("no eigenvalue lies in the frequency window") !=
        std::string::npos,
    "a window without an eigenvalue is an error with an empty output");
  return ok;
}

//------------------------------------------------------------------------------
// More harmonics than points: clamped with a warning. Empty input: passed through.
bool TestClampAndEmpty()
{
  auto sphere = MakeIcosphere(0, VTK_DOUBLE);
  vtkNew<vtkTest::ErrorObserver> warnings;
  auto output = Run(sphere, 50, warnings);
  bool ok = Check(warnings->CheckWarningMessage("clamped to 12") == 0, "warned about clamp");
  vtkDoubleArray* lambda = output ? Eigenvalues(output) : nullptr;
  ok &= Check(lambda && lambda->GetNumberOfTuples() == 12, "clamped to the number of points");

  vtkNew<vtkPolyData> empty;
  vtkNew<vtkTest::ErrorObserver> emptyWarnings;
  auto passed = Run(empty, 10, emptyWarnings);
  ok &= Check(emptyWarnings->GetWarning() && !emptyWarnings->GetError(), "empty input: warning");
  ok &= Check(
    passed && passed->GetNumberOfPoints() == 0 && !Harmonics(passed), "empty input passed through");

  // Fewer than one harmonic: refused with an error, the previous value kept.
  for (int m : { 0, -3 })
  {
    vtkNew<vtkManifoldHarmonicBasis> basis;
    vtkNew<vtkTest::ErrorObserver> errors;
    basis->AddObserver(vtkCommand::ErrorEvent, errors);
    basis->SetNumberOfHarmonics(25);
    basis->SetNumberOfHarmonics(m);
    ok &= Check(errors->CheckErrorMessage("at least 1") == 0 && basis->GetNumberOfHarmonics() == 25,
      ("NumberOfHarmonics " + std::to_string(m) + " refused").c_str());
  }
  return ok;
}

//------------------------------------------------------------------------------
// BasisPrecision Float: a vtkFloatArray holding the double harmonics rounded once; the mass and
// the eigenvalues stay double, and the eigenvalues are those of the double basis.
bool TestBasisPrecision()
{
  auto sphere = MakeIcosphere(3, VTK_DOUBLE);
  const int m = 20;
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetNumberOfHarmonics(m);
  basis->SetInputData(sphere);
  bool ok = Check(basis->GetBasisPrecision() == vtkManifoldHarmonicBasis::DOUBLE,
    "BasisPrecision defaults to DOUBLE");
  basis->Update();
  vtkNew<vtkDoubleArray> reference;
  reference->DeepCopy(Harmonics(basis->GetOutput()));
  vtkNew<vtkDoubleArray> referenceLambda;
  referenceLambda->DeepCopy(Eigenvalues(basis->GetOutput()));

  basis->SetBasisPrecisionToFloat();
  basis->Update();
  vtkPolyData* output = basis->GetPolyDataOutput();
  auto* floats = vtkFloatArray::SafeDownCast(
    output->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName()));
  ok &= Check(floats && floats->GetNumberOfComponents() == m &&
      floats->GetNumberOfTuples() == sphere->GetNumberOfPoints(),
    "BasisPrecision Float writes an n x m vtkFloatArray");
  ok &= Check(Mass(output) && Eigenvalues(output), "the mass and eigenvalues stay double");
  if (!ok)
  {
    return false;
  }
  ok &= Check(std::string(floats->GetComponentName(m - 1)) == "Phi_" + std::to_string(m - 1),
    "float harmonics keep their component names");
  double worst = 0.0;
  for (vtkIdType i = 0; i < reference->GetNumberOfValues(); ++i)
  {
    worst = std::max(worst,
      std::abs(static_cast<double>(floats->GetValue(i)) -
        static_cast<double>(static_cast<float>(reference->GetValue(i)))));
  }
  double lambda = 0.0;
  for (int k = 0; k < m; ++k)
  {
    lambda =
      std::max(lambda, std::abs(Eigenvalues(output)->GetValue(k) - referenceLambda->GetValue(k)));
  }
  std::cout << "Float basis: max |float - round(double)| " << worst << ", max |d lambda| " << lambda
            << std::endl;
  ok &= Check(worst == 0.0, "the float harmonics are the double ones rounded once");
  ok &= Check(lambda < 1e-10, "the eigenvalues do not depend on BasisPrecision");
  return ok;
}

//------------------------------------------------------------------------------
// A memory limit below the estimate: an error with the figures and the advice, an empty output,
// no crash; BasisPrecision Float is only suggested for a double basis.
bool TestMemoryGuard()
{
  auto sphere = MakeIcosphere(3, VTK_DOUBLE);
  bool ok = true;
  for (int precision : { vtkManifoldHarmonicBasis::DOUBLE, vtkManifoldHarmonicBasis::FLOAT })
  {
    vtkNew<vtkManifoldHarmonicBasis> basis;
    basis->SetNumberOfHarmonics(30);
    basis->SetBasisPrecision(precision);
    basis->SetMemoryLimit(0.01); // 10 KiB
    basis->SetInputData(sphere);
    const ManifoldHarmonicsTest::Messages errors(basis);
    basis->Update();
    const std::string message = errors->GetErrorMessage();
    // The text only: the output of a test must not contain the word that marks VTK errors.
    const std::size_t start = message.find("Not enough memory");
    const std::string text = start == std::string::npos
      ? std::string("(no message)")
      : message.substr(start, message.find('\n', start) - start);
    std::cout << "Memory guard: " << text << std::endl;
    ok &= Check(errors->GetError() && message.find("Not enough memory") != std::string::npos &&
        message.find("needed") != std::string::npos &&
        message.find("10.2 KiB available (MemoryLimit)") != std::string::npos &&
        message.find("fewer harmonics") != std::string::npos &&
        message.find("BandSize") != std::string::npos,
      "a tiny MemoryLimit gives an error with what is needed, what is available, what to do");
    const bool suggestsFloat = message.find("BasisPrecision to Float") != std::string::npos;
    ok &= Check(suggestsFloat == (precision == vtkManifoldHarmonicBasis::DOUBLE),
      "BasisPrecision Float is suggested for a double basis only");
    ok &= Check(basis->GetOutput()->GetNumberOfPoints() == 0 && !Harmonics(basis->GetOutput()),
      "the output is empty after the memory error");

    // A limit below one byte still limits (it rounded to 0, "the system does not say").
    basis->SetMemoryLimit(1e-9);
    errors->Clear();
    basis->Update();
    ok &= Check(errors->GetError() &&
        errors->GetErrorMessage().find("Not enough memory") != std::string::npos &&
        basis->GetOutput()->GetNumberOfPoints() == 0,
      "a MemoryLimit below one byte fails like any limit too small");

    // A limit the estimate fits in: the basis is computed.
    basis->SetMemoryLimit(1024.0);
    errors->Clear();
    basis->Update();
    ok &= Check(!errors->GetError() &&
        basis->GetOutput()->GetPointData()->GetArray(
          vtkManifoldHarmonicBasis::HarmonicsArrayName()),
      "a sufficient MemoryLimit computes the basis");
  }
  return ok;
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestManifoldHarmonicBasis(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "ArraysAndSphereSpectrum", TestArraysAndSphereSpectrum },
      { "FloatAndDoublePoints", TestFloatAndDoublePoints },
      { "ConsistentMass", TestConsistentMass },
      { "Abort", TestAbort },
      { "Quads", TestQuads },
      { "UnusedPoints", TestUnusedPoints },
      { "ClampAndEmpty", TestClampAndEmpty },
      { "MinimumComponentSize", TestMinimumComponentSize },
      { "SpectrumOptions", TestSpectrumOptions },
      { "BasisPrecision", TestBasisPrecision },
      { "MemoryGuard", TestMemoryGuard },
    });
}
