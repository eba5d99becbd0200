// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicTransform.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkManifoldHarmonicsArrays.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkManifoldHarmonicsParallel.h"
#include "vtkManifoldHarmonicsStages.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include <cmath>
#include <exception>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkManifoldHarmonicTransform);

namespace
{
namespace Names = vtkManifoldHarmonicsNames;

/// A signal to transform: its name in the output and the array holding it.
using NamedSignal = std::pair<std::string, vtkDataArray*>;

void SelectionModified(vtkObject*, unsigned long, void* clientData, void*)
{
  static_cast<vtkManifoldHarmonicTransform*>(clientData)->Modified();
}

bool IsBasisArray(const char* name)
{
  const std::string text(name);
  return text == Names::Harmonics || text == Names::Mass;
}

/// The signals to transform: the coordinates, then the enabled point-data arrays in input order.
std::vector<NamedSignal> SelectSignals(vtkManifoldHarmonicTransform* self, vtkPointSet* input)
{
  std::vector<NamedSignal> signals;
  const bool points = self->GetTransformPoints();
  if (points)
  {
    signals.emplace_back(Names::Points, input->GetPoints()->GetData());
  }
  vtkPointData* pointData = input->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pointData->GetArray(a);
    const char* name = array ? array->GetName() : nullptr;
    if (!name || IsBasisArray(name) || !self->GetPointDataArraySelection()->ArrayIsEnabled(name))
    {
      continue;
    }
    if (points && std::string(name) == Names::Points)
    {
      vtkWarningWithObjectMacro(self,
        << "Point-data array '" << name
        << "' is skipped: its coefficients would replace those of the points.");
      continue;
    }
    signals.emplace_back(name, array);
  }
  return signals;
}

/// Whether the harmonics are finite at the points of non-zero mass (those of the surface).
bool HarmonicsFinite(const vtkManifoldHarmonicsArrays::Basis& basis, const spectral::Vector& mass)
{
  const auto m = static_cast<std::size_t>(basis.NumberOfHarmonics);
  for (vtkIdType i = 0; i < basis.NumberOfPoints; ++i)
  {
    for (std::size_t k = 0; mass[i] != 0.0 && k < m; ++k)
    {
      const std::size_t at = static_cast<std::size_t>(i) * m + k;
      if (!std::isfinite(basis.Doubles ? basis.Doubles[at] : static_cast<double>(basis.Floats[at])))
      {
        return false;
      }
    }
  }
  return true;
}

/// The coefficients of the selected signals summed over the points of this process, which a
/// ghost array may mark as duplicates of another process's points (those count 0).
/// \return An error message, empty on success. \throws what the core throws.
std::string LocalCoefficients(vtkManifoldHarmonicTransform* self,
  vtkPointSet* input,
  std::vector<vtkManifoldHarmonicsParallel::NamedMatrix>& coefficients,
  spectral::Vector& lambda)
{
  vtkManifoldHarmonicsArrays::Basis basis;
  const std::string problem = vtkManifoldHarmonicsArrays::FindBasis(input, basis);
  if (!problem.empty())
  {
    return problem;
  }
  const std::vector<NamedSignal> signals = SelectSignals(self, input);
  self->SetProgressText("Transform");
  lambda = basis.EigenvalueVector();
  const spectral::Vector mass = vtkManifoldHarmonicsStages::OwnedMass(basis, input);
  // A distributed run finishes (its sums are collective); a serial one stops at an abort.
  for (std::size_t s = 0; s < signals.size() && !self->AbortRequested(); ++s)
  {
    coefficients.push_back(
      { Names::Concatenate(signals[s].first.c_str(), Names::CoefficientsSuffix),
        vtkManifoldHarmonicsStages::LocalCoefficients(
          basis, mass, signals[s].second, self->GetNumberOfThreads()) });
    if (!coefficients.back().Values.allFinite())
    {
      // The harmonics themselves (a damaged basis file, whose payload has no checksum), or
      // else the array: points used by no triangle add nothing, so a NaN or infinity on the
      // surface did this.
      if (!HarmonicsFinite(basis, mass))
      {
        return "The basis holds harmonics that are not finite (NaN or infinity) at points of the "
               "surface: a damaged basis (a basis file altered after it was written?). Compute "
               "it again (remove the basis file).";
      }
      return vtkManifoldHarmonicsArrays::NotFiniteOnSurface(
        signals[s].first, "its transform", "Deselect the array");
    }
    self->UpdateProgress(static_cast<double>(s + 1) / static_cast<double>(signals.size()));
  }
  return std::string();
}

/// The spectrum table: Index, Eigenvalue, Frequency and the magnitude of each signal's
/// coefficients.
void FillSpectrum(vtkTable* spectrum,
  const spectral::Vector& lambda,
  const std::vector<vtkManifoldHarmonicsParallel::NamedMatrix>& coefficients)
{
  const std::size_t suffix = std::string(Names::CoefficientsSuffix).size();
  std::vector<vtkManifoldHarmonicsArrays::SpectrumSignal> signals;
  for (const auto& signal : coefficients)
  {
    signals.push_back({ signal.Name.substr(0, signal.Name.size() - suffix), signal.Values });
  }
  vtkManifoldHarmonicsArrays::FillSpectrum(spectrum, lambda, true, nullptr, signals);
}
} // anonymous namespace

//------------------------------------------------------------------------------
vtkManifoldHarmonicTransform::vtkManifoldHarmonicTransform()
  : vtkManifoldHarmonicsAlgorithm(POINT_SET_AND_TABLE)
  , PointDataArraySelection(vtkDataArraySelection::New())
  , SelectionObserver(vtkCallbackCommand::New())
{
  this->TransformPoints = true;
  this->SelectionObserver->SetCallback(&SelectionModified);
  this->SelectionObserver->SetClientData(this);
  this->PointDataArraySelection->AddObserver(vtkCommand::ModifiedEvent, this->SelectionObserver);
}

//------------------------------------------------------------------------------
vtkManifoldHarmonicTransform::~vtkManifoldHarmonicTransform()
{
  this->PointDataArraySelection->RemoveObserver(this->SelectionObserver);
  this->SelectionObserver->Delete();
  this->PointDataArraySelection->Delete();
}

//------------------------------------------------------------------------------
vtkDataArraySelection* vtkManifoldHarmonicTransform::GetPointDataArraySelection()
{
  return this->PointDataArraySelection;
}

//------------------------------------------------------------------------------
vtkTable* vtkManifoldHarmonicTransform::GetSpectrumOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
const char* vtkManifoldHarmonicTransform::CoefficientsSuffix()
{
  return Names::CoefficientsSuffix;
}

//------------------------------------------------------------------------------
const char* vtkManifoldHarmonicTransform::MagnitudeSuffix()
{
  return Names::MagnitudeSuffix;
}

//------------------------------------------------------------------------------
const char* vtkManifoldHarmonicTransform::PointsName()
{
  return Names::Points;
}

//------------------------------------------------------------------------------
const char* vtkManifoldHarmonicTransform::IndexColumnName()
{
  return Names::IndexColumn;
}

//------------------------------------------------------------------------------
const char* vtkManifoldHarmonicTransform::EigenvalueColumnName()
{
  return Names::EigenvalueColumn;
}

//------------------------------------------------------------------------------
const char* vtkManifoldHarmonicTransform::FrequencyColumnName()
{
  return Names::FrequencyColumn;
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicTransform::Execute(vtkPointSet* input,
  vtkPointSet* output,
  vtkTable* spectrum)
{
  output->ShallowCopy(input);
  vtkMultiProcessController* controller = GetDistributedController();
  const bool empty = input->GetNumberOfPoints() == 0;
  if (empty && !controller)
  {
    vtkWarningMacro(<< "No data to transform!");
    return 1;
  }

  // Local sums over the points of this process (all of them in a serial run). An error is
  // reported here and returned after the collective sum below.
  std::vector<vtkManifoldHarmonicsParallel::NamedMatrix> coefficients;
  spectral::Vector lambda;
  std::string problem;
  bool computed =
    empty || this->Guard([&]() { problem = LocalCoefficients(this, input, coefficients, lambda); });

  // Distributed run: every process holds a partial sum; add them up (collective, even on
  // processes without data or with an error, so that no process waits forever).
  if (controller && !vtkManifoldHarmonicsParallel::SumOverRanks(controller, coefficients, lambda))
  {
    problem = "Processes disagree on the number of harmonics or components of the coefficients.";
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
  }
  if (!computed || !problem.empty() || this->AbortRequested())
  {
    return 0;
  }
  // The spectrum table once: on process 0 of a distributed run, whose table ParaView shows.
  if (lambda.size() > 0 && (!controller || controller->GetLocalProcessId() == 0))
  {
    FillSpectrum(spectrum, lambda, coefficients);
  }
  for (const auto& signal :
    empty ? std::vector<vtkManifoldHarmonicsParallel::NamedMatrix>() : coefficients)
  {
    output->GetFieldData()->AddArray(
      vtkManifoldHarmonicsArrays::NewDoubleArray(signal.Values, signal.Name.c_str()));
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicTransform::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TransformPoints: " << (this->TransformPoints ? "On" : "Off") << "\n";
  os << indent << "PointDataArraySelection:";
  for (int a = 0; a < this->PointDataArraySelection->GetNumberOfArrays(); ++a)
  {
    const char* name = this->PointDataArraySelection->GetArrayName(a);
    os << " " << name << (this->PointDataArraySelection->ArrayIsEnabled(name) ? "" : " (off)");
  }
  os << "\n";
}
