// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// A basis saved with its mesh and read back is used as it is: vtkManifoldHarmonicBasis output
// written with vtkXMLPolyDataWriter (binary data inline), read with vtkXMLPolyDataReader, then
// vtkManifoldHarmonicTransform and vtkSpectralFilter on the read data give what the in-memory
// pipeline gives, for a double and a float basis (BasisPrecision).

#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkSpectralFilter.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"
#include "vtkTestUtilities.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
using ManifoldHarmonicsTest::Check;
using ManifoldHarmonicsTest::RelativeDifference;

//------------------------------------------------------------------------------
// A unit sphere (double points) with a scalar "Height".
vtkSmartPointer<vtkPolyData> MakeSphere()
{
  return ManifoldHarmonicsTest::SphereWithHeight(24, 16);
}

//------------------------------------------------------------------------------
// Transform (points and Height) and a band-stop filter of a mesh that carries a basis.
struct Downstream
{
  vtkNew<vtkManifoldHarmonicTransform> Transform;
  vtkNew<vtkSpectralFilter> Filter;
  ManifoldHarmonicsTest::Messages Errors;

  explicit Downstream(vtkAlgorithmOutput* basis)
  {
    this->Transform->SetInputConnection(basis);
    this->Transform->GetPointDataArraySelection()->EnableArray("Height");
    this->Filter->SetInputConnection(this->Transform->GetOutputPort());
    this->Filter->SetFilterKindToBandStop();
    this->Filter->SetCutoffUnitsToAbsoluteFrequency();
    this->Filter->SetCutoff(3.0);
    this->Filter->SetUpperCutoff(5.0);
    this->Errors.Observe(this->Transform);
    this->Errors.Observe(this->Filter);
    this->Filter->Update();
  }
  vtkDataArray* Coefficients(const char* name)
  {
    return this->Transform->GetOutput()->GetFieldData()->GetArray(name);
  }
  vtkPolyData* Output() { return vtkPolyData::SafeDownCast(this->Filter->GetOutput()); }
};

//------------------------------------------------------------------------------
// Largest relative difference of the coefficients and the filtered signals of two runs.
double Difference(Downstream& a, Downstream& b)
{
  return std::max({ RelativeDifference(
                      a.Coefficients("Points_Coefficients"), b.Coefficients("Points_Coefficients")),
    RelativeDifference(
      a.Coefficients("Height_Coefficients"), b.Coefficients("Height_Coefficients")),
    RelativeDifference(a.Output()->GetPoints()->GetData(), b.Output()->GetPoints()->GetData()),
    RelativeDifference(a.Output()->GetPointData()->GetArray("Height_Filtered"),
      b.Output()->GetPointData()->GetArray("Height_Filtered")) });
}

//------------------------------------------------------------------------------
// Compute a basis of the given precision, save it, read it back and compare the pipelines.
bool TestRoundTrip(int precision, const std::string& directory, Downstream& doubleReference)
{
  const bool floats = precision == vtkManifoldHarmonicBasis::FLOAT;
  const std::string label = floats ? "float basis" : "double basis";
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(MakeSphere());
  basis->SetNumberOfHarmonics(40);
  basis->SetBasisPrecision(precision);
  Downstream memory(basis->GetOutputPort());

  const std::string file = directory + "/TestBasisReuse" + (floats ? "Float" : "Double") + ".vtp";
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(basis->GetOutputPort());
  writer->SetFileName(file.c_str());
  writer->SetDataModeToBinary(); // inline binary; ParaView 5.11 reads it back
  bool ok = Check(writer->Write() == 1, label + ": cannot write " + file);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkPolyData* read = reader->GetOutput();
  vtkDataArray* harmonics =
    read->GetPointData()->GetArray(vtkManifoldHarmonicBasis::HarmonicsArrayName());
  ok &= Check(floats ? vtkFloatArray::SafeDownCast(harmonics) != nullptr
                     : vtkDoubleArray::SafeDownCast(harmonics) != nullptr,
    label + ": the harmonics read back do not have their precision");
  ok &= Check(harmonics && harmonics->GetNumberOfComponents() == 40 &&
      std::string(harmonics->GetComponentName(39)) == "Phi_39",
    label + ": the harmonics read back lost their components or names");
  ok &= Check(read->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName()) &&
      read->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName()),
    label + ": the mass or the eigenvalues (field data) were not read back");

  Downstream fromFile(reader->GetOutputPort());
  ok &= Check(!fromFile.Errors->GetError() && !memory.Errors->GetError(),
    label + ": the read basis is not accepted: " + fromFile.Errors->GetErrorMessage() +
      memory.Errors->GetErrorMessage());
  const double same = Difference(fromFile, memory);
  const double toDouble = Difference(fromFile, doubleReference);
  std::cout << label << ": read back vs in memory " << same << ", vs the double pipeline "
            << toDouble << std::endl;
  ok &= Check(same <= 1e-12, label + ": the pipeline on the file differs from the one in memory");
  ok &= Check(toDouble <= (floats ? 1e-5 : 1e-12),
    label + ": the pipeline on the file differs from the double one in memory");
  return ok;
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestBasisReuse(int argc, char* argv[])
{
  char* temporary =
    vtkTestUtilities::GetArgOrEnvOrDefault("-T", argc, argv, "VTK_TEMP_DIR", "Testing/Temporary");
  const std::string directory = temporary;
  delete[] temporary;

  // The pipeline on the basis in memory, which the pipeline on the file must reproduce.
  auto roundTrip = [directory](int precision) {
    vtkNew<vtkManifoldHarmonicBasis> basis;
    basis->SetInputData(MakeSphere());
    basis->SetNumberOfHarmonics(40);
    Downstream reference(basis->GetOutputPort());
    return TestRoundTrip(precision, directory, reference);
  };
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "DoubleBasisRoundTrip", [&] { return roundTrip(vtkManifoldHarmonicBasis::DOUBLE); } },
      { "FloatBasisRoundTrip", [&] { return roundTrip(vtkManifoldHarmonicBasis::FLOAT); } },
    });
}
