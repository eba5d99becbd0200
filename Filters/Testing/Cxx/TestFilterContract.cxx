// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The contract every filter of the module keeps (vtkManifoldHarmonicsAlgorithm):
// - after an error, every output port is empty and the request fails with one error message;
// - after an abort, every output port is empty and the request succeeds without an error; the
//   next request runs whole;
// - the output has the input's type, the table port a vtkTable;
// - NumberOfThreads is every filter's, 0 by default; PrintSelf prints the values (enumerated
//   ones by their names);
// - a setting set to NaN is refused with an error when the filter runs.
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicSmoothing.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkManifoldHarmonicsAlgorithm.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSpectralDescriptors.h"
#include "vtkSpectralFilter.h"
#include "vtkTable.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"

#include "ManifoldHarmonicsTestUtilities.h"

#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using ManifoldHarmonicsTest::Check;

//------------------------------------------------------------------------------
// Updates `filter`: whether the request succeeded.
bool Run(vtkAlgorithm* filter)
{
  return filter->GetExecutive()->Update() != 0;
}

//------------------------------------------------------------------------------
// One filter of each kind, fresh.
std::vector<vtkSmartPointer<vtkManifoldHarmonicsAlgorithm>> AllFilters()
{
  return { vtkSmartPointer<vtkManifoldHarmonicBasis>::New(),
    vtkSmartPointer<vtkManifoldHarmonicTransform>::New(),
    vtkSmartPointer<vtkSpectralFilter>::New(),
    vtkSmartPointer<vtkManifoldHarmonicSmoothing>::New(),
    vtkSmartPointer<vtkSpectralDescriptors>::New() };
}

//------------------------------------------------------------------------------
// Whether every output port of `filter` is empty: no points on port 0, no rows on port 1.
bool OutputsEmpty(vtkManifoldHarmonicsAlgorithm* filter)
{
  bool empty = vtkPointSet::SafeDownCast(filter->GetOutputDataObject(0))->GetNumberOfPoints() == 0;
  if (filter->GetNumberOfOutputPorts() > 1)
  {
    vtkTable* table = vtkTable::SafeDownCast(filter->GetOutputDataObject(1));
    empty = empty && table && table->GetNumberOfRows() == 0 && table->GetNumberOfColumns() == 0;
  }
  return empty;
}

//------------------------------------------------------------------------------
// A sphere with its basis, coefficients of the points and a filtered copy: a valid input for
// every filter, after which a failing one must not keep the previous output.
vtkSmartPointer<vtkPolyData> SphereWithCoefficients()
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(ManifoldHarmonicsTest::UnitSphere(16, 12));
  basis->SetNumberOfHarmonics(12);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputConnection(basis->GetOutputPort());
  transform->Update();
  return vtkPolyData::SafeDownCast(transform->GetOutputDataObject(0));
}

//------------------------------------------------------------------------------
// Each filter on a good input, then on one it refuses (the basis: an unstructured grid mixing
// a triangle and a tetrahedron; the others: a sphere without a basis, or with a basis of
// constant harmonics only for the smoothing): the request fails with an error and every port is
// empty, not the input passed on or the last output kept.
bool ErrorsEmptyEveryPort()
{
  vtkSmartPointer<vtkPolyData> good = SphereWithCoefficients();
  vtkNew<vtkUnstructuredGrid> mixed;
  vtkNew<vtkPoints> points;
  for (double p : { 0.0, 1.0, 2.0, 3.0 })
  {
    points->InsertNextPoint(p == 1.0 ? 1.0 : 0.0, p == 2.0 ? 1.0 : 0.0, p == 3.0 ? 1.0 : 0.0);
  }
  mixed->SetPoints(points);
  const vtkIdType triangle[3] = { 0, 1, 2 };
  const vtkIdType tetrahedron[4] = { 0, 1, 2, 3 };
  mixed->InsertNextCell(VTK_TRIANGLE, 3, triangle);
  mixed->InsertNextCell(VTK_TETRA, 4, tetrahedron);
  vtkSmartPointer<vtkPolyData> bare = ManifoldHarmonicsTest::UnitSphere(16, 12);

  bool ok = true;
  for (const auto& filter : AllFilters())
  {
    const std::string name = filter->GetClassName();
    if (auto* smoothing = vtkManifoldHarmonicSmoothing::SafeDownCast(filter))
    {
      smoothing->SetNumberOfHarmonics(12);
    }
    filter->SetInputDataObject(
      name == "vtkManifoldHarmonicBasis" ? static_cast<vtkDataObject*>(bare) : good);
    ok &= Check(Run(filter) && !OutputsEmpty(filter), name + " runs on a good input");
    vtkNew<vtkTest::ErrorObserver> errors;
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    vtkNew<vtkTest::ErrorObserver> executiveErrors; // "returned failure for request"
    filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, executiveErrors);
    vtkDataObject* refused = bare;
    if (name == "vtkManifoldHarmonicBasis")
    {
      refused = mixed;
    }
    else if (name == "vtkManifoldHarmonicSmoothing")
    {
      vtkManifoldHarmonicSmoothing::SafeDownCast(filter)->SetNumberOfHarmonics(1);
    }
    filter->SetInputDataObject(refused);
    const bool succeeded = Run(filter);
    ok &= Check(!succeeded && errors->GetError(), name + " fails with an error");
    ok &= Check(OutputsEmpty(filter), name + " leaves every output port empty after an error");
  }
  return ok;
}

//------------------------------------------------------------------------------
// Each filter asked to abort at its first progress report: the request succeeds without an
// error and every port is empty; the next request runs whole (VTK 9.2 leaves AbortExecute set).
bool AbortsEmptyEveryPort()
{
  vtkSmartPointer<vtkPolyData> good = SphereWithCoefficients();
  bool ok = true;
  for (const auto& filter : AllFilters())
  {
    const std::string name = filter->GetClassName();
    filter->SetInputDataObject(good);
    vtkNew<vtkTest::ErrorObserver> errors;
    filter->AddObserver(vtkCommand::ErrorEvent, errors);
    vtkNew<vtkCallbackCommand> abort;
    abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
      { vtkAlgorithm::SafeDownCast(caller)->AbortExecuteOn(); });
    const unsigned long observer = filter->AddObserver(vtkCommand::ProgressEvent, abort);
    const bool succeeded = Run(filter);
    ok &= Check(succeeded && !errors->GetError(), name + " succeeds without an error on abort");
    ok &= Check(OutputsEmpty(filter), name + " leaves every output port empty after an abort");
    // The abort stopped that request only: the next one runs whole (without AbortExecuteOff,
    // and without a change of setting: the emptied output is not kept as up to date).
    filter->RemoveObserver(observer);
    ok &= Check(Run(filter) && !OutputsEmpty(filter), name + " runs whole after an abort");
  }
  // Downstream too: the basis aborted under a transform; the transform's next update runs both.
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(ManifoldHarmonicsTest::UnitSphere(16, 12));
  basis->SetNumberOfHarmonics(12);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputConnection(basis->GetOutputPort());
  vtkNew<vtkTest::ErrorObserver> transformErrors; // its message about the missing basis
  transform->AddObserver(vtkCommand::ErrorEvent, transformErrors);
  transform->AddObserver(vtkCommand::WarningEvent, transformErrors);
  vtkNew<vtkTest::ErrorObserver> executiveErrors;
  transform->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, executiveErrors);
  vtkNew<vtkCallbackCommand> abort;
  abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
    { vtkAlgorithm::SafeDownCast(caller)->AbortExecuteOn(); });
  const unsigned long observer = basis->AddObserver(vtkCommand::ProgressEvent, abort);
  Run(transform);
  ok &= Check(OutputsEmpty(basis), "the basis under a transform is empty after an abort");
  basis->RemoveObserver(observer);
  ok &= Check(Run(transform), "the transform's next update succeeds");
  ok &= Check(!OutputsEmpty(basis), "the transform's next update runs the aborted basis again");
  ok &= Check(!OutputsEmpty(transform), "the transform's next update runs the transform again");
  return ok;
}

//------------------------------------------------------------------------------
// The output of each filter has the input's type; the table port holds a vtkTable.
bool OutputLikeInput()
{
  vtkSmartPointer<vtkPolyData> good = SphereWithCoefficients();
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(good->GetPoints());
  grid->GetPointData()->ShallowCopy(good->GetPointData());
  grid->GetFieldData()->ShallowCopy(good->GetFieldData());
  vtkCellArray* polys = good->GetPolys();
  grid->SetCells(VTK_TRIANGLE, polys);
  bool ok = true;
  for (const auto& filter : AllFilters())
  {
    const std::string name = filter->GetClassName();
    if (auto* smoothing = vtkManifoldHarmonicSmoothing::SafeDownCast(filter))
    {
      smoothing->SetNumberOfHarmonics(12);
    }
    filter->SetInputDataObject(grid);
    Run(filter);
    ok &= Check(vtkUnstructuredGrid::SafeDownCast(filter->GetOutputDataObject(0)) != nullptr,
      name + " gives an unstructured grid for an unstructured grid");
    if (filter->GetNumberOfOutputPorts() > 1)
    {
      ok &= Check(vtkTable::SafeDownCast(filter->GetOutputDataObject(1)) != nullptr,
        name + " has a table on port 1");
    }
  }
  return ok;
}

//------------------------------------------------------------------------------
// Every filter has NumberOfThreads (0 by default) and prints its values with the names of
// enumerated settings.
bool SharedSettingsAndPrintSelf()
{
  bool ok = true;
  for (const auto& filter : AllFilters())
  {
    ok &= Check(filter->GetNumberOfThreads() == 0,
      std::string(filter->GetClassName()) + ": NumberOfThreads 0 by default");
    filter->SetNumberOfThreads(3);
    std::ostringstream text;
    filter->Print(text);
    ok &= Check(text.str().find("NumberOfThreads: 3") != std::string::npos,
      std::string(filter->GetClassName()) + " prints NumberOfThreads");
  }
  vtkNew<vtkSpectralFilter> filter;
  filter->SetFilterKindToHeatDiffusion();
  filter->SetCutoffUnitsToHarmonicIndex();
  std::ostringstream filterText;
  filter->Print(filterText);
  ok &= Check(filterText.str().find("FilterKind: Heat Diffusion") != std::string::npos &&
      filterText.str().find("CutoffUnits: Harmonic Index") != std::string::npos,
    "the spectral filter prints its kind and units by name:\n" + filterText.str());
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetMassMatrixToConsistent();
  std::ostringstream basisText;
  basis->Print(basisText);
  ok &= Check(basisText.str().find("MassMatrix: Consistent") != std::string::npos,
    "the basis prints its mass matrix by name");
  vtkNew<vtkSpectralDescriptors> descriptors;
  descriptors->SetDistanceKindToDiffusion();
  std::ostringstream descriptorsText;
  descriptors->Print(descriptorsText);
  ok &= Check(descriptorsText.str().find("DistanceKind: Diffusion") != std::string::npos,
    "the descriptors print their distance kind by name");
  return ok;
}

//------------------------------------------------------------------------------
// A setting set to NaN (which vtkSetClampMacro lets through) makes the request fail with an error
// that names it, and every port empty: never a run with a NaN tolerance, limit or cutoff.
bool NotANumberRefused()
{
  vtkSmartPointer<vtkPolyData> good = SphereWithCoefficients();
  vtkSmartPointer<vtkPolyData> bare = ManifoldHarmonicsTest::UnitSphere(16, 12);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Setting
  {
    std::string Name;
    std::function<void(vtkManifoldHarmonicsAlgorithm*)> Set;
  };
  const auto basis = [](vtkManifoldHarmonicsAlgorithm* f)
  { return vtkManifoldHarmonicBasis::SafeDownCast(f); };
  const auto smoothing = [](vtkManifoldHarmonicsAlgorithm* f)
  { return vtkManifoldHarmonicSmoothing::SafeDownCast(f); };
  const std::vector<std::pair<std::string, std::vector<Setting>>> cases = {
    { "vtkManifoldHarmonicBasis",
      { { "Tolerance", [&](vtkManifoldHarmonicsAlgorithm* f) { basis(f)->SetTolerance(nan); } },
        { "SeamTolerance",
          [&](vtkManifoldHarmonicsAlgorithm* f) { basis(f)->SetSeamTolerance(nan); } },
        { "MemoryLimit",
          [&](vtkManifoldHarmonicsAlgorithm* f) { basis(f)->SetMemoryLimit(nan); } } } },
    { "vtkManifoldHarmonicSmoothing",
      { { "CutoffFraction",
          [&](vtkManifoldHarmonicsAlgorithm* f) { smoothing(f)->SetCutoffFraction(nan); } },
        { "SeamTolerance",
          [&](vtkManifoldHarmonicsAlgorithm* f) { smoothing(f)->SetSeamTolerance(nan); } },
        { "MemoryLimit",
          [&](vtkManifoldHarmonicsAlgorithm* f) { smoothing(f)->SetMemoryLimit(nan); } } } },
  };
  bool ok = true;
  for (const auto& filterCase : cases)
  {
    for (const Setting& setting : filterCase.second)
    {
      vtkSmartPointer<vtkManifoldHarmonicsAlgorithm> filter;
      for (const auto& candidate : AllFilters())
      {
        filter = filterCase.first == candidate->GetClassName() ? candidate : filter;
      }
      const std::string what = filterCase.first + " with " + setting.Name + " NaN";
      if (auto* smooth = smoothing(filter))
      {
        smooth->SetNumberOfHarmonics(12);
      }
      filter->SetInputDataObject(
        filterCase.first == "vtkManifoldHarmonicBasis" ? static_cast<vtkDataObject*>(bare) : good);
      ok &= Check(Run(filter) && !OutputsEmpty(filter), what + ": runs before it is set");
      vtkNew<vtkTest::ErrorObserver> errors;
      filter->AddObserver(vtkCommand::ErrorEvent, errors);
      vtkNew<vtkTest::ErrorObserver> executiveErrors;
      filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, executiveErrors);
      setting.Set(filter);
      const bool succeeded = Run(filter);
      ok &= Check(!succeeded && errors->CheckErrorMessage(setting.Name + " is NaN") == 0,
        what + ": no error naming it");
      ok &= Check(OutputsEmpty(filter), what + ": an output port is not empty");
    }
  }
  return ok;
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestFilterContract(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "ErrorsEmptyEveryPort", ErrorsEmptyEveryPort },
      { "AbortsEmptyEveryPort", AbortsEmptyEveryPort },
      { "OutputLikeInput", OutputLikeInput },
      { "SharedSettingsAndPrintSelf", SharedSettingsAndPrintSelf },
      { "NotANumberRefused", NotANumberRefused },
    });
}
