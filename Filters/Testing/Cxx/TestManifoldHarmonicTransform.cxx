// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Checks of vtkManifoldHarmonicTransform: output names and shapes, the spectrum table, the
// coefficients against the defining sum, float and double signals, the array selection, and
// clear errors when the basis arrays are missing or do not match the mesh.

#include "vtkManifoldHarmonicTransform.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTable.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
using ManifoldHarmonicsTest::AbortAtFirstProgress;
using ManifoldHarmonicsTest::Check;
using ManifoldHarmonicsTest::LinesOnly;

//------------------------------------------------------------------------------
// A unit sphere (double points) with a smooth scalar "Height" (float and double copies) and an
// RGB colour array, run through the basis filter with `harmonics` harmonics.
vtkSmartPointer<vtkPolyData> MakeBasis(int harmonics)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(12);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->ShallowCopy(sphere->GetOutput());
  const vtkIdType n = mesh->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> height;
  height->SetName("Height");
  height->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> heightFloat;
  heightFloat->SetName("HeightFloat");
  heightFloat->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    const double value = p[2] + 0.5 * p[0] * p[1];
    height->SetValue(i, value);
    heightFloat->SetValue(i, static_cast<float>(value));
    for (int c = 0; c < 3; ++c)
    {
      colors->SetTypedComponent(i, c, static_cast<unsigned char>(127.5 * (p[c] + 1.0)));
    }
  }
  mesh->GetPointData()->AddArray(height);
  mesh->GetPointData()->AddArray(heightFloat);
  mesh->GetPointData()->AddArray(colors);

  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(mesh);
  basis->SetNumberOfHarmonics(harmonics);
  basis->Update();
  vtkSmartPointer<vtkPolyData> output = basis->GetPolyDataOutput();
  return output;
}

//------------------------------------------------------------------------------
// Largest |transform coefficient - sum_i x_i D_ii H^k_i| relative to the largest coefficient.
double DefinitionError(vtkPolyData* basis, vtkDataArray* signal, vtkDataArray* coefficients)
{
  vtkDataArray* H = basis->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName());
  vtkDataArray* D = basis->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName());
  double error = 0.0;
  double scale = 0.0;
  for (int k = 0; k < H->GetNumberOfComponents(); ++k)
  {
    for (int c = 0; c < signal->GetNumberOfComponents(); ++c)
    {
      double sum = 0.0;
      for (vtkIdType i = 0; i < signal->GetNumberOfTuples(); ++i)
      {
        sum += signal->GetComponent(i, c) * D->GetComponent(i, 0) * H->GetComponent(i, k);
      }
      error = std::max(error, std::abs(sum - coefficients->GetComponent(k, c)));
      scale = std::max(scale, std::abs(sum));
    }
  }
  return error / scale;
}

//------------------------------------------------------------------------------
bool TestNamesAndShapes()
{
  const int m = 25;
  vtkSmartPointer<vtkPolyData> basis = MakeBasis(m);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputData(basis);
  transform->GetPointDataArraySelection()->EnableArray("Height");
  transform->GetPointDataArraySelection()->EnableArray("Colors");
  // Basis arrays are never transformed, even when asked for.
  transform->GetPointDataArraySelection()->EnableArray(vtkManifoldHarmonicBasis::MassArrayName());
  transform->Update();

  bool ok = true;
  vtkPolyData* output = transform->GetPolyDataOutput();
  vtkFieldData* fd = output->GetFieldData();
  ok &= Check(output->GetNumberOfPoints() == basis->GetNumberOfPoints(), "point count changed");
  ok &= Check(output->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName()),
    "the basis is not passed through");
  const char* expected[][2] = {
    { "Points_Coefficients", "3" }, { "Height_Coefficients", "1" }, { "Colors_Coefficients", "3" }
  };
  for (const auto& entry : expected)
  {
    vtkDataArray* array = fd->GetArray(entry[0]);
    ok &= Check(array != nullptr, std::string("missing ") + entry[0]);
    ok &=
      Check(array && vtkDoubleArray::SafeDownCast(array), std::string(entry[0]) + " not double");
    ok &= Check(array && array->GetNumberOfTuples() == m &&
        array->GetNumberOfComponents() == std::stoi(entry[1]),
      std::string(entry[0]) + " has the wrong shape");
  }
  ok &= Check(!fd->GetArray("HeightFloat_Coefficients"), "unselected array transformed");
  ok &= Check(!fd->GetArray((std::string(vtkManifoldHarmonicBasis::MassArrayName()) +
                vtkManifoldHarmonicTransform::CoefficientsSuffix())
                              .c_str()),
    "basis array transformed");

  // Spectrum: Index, Eigenvalue, Frequency and one magnitude column per signal.
  vtkTable* spectrum = transform->GetSpectrumOutput();
  ok &= Check(spectrum && spectrum->GetNumberOfRows() == m, "spectrum rows != m");
  ok &= Check(spectrum && spectrum->GetNumberOfColumns() == 6, "spectrum columns != 6");
  vtkDataArray* lambda =
    output->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  vtkDataArray* frequency = vtkArrayDownCast<vtkDataArray>(spectrum->GetColumnByName("Frequency"));
  vtkDataArray* eigenvalue =
    vtkArrayDownCast<vtkDataArray>(spectrum->GetColumnByName("Eigenvalue"));
  vtkDataArray* index = vtkArrayDownCast<vtkDataArray>(spectrum->GetColumnByName("Index"));
  vtkDataArray* magnitude =
    vtkArrayDownCast<vtkDataArray>(spectrum->GetColumnByName("Points_Magnitude"));
  ok &= Check(frequency && eigenvalue && index && magnitude, "spectrum columns misnamed");
  if (!ok)
  {
    return false;
  }
  vtkDataArray* pointsCoefficients = fd->GetArray("Points_Coefficients");
  for (vtkIdType k = 0; k < m; ++k)
  {
    const double l = lambda->GetComponent(k, 0);
    ok &= Check(index->GetComponent(k, 0) == k, "Index column");
    ok &= Check(eigenvalue->GetComponent(k, 0) == l, "Eigenvalue column");
    ok &= Check(std::abs(frequency->GetComponent(k, 0) - std::sqrt(std::max(l, 0.0))) < 1e-14,
      "Frequency column");
    double tuple[3];
    pointsCoefficients->GetTuple(k, tuple);
    const double norm = std::sqrt(tuple[0] * tuple[0] + tuple[1] * tuple[1] + tuple[2] * tuple[2]);
    ok &= Check(std::abs(magnitude->GetComponent(k, 0) - norm) < 1e-14, "Magnitude column");
  }
  // The coordinates of a sphere are first-order harmonics: harmonics 1-3 carry all of them.
  double inBand = 0.0;
  double total = 0.0;
  for (vtkIdType k = 0; k < m; ++k)
  {
    const double power = std::pow(magnitude->GetComponent(k, 0), 2);
    total += power;
    inBand += (k >= 1 && k <= 3) ? power : 0.0;
  }
  std::cout << "Sphere coordinates: " << 100.0 * inBand / total << "% of the power in harmonics 1-3"
            << std::endl;
  ok &= Check(inBand / total > 0.999, "sphere coordinates are not first-order harmonics");
  return ok;
}

//------------------------------------------------------------------------------
bool TestDefinitionAndPrecision()
{
  vtkSmartPointer<vtkPolyData> basis = MakeBasis(30);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputData(basis);
  transform->GetPointDataArraySelection()->EnableArray("Height");
  transform->GetPointDataArraySelection()->EnableArray("HeightFloat");
  transform->GetPointDataArraySelection()->EnableArray("Colors");
  transform->Update();
  vtkFieldData* fd = transform->GetOutput()->GetFieldData();
  vtkPointData* pd = basis->GetPointData();

  bool ok = true;
  const double heightError =
    DefinitionError(basis, pd->GetArray("Height"), fd->GetArray("Height_Coefficients"));
  const double colorError =
    DefinitionError(basis, pd->GetArray("Colors"), fd->GetArray("Colors_Coefficients"));
  const double pointsError =
    DefinitionError(basis, basis->GetPoints()->GetData(), fd->GetArray("Points_Coefficients"));
  std::cout << "Coefficients against sum_i x_i D_ii H^k_i: double " << heightError
            << ", unsigned char " << colorError << ", points " << pointsError << std::endl;
  ok &= Check(heightError < 1e-12, "double coefficients differ from the definition");
  ok &= Check(colorError < 1e-12, "unsigned char coefficients differ from the definition");
  ok &= Check(pointsError < 1e-12, "point coefficients differ from the definition");

  // A float copy of the same signal gives the same coefficients to float precision.
  vtkDataArray* a = fd->GetArray("Height_Coefficients");
  vtkDataArray* b = fd->GetArray("HeightFloat_Coefficients");
  double difference = 0.0;
  for (vtkIdType k = 0; k < a->GetNumberOfTuples(); ++k)
  {
    difference = std::max(difference, std::abs(a->GetComponent(k, 0) - b->GetComponent(k, 0)));
  }
  std::cout << "float vs double coefficients: " << difference << std::endl;
  ok &= Check(difference < 1e-6, "float and double signals disagree");
  return ok;
}

//------------------------------------------------------------------------------
bool TestSelectionModifies()
{
  vtkNew<vtkManifoldHarmonicTransform> transform;
  const vtkMTimeType before = transform->GetMTime();
  transform->GetPointDataArraySelection()->EnableArray("Height");
  const vtkMTimeType after = transform->GetMTime();
  bool ok = Check(after > before, "enabling an array does not modify the filter");
  transform->SetTransformPoints(false);
  transform->GetPointDataArraySelection()->DisableArray("Height");
  ok &= Check(transform->GetMTime() > after, "disabling an array does not modify the filter");
  return ok;
}

//------------------------------------------------------------------------------
// Runs the transform on `input` and expects an error mentioning each of `words`.
bool ExpectError(vtkPointSet* input, const std::string& words1, const std::string& words2)
{
  vtkNew<vtkManifoldHarmonicTransform> transform;
  const ManifoldHarmonicsTest::Messages filterErrors(transform);
  transform->SetInputData(input);
  transform->Update();
  const std::string message = filterErrors->GetErrorMessage();
  // Without the "ERROR: In file, line" prefix, which the test harness takes for a failure.
  std::cout << "Expected error:" << message.substr(message.find("): ") + 2);
  bool ok = Check(filterErrors->GetError(), "no error for input lacking '" + words1 + "'");
  ok &= Check(message.find(words1) != std::string::npos, "error does not name " + words1);
  ok &= Check(message.find(words2) != std::string::npos, "error does not name " + words2);
  return ok;
}

//------------------------------------------------------------------------------
bool TestErrors()
{
  bool ok = true;
  vtkNew<vtkSphereSource> sphere;
  sphere->Update();
  ok &= ExpectError(
    sphere->GetOutput(), vtkManifoldHarmonicBasis::HarmonicsArrayName(), "ManifoldHarmonicBasis");

  vtkSmartPointer<vtkPolyData> basis = MakeBasis(10);
  vtkNew<vtkPolyData> noMass;
  noMass->ShallowCopy(basis);
  noMass->GetPointData()->RemoveArray(vtkManifoldHarmonicBasis::MassArrayName());
  ok &= ExpectError(noMass, vtkManifoldHarmonicBasis::MassArrayName(), "ManifoldHarmonicBasis");

  vtkNew<vtkPolyData> noEigenvalues;
  noEigenvalues->ShallowCopy(basis);
  vtkNew<vtkFieldData> emptyFieldData;
  noEigenvalues->SetFieldData(emptyFieldData);
  ok &= ExpectError(
    noEigenvalues, vtkManifoldHarmonicBasis::EigenvaluesArrayName(), "ManifoldHarmonicBasis");

  // A spectrum without harmonics (EigenvaluesOnly): the error names the setting to turn off.
  vtkNew<vtkManifoldHarmonicBasis> spectrumOnly;
  spectrumOnly->SetInputConnection(sphere->GetOutputPort());
  spectrumOnly->SetNumberOfHarmonics(5);
  spectrumOnly->EigenvaluesOnlyOn();
  spectrumOnly->Update();
  ok &= ExpectError(spectrumOnly->GetOutput(), "EigenvaluesOnly", "turn EigenvaluesOnly off");

  // Eigenvalues of another basis (m disagrees with the harmonics).
  vtkSmartPointer<vtkPolyData> other = MakeBasis(5);
  vtkNew<vtkPolyData> mismatched;
  mismatched->ShallowCopy(basis);
  vtkNew<vtkFieldData> otherFieldData;
  otherFieldData->AddArray(
    other->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName()));
  mismatched->SetFieldData(otherFieldData);
  ok &= ExpectError(mismatched, vtkManifoldHarmonicBasis::EigenvaluesArrayName(), "5 values");

  // A NaN in the harmonics (a damaged basis file): the error names the basis, not the points.
  vtkNew<vtkPolyData> damaged;
  damaged->DeepCopy(basis);
  damaged->GetPointData()
    ->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName())
    ->SetComponent(7, 3, std::nan(""));
  ok &= ExpectError(damaged, "The basis holds harmonics that are not finite", "a damaged basis");

  // Points without polygons, passed through by the basis without a basis (it warns): the error
  // says why there is no basis instead of asking for the filter that is upstream.
  vtkSmartPointer<vtkPolyData> cloud = LinesOnly(sphere->GetOutput()->GetPoints());
  vtkNew<vtkManifoldHarmonicBasis> passThrough;
  vtkNew<vtkTest::ErrorObserver> basisWarnings;
  passThrough->AddObserver(vtkCommand::WarningEvent, basisWarnings);
  passThrough->SetInputData(cloud);
  passThrough->Update();
  ok &= Check(basisWarnings->GetWarning() &&
      passThrough->GetOutput()->GetNumberOfPoints() == cloud->GetNumberOfPoints(),
    "set-up: the basis passes points without polygons through, with a warning");
  ok &= ExpectError(passThrough->GetOutput(),
    vtkManifoldHarmonicBasis::HarmonicsArrayName(),
    "the input has no polygons or volume cells, so ManifoldHarmonicBasis passed it "
    "through without a basis");
  return ok;
}

//------------------------------------------------------------------------------
// An abort during the transform (after the first of three signals) leaves both outputs empty,
// as VTK's executive has it, not the mesh without coefficients; the next run is complete.
bool TestAbort()
{
  vtkSmartPointer<vtkPolyData> basis = MakeBasis(10);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputData(basis);
  transform->GetPointDataArraySelection()->EnableArray("Height");
  transform->GetPointDataArraySelection()->EnableArray("Colors");
  vtkNew<AbortAtFirstProgress> abort;
  const unsigned long observer = transform->AddObserver(vtkCommand::ProgressEvent, abort);
  transform->Update();
  vtkPolyData* output = transform->GetPolyDataOutput();
  std::cout << "Abort: " << abort->Count << " progress report(s), " << output->GetNumberOfPoints()
            << " points, " << transform->GetSpectrumOutput()->GetNumberOfColumns()
            << " spectrum columns out" << std::endl;
  bool ok = Check(abort->Count == 1, "the transform does not stop when asked to abort");
  ok &= Check(output->GetNumberOfPoints() == 0 && output->GetNumberOfCells() == 0 &&
      output->GetPointData()->GetNumberOfArrays() == 0 &&
      output->GetFieldData()->GetNumberOfArrays() == 0,
    "the output of an aborted transform is not empty");
  ok &= Check(transform->GetSpectrumOutput()->GetNumberOfColumns() == 0,
    "the spectrum of an aborted transform is not empty");
  transform->RemoveObserver(observer);
  transform->AbortExecuteOff();
  transform->Modified();
  transform->Update();
  ok &= Check(transform->GetOutput()->GetNumberOfPoints() == basis->GetNumberOfPoints() &&
      transform->GetOutput()->GetFieldData()->GetArray("Colors_Coefficients") != nullptr,
    "the run after an abort is not complete");
  return ok;
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestManifoldHarmonicTransform(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "NamesAndShapes", TestNamesAndShapes },
      { "DefinitionAndPrecision", TestDefinitionAndPrecision },
      { "SelectionModifies", TestSelectionModifies },
      { "Errors", TestErrors },
      { "Abort", TestAbort },
    });
}
