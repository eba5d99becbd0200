// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Checks of vtkSpectralDescriptors: the arrays and the ShapeDNA table, the sphere's heat kernel
// signature against its analytic value, invariance under a rigid motion, symmetric distances
// from a source point or location, ShapeDNA under scaling, a float basis against a double one,
// and the errors and abort of the filter.

#include "vtkSpectralDescriptors.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTable.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
using ManifoldHarmonicsTest::Check;
using ManifoldHarmonicsTest::RelativeDifference;

//------------------------------------------------------------------------------
// A sphere of the given radius with its basis of m harmonics (double unless `floats`),
// stretched into an ellipsoid of semi-axes (1, 1.3, 0.8) times the radius if `ellipsoid`.
vtkSmartPointer<vtkPolyData> SphereBasis(double radius,
  int m,
  bool floats = false,
  bool ellipsoid = false)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(40);
  sphere->SetPhiResolution(40);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->DeepCopy(sphere->GetOutput());
  for (vtkIdType i = 0; ellipsoid && i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    mesh->GetPoints()->SetPoint(i, p[0], 1.3 * p[1], 0.8 * p[2]);
  }
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(mesh);
  basis->SetNumberOfHarmonics(m);
  if (floats)
  {
    basis->SetBasisPrecisionToFloat();
  }
  basis->Update();
  vtkSmartPointer<vtkPolyData> output = basis->GetPolyDataOutput();
  return output;
}

//------------------------------------------------------------------------------
vtkDataArray* Run(vtkSpectralDescriptors* filter, vtkPolyData* input, const char* name)
{
  filter->SetInputData(input);
  filter->Update();
  return filter->GetOutput()->GetPointData()->GetArray(name);
}

//------------------------------------------------------------------------------
// Names, shapes, defaults, and the unit sphere's HKS sum_l (2l+1) e^{-l(l+1)t} / (4 pi), the
// same at every point, to the discretization error measured by the eigenvalues (the core test
// TestDescriptors bounds it; here 1% at t = 0.5, where the 40 x 40 sphere's lambda_1 ... lambda_3
// are within 0.2% of 2 and the area within 0.3% of 4 pi).
bool TestSphere()
{
  vtkSmartPointer<vtkPolyData> input = SphereBasis(1.0, 36);
  vtkNew<vtkSpectralDescriptors> filter;
  vtkDataArray* hks = Run(filter, input, vtkSpectralDescriptors::HeatKernelSignatureArrayName());
  bool ok = Check(hks && hks->GetNumberOfComponents() == 16, "default HKS of 16 times");
  ok &= Check(!filter->GetOutput()->GetPointData()->GetArray(
                vtkSpectralDescriptors::WaveKernelSignatureArrayName()),
    "WKS is off by default");
  vtkTable* dna = filter->GetShapeDNAOutput();
  ok &= Check(dna->GetNumberOfRows() == 36 && dna->GetColumnByName("Index") &&
      dna->GetColumnByName("Eigenvalue") &&
      dna->GetColumnByName(vtkSpectralDescriptors::ScaledEigenvalueColumnName()),
    "ShapeDNA table of 36 rows with Index, Eigenvalue, ScaledEigenvalue");

  filter->AddHeatKernelTime(0.5);
  hks = Run(filter, input, vtkSpectralDescriptors::HeatKernelSignatureArrayName());
  double exact = 0.0;
  for (int l = 0; l < 40; ++l)
  {
    exact += (2 * l + 1) * std::exp(-l * (l + 1.0) * 0.5) / (4.0 * vtkMath::Pi());
  }
  double worst = 0.0;
  for (vtkIdType i = 0; i < hks->GetNumberOfTuples(); ++i)
  {
    worst = std::max(worst, std::abs(hks->GetComponent(i, 0) - exact) / exact);
  }
  std::cout << "Sphere: HKS(t = 0.5) exact " << exact << ", largest relative error " << worst
            << std::endl;
  ok &= Check(worst < 0.01, "the unit sphere's HKS at t = 0.5 is not the analytic value");
  return ok;
}

//------------------------------------------------------------------------------
// A rotation and a translation change neither the harmonics' values nor the eigenvalues
// beyond the eigensolver's residual (1e-8) over the relative gaps of a generic spectrum;
// 1e-5 of the largest value leaves room for the 1e-3 gaps of the sphere's split clusters.
bool TestRigidMotion()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(15);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  // Rotation by 0.7 radians about (1, 2, 3) (Rodrigues), then a translation by (2, -1, 0.5).
  vtkNew<vtkPolyData> movedMesh;
  movedMesh->DeepCopy(sphere->GetOutput());
  double axis[3] = { 1.0, 2.0, 3.0 };
  vtkMath::Normalize(axis);
  const double c = std::cos(0.7);
  const double s = std::sin(0.7);
  for (vtkIdType i = 0; i < movedMesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    double cross[3];
    movedMesh->GetPoint(i, p);
    vtkMath::Cross(axis, p, cross);
    const double along = vtkMath::Dot(axis, p) * (1.0 - c);
    const double q[3] = { p[0] * c + cross[0] * s + axis[0] * along + 2.0,
      p[1] * c + cross[1] * s + axis[1] * along - 1.0,
      p[2] * c + cross[2] * s + axis[2] * along + 0.5 };
    movedMesh->GetPoints()->SetPoint(i, q);
  }
  vtkNew<vtkManifoldHarmonicBasis> basisA;
  basisA->SetInputConnection(sphere->GetOutputPort());
  basisA->SetNumberOfHarmonics(30);
  vtkNew<vtkManifoldHarmonicBasis> basisB;
  basisB->SetInputData(movedMesh);
  basisB->SetNumberOfHarmonics(30);
  vtkNew<vtkSpectralDescriptors> a;
  a->SetInputConnection(basisA->GetOutputPort());
  a->AddHeatKernelTime(0.05);
  a->AddHeatKernelTime(0.5);
  a->Update();
  vtkNew<vtkSpectralDescriptors> b;
  b->SetInputConnection(basisB->GetOutputPort());
  b->AddHeatKernelTime(0.05);
  b->AddHeatKernelTime(0.5);
  b->Update();
  const double difference =
    RelativeDifference(b->GetOutput()->GetPointData()->GetArray("HeatKernelSignature"),
      a->GetOutput()->GetPointData()->GetArray("HeatKernelSignature"));
  std::cout << "Rigid motion: HKS relative difference " << difference << std::endl;
  return Check(difference < 1e-5, "HKS changed under a rigid motion");
}

//------------------------------------------------------------------------------
// d(x, y) = d(y, x) for each kind (the same sum in another order: round-off), zero only at the
// source; the source found from a location is the nearest point.
bool TestDistances()
{
  vtkSmartPointer<vtkPolyData> input = SphereBasis(1.0, 36);
  const vtkIdType x = 5;
  const vtkIdType y = 700;
  bool ok = true;
  for (int kind = vtkSpectralDescriptors::DIFFUSION; kind <= vtkSpectralDescriptors::BIHARMONIC;
       ++kind)
  {
    vtkNew<vtkSpectralDescriptors> filter;
    filter->ComputeHeatKernelSignatureOff();
    filter->ComputeSpectralDistanceOn();
    filter->SetDistanceKind(kind);
    filter->SetDiffusionTime(0.05);
    filter->SetSourcePoint(x);
    vtkNew<vtkDoubleArray> fromX;
    fromX->DeepCopy(Run(filter, input, "SpectralDistance"));
    // The source given by the location of y.
    filter->UseSourceLocationOn();
    filter->SetSourceLocation(input->GetPoint(y));
    vtkDataArray* fromY = Run(filter, input, "SpectralDistance");
    ok &= Check(filter->GetUsedSourcePoint() == y, "the location of y does not select y");
    const double dxy = fromX->GetValue(y);
    const double dyx = fromY->GetComponent(x, 0);
    double smallest = VTK_DOUBLE_MAX;
    for (vtkIdType i = 0; i < fromX->GetNumberOfTuples(); ++i)
    {
      smallest = i == x ? smallest : std::min(smallest, fromX->GetValue(i));
    }
    std::cout << "Distance kind " << kind << ": d(x, y) " << dxy << ", d(y, x) " << dyx
              << ", smallest to another point " << smallest << std::endl;
    ok &= Check(std::abs(dxy - dyx) <= 1e-12 * dxy, "distance not symmetric");
    ok &= Check(fromX->GetValue(x) == 0.0 && smallest > 0.0, "distance not zero only at source");
  }
  return ok;
}

//------------------------------------------------------------------------------
// lambda A of spheres of radius 1 and 3 agree to the eigensolver's residual (the cotangent
// weights do not change with scale and the mass scales by 9).
bool TestShapeDNA()
{
  vtkNew<vtkSpectralDescriptors> small;
  small->SetInputData(SphereBasis(1.0, 16));
  small->Update();
  vtkNew<vtkSpectralDescriptors> large;
  large->SetInputData(SphereBasis(3.0, 16));
  large->Update();
  vtkDataArray* a =
    vtkDataArray::SafeDownCast(small->GetShapeDNAOutput()->GetColumnByName("ScaledEigenvalue"));
  vtkDataArray* b =
    vtkDataArray::SafeDownCast(large->GetShapeDNAOutput()->GetColumnByName("ScaledEigenvalue"));
  const double difference = RelativeDifference(b, a);
  std::cout << "ShapeDNA radius 3 vs 1: relative difference " << difference
            << ", lambda_1 A = " << a->GetComponent(1, 0) << " (8 pi = " << 8 * vtkMath::Pi() << ")"
            << std::endl;
  return Check(difference < 1e-8, "ShapeDNA not scale-invariant");
}

//------------------------------------------------------------------------------
// A basis computed with EigenvaluesOnly (no harmonics) gives the same ShapeDNA; the point
// descriptors, which need the harmonics, are left out with a warning saying why, and ShapeDNA
// is still computed.
bool TestShapeDNAFromEigenvaluesOnly()
{
  vtkNew<vtkSpectralDescriptors> full;
  full->SetInputData(SphereBasis(1.0, 16));
  full->Update();
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(40);
  sphere->SetPhiResolution(40);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputConnection(sphere->GetOutputPort());
  basis->SetNumberOfHarmonics(16);
  basis->EigenvaluesOnlyOn();
  vtkNew<vtkSpectralDescriptors> spectrum;
  spectrum->SetInputConnection(basis->GetOutputPort());
  spectrum->ComputeHeatKernelSignatureOff();
  spectrum->Update();
  vtkDataArray* a =
    vtkDataArray::SafeDownCast(full->GetShapeDNAOutput()->GetColumnByName("ScaledEigenvalue"));
  vtkDataArray* b =
    vtkDataArray::SafeDownCast(spectrum->GetShapeDNAOutput()->GetColumnByName("ScaledEigenvalue"));
  // The same solve, equal bit for bit since its rounding no longer follows the heap's layout
  // (SumOfEntries, Common/Mesh.h; 1e-15 before); the bound leaves room for other machines.
  bool ok = Check(a && b && RelativeDifference(b, a) <= 1e-12,
    "ShapeDNA from an EigenvaluesOnly basis differs from the full basis's");
  const ManifoldHarmonicsTest::Messages warnings(spectrum);
  spectrum->ComputeHeatKernelSignatureOn();
  spectrum->Update();
  ok &= Check(warnings->GetWarning() && !warnings->GetError() &&
      warnings->GetWarningMessage().find("EigenvaluesOnly") != std::string::npos,
    "point descriptors on an EigenvaluesOnly basis are not left out with a warning saying why");
  vtkDataArray* again =
    vtkDataArray::SafeDownCast(spectrum->GetShapeDNAOutput()->GetColumnByName("ScaledEigenvalue"));
  ok &= Check(again && RelativeDifference(again, a) <= 1e-12 &&
      !spectrum->GetOutput()->GetPointData()->GetArray(
        vtkSpectralDescriptors::HeatKernelSignatureArrayName()),
    "with the point descriptors on, ShapeDNA is still computed and no HKS array made up");
  return ok;
}

//------------------------------------------------------------------------------
// A float basis changes the descriptors by float round-off: 1e-6 of each array's largest value.
// On an ellipsoid, whose eigenvalues are simple: the global point signature depends on the
// harmonics themselves, which a multiple eigenvalue (the sphere's) leaves free to rotate.
bool TestFloatBasis()
{
  bool ok = true;
  vtkSmartPointer<vtkPolyData> doubles = SphereBasis(1.0, 30, false, true);
  vtkSmartPointer<vtkPolyData> floats = SphereBasis(1.0, 30, true, true);
  ok &= Check(floats->GetPointData()->GetArray("ManifoldHarmonics")->GetDataType() == VTK_FLOAT,
    "float basis expected");
  vtkNew<vtkSpectralDescriptors> a;
  vtkNew<vtkSpectralDescriptors> b;
  for (vtkSpectralDescriptors* filter : { a.Get(), b.Get() })
  {
    filter->ComputeWaveKernelSignatureOn();
    filter->ComputeGlobalPointSignatureOn();
    filter->ComputeSpectralDistanceOn();
  }
  a->SetInputData(doubles);
  a->Update();
  b->SetInputData(floats);
  b->Update();
  for (const char* name :
    { "HeatKernelSignature", "WaveKernelSignature", "GlobalPointSignature", "SpectralDistance" })
  {
    vtkDataArray* fromFloats = b->GetOutput()->GetPointData()->GetArray(name);
    vtkDataArray* fromDoubles = a->GetOutput()->GetPointData()->GetArray(name);
    if (std::string(name) == "GlobalPointSignature")
    {
      // Each harmonic is defined up to its sign, which the basis fixes by its largest entry:
      // on a shape with mirror symmetries, two entries of opposite signs tie and round-off
      // decides. Align each column's sign before comparing.
      vtkNew<vtkDoubleArray> aligned;
      aligned->DeepCopy(fromFloats);
      for (int c = 0; c < aligned->GetNumberOfComponents(); ++c)
      {
        double dot = 0.0;
        for (vtkIdType i = 0; i < aligned->GetNumberOfTuples(); ++i)
        {
          dot += aligned->GetComponent(i, c) * fromDoubles->GetComponent(i, c);
        }
        for (vtkIdType i = 0; dot < 0.0 && i < aligned->GetNumberOfTuples(); ++i)
        {
          aligned->SetComponent(i, c, -aligned->GetComponent(i, c));
        }
      }
      fromFloats = aligned;
      const double difference = RelativeDifference(fromFloats, fromDoubles);
      std::cout << "Float basis: " << name << " (signs aligned) relative difference " << difference
                << std::endl;
      ok &= Check(difference < 1e-6, std::string(name) + " of a float basis differs");
      continue;
    }
    const double difference = RelativeDifference(fromFloats, fromDoubles);
    std::cout << "Float basis: " << name << " relative difference " << difference << std::endl;
    ok &= Check(difference < 1e-6, std::string(name) + " of a float basis differs");
  }
  return ok;
}

//------------------------------------------------------------------------------
// One execution that must fail with an error containing `expected` and leave an empty output.
bool ExpectError(vtkSpectralDescriptors* filter, vtkPolyData* input, const std::string& expected)
{
  const ManifoldHarmonicsTest::Messages errors(filter);
  filter->SetInputData(input);
  filter->Update();
  const std::string message = errors->GetErrorMessage();
  // The message without its "ERROR: In file, line" prefix (the test fails on "ERROR: ").
  std::cout << "Expected error: " << message.substr(message.find('\n') + 1);
  return Check(errors->GetError() && message.find(expected) != std::string::npos &&
      filter->GetOutput()->GetNumberOfPoints() == 0,
    "no error containing '" + expected + "' with an empty output");
}

//------------------------------------------------------------------------------
bool TestErrors()
{
  vtkSmartPointer<vtkPolyData> input = SphereBasis(1.0, 10);
  bool ok = true;
  {
    vtkNew<vtkSphereSource> plain;
    plain->Update();
    vtkNew<vtkSpectralDescriptors> filter;
    ok &= ExpectError(filter, plain->GetOutput(), "ManifoldHarmonicBasis");
  }
  {
    vtkNew<vtkSpectralDescriptors> filter;
    filter->ComputeSpectralDistanceOn();
    filter->SetSourcePoint(input->GetNumberOfPoints());
    ok &= ExpectError(filter, input, "SourcePoint");
  }
  {
    vtkNew<vtkSpectralDescriptors> filter;
    filter->AddHeatKernelTime(0.1);
    filter->AddHeatKernelTime(-1.0);
    ok &= ExpectError(filter, input, "HeatKernelTimes[1]");
  }
  {
    vtkNew<vtkSpectralDescriptors> filter;
    filter->ComputeSpectralDistanceOn();
    filter->SetDistanceKindToDiffusion();
    filter->SetDiffusionTime(-0.1);
    ok &= ExpectError(filter, input, "DiffusionTime");
  }
  {
    // NaN, not a point: an error naming SourceLocation (it said "Source point -1 is used by no
    // triangle").
    vtkNew<vtkSpectralDescriptors> filter;
    filter->ComputeSpectralDistanceOn();
    filter->UseSourceLocationOn();
    filter->SetSourceLocation(std::nan(""), 0.0, 0.0);
    ok &= ExpectError(filter, input, "SourceLocation (nan, 0, 0) is not a finite point");
  }
  return ok;
}

//------------------------------------------------------------------------------
// Warnings: GPS components beyond the basis are clamped; times too small for the basis say
// how many harmonics they need.
bool TestWarnings()
{
  vtkSmartPointer<vtkPolyData> input = SphereBasis(1.0, 10);
  vtkNew<vtkTest::ErrorObserver> warnings;
  vtkNew<vtkSpectralDescriptors> filter;
  filter->AddObserver(vtkCommand::WarningEvent, warnings);
  filter->ComputeGlobalPointSignatureOn();
  filter->SetNumberOfGPSComponents(50);
  filter->AddHeatKernelTime(0.001);
  vtkDataArray* gps = Run(filter, input, "GlobalPointSignature");
  const std::string message = warnings->GetWarningMessage();
  std::cout << "Expected warnings: " << message;
  bool ok = Check(gps && gps->GetNumberOfComponents() == 9, "GPS not clamped to 9 components");
  ok &= Check(message.find("harmonic") != std::string::npos, "no warning");
  return ok;
}

//------------------------------------------------------------------------------
// Asks the filter to abort at its first progress event: both outputs are then empty.
bool TestAbort()
{
  vtkSmartPointer<vtkPolyData> input = SphereBasis(1.0, 10);
  vtkNew<vtkSpectralDescriptors> filter;
  vtkNew<ManifoldHarmonicsTest::AbortAtFirstProgress> abort;
  filter->AddObserver(vtkCommand::ProgressEvent, abort);
  filter->ComputeWaveKernelSignatureOn();
  filter->SetInputData(input);
  filter->Update();
  std::cout << "Abort: " << abort->Count << " progress event(s)" << std::endl;
  return Check(abort->Count == 1 && filter->GetOutput()->GetNumberOfPoints() == 0 &&
      filter->GetShapeDNAOutput()->GetNumberOfRows() == 0,
    "an aborted execution did not stop with empty outputs");
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestSpectralDescriptors(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "Sphere", TestSphere },
      { "RigidMotion", TestRigidMotion },
      { "Distances", TestDistances },
      { "ShapeDNA", TestShapeDNA },
      { "ShapeDNAFromEigenvaluesOnly", TestShapeDNAFromEigenvaluesOnly },
      { "FloatBasis", TestFloatBasis },
      { "Errors", TestErrors },
      { "Warnings", TestWarnings },
      { "Abort", TestAbort },
    });
}
