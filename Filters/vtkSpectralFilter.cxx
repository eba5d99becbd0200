// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSpectralFilter.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkManifoldHarmonicsArrays.h"
#include "vtkManifoldHarmonicsCutoffs.h"
#include "vtkManifoldHarmonicsEnums.h"
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

#include "Spectral/Common/Defaults.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSpectralFilter);

namespace
{
namespace Names = vtkManifoldHarmonicsNames;

/// A signal to filter: its name, its coefficients and the array it was computed from, which
/// may be the points or the input's normals (GetNormals()).
struct FilterJob
{
  std::string Name;
  vtkDataArray* Coefficients;
  vtkDataArray* Source;
  bool IsPoints;
  bool IsNormals;
};

/// The signals to filter: every <Signal>_Coefficients field array whose signal is on the input.
/// \return An error message if coefficients disagree with the basis or their signal.
std::string FindJobs(vtkSpectralFilter* self,
  vtkPointSet* input,
  const vtkManifoldHarmonicsArrays::Basis& basis,
  std::vector<FilterJob>& jobs)
{
  const std::string suffix = Names::CoefficientsSuffix;
  vtkFieldData* fieldData = input->GetFieldData();
  for (int a = 0; a < fieldData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* coefficients = fieldData->GetArray(a);
    const std::string arrayName =
      coefficients && coefficients->GetName() ? coefficients->GetName() : "";
    if (arrayName.size() <= suffix.size() ||
      arrayName.compare(arrayName.size() - suffix.size(), suffix.size(), suffix) != 0)
    {
      continue;
    }
    const std::string name = arrayName.substr(0, arrayName.size() - suffix.size());
    const bool isPoints = name == Names::Points;
    vtkDataArray* source =
      isPoints ? input->GetPoints()->GetData() : input->GetPointData()->GetArray(name.c_str());
    if (!source)
    {
      vtkWarningWithObjectMacro(self,
        << "Coefficients '" << arrayName << "' skipped: no point-data array '" << name << "'.");
      continue;
    }
    if (coefficients->GetNumberOfTuples() != basis.NumberOfHarmonics ||
      coefficients->GetNumberOfComponents() != source->GetNumberOfComponents())
    {
      return "Coefficients '" + arrayName + "' have " +
        std::to_string(coefficients->GetNumberOfTuples()) + " x " +
        std::to_string(coefficients->GetNumberOfComponents()) + " values where " +
        std::to_string(basis.NumberOfHarmonics) + " x " +
        std::to_string(source->GetNumberOfComponents()) +
        " are expected: recompute them with ManifoldHarmonicTransform.";
    }
    const bool isNormals = !isPoints && source == input->GetPointData()->GetNormals();
    jobs.push_back({ name, coefficients, source, isPoints, isNormals });
  }
  return std::string();
}

/// The parameters of the core transfer function, in the filter's CutoffUnits.
spectral::FilterParameters Parameters(vtkSpectralFilter* self)
{
  spectral::FilterParameters parameters;
  parameters.Kind = vtkManifoldHarmonicsEnums::To(
    vtkManifoldHarmonicsEnums::FilterKind, self->GetFilterKind(), "FilterKind");
  parameters.Cutoff = self->GetCutoff();
  parameters.UpperCutoff = self->GetUpperCutoff();
  parameters.Transition = self->GetTransition();
  parameters.Gain = self->GetGain();
  parameters.Time = self->GetTime();
  for (int i = 0; i < self->GetNumberOfControlPoints(); ++i)
  {
    double point[2];
    self->GetControlPoint(i, point);
    parameters.ControlPoints.emplace_back(point[0], point[1]);
  }
  return parameters;
}

/// The spectrum table: Index, Frequency, Gain, then the magnitudes before and after filtering.
void FillSpectrum(const spectral::Vector& lambda,
  const spectral::Vector& gains,
  const std::vector<FilterJob>& jobs,
  vtkTable* spectrum)
{
  std::vector<vtkManifoldHarmonicsArrays::SpectrumSignal> signals;
  for (const FilterJob& job : jobs)
  {
    signals.push_back({ job.Name, vtkManifoldHarmonicsArrays::Signal(job.Coefficients).View() });
  }
  vtkManifoldHarmonicsArrays::FillSpectrum(spectrum, lambda, false, &gains, signals);
}

/// The rows of `values` scaled to unit length (rows of zero length stay zero).
spectral::RowMatrix UnitRows(const spectral::RowMatrix& values)
{
  spectral::RowMatrix unit = values;
  for (Eigen::Index i = 0; i < unit.rows(); ++i)
  {
    const double length = unit.row(i).norm();
    if (length > 0.0)
    {
      unit.row(i) /= length;
    }
  }
  return unit;
}

/// Store a filtered signal: new points, or a new or replacing point-data array. The
/// coefficients of a replaced signal become those of the filtered one.
void WriteSignal(const FilterJob& job,
  const spectral::RowMatrix& values,
  const spectral::RowMatrix& filteredCoefficients,
  bool replaceInput,
  vtkPointSet* output)
{
  const bool replace = job.IsPoints || replaceInput;
  const std::string name =
    replace ? job.Name : Names::Concatenate(job.Name.c_str(), Names::FilteredSuffix);
  const char* arrayName = job.IsPoints ? job.Source->GetName() : name.c_str();
  // Filtered normals (of the array the input marks as its normals) are normals again: unit
  // length, whether they replace the input's or are added as <Normals>_Filtered.
  const bool normals = job.IsNormals && values.cols() == 3;
  vtkSmartPointer<vtkDataArray> filtered = vtkManifoldHarmonicsArrays::NewArrayLike(
    job.Source, normals ? UnitRows(values) : values, arrayName);
  if (job.IsPoints)
  {
    vtkNew<vtkPoints> points;
    points->SetData(filtered);
    output->SetPoints(points);
  }
  else
  {
    output->GetPointData()->AddArray(filtered);
  }
  if (replace)
  {
    output->GetFieldData()->AddArray(vtkManifoldHarmonicsArrays::NewDoubleArray(
      filteredCoefficients, job.Coefficients->GetName()));
  }
}
/// Filters each job's signal and writes it onto the output, until an abort.
void FilterSignals(vtkSpectralFilter* self,
  const vtkManifoldHarmonicsArrays::Basis& basis,
  const spectral::Vector& gains,
  double highFrequencyGain,
  const std::vector<FilterJob>& jobs,
  vtkPointSet* output)
{
  const spectral::Vector mass = basis.MassVector();
  for (std::size_t j = 0; j < jobs.size() && !self->AbortRequested(); ++j)
  {
    // The points no triangle uses (zero mass) keep their input values.
    const vtkManifoldHarmonicsArrays::Signal x(jobs[j].Source);
    const vtkManifoldHarmonicsArrays::Signal coefficients(jobs[j].Coefficients);
    const spectral::RowMatrix y = basis.FilterSignal(
      mass, gains, coefficients.View(), x.View(), highFrequencyGain, self->GetNumberOfThreads());
    WriteSignal(
      jobs[j], y, gains.asDiagonal() * coefficients.View(), self->GetReplaceInput(), output);
    self->UpdateProgress(static_cast<double>(j + 1) / static_cast<double>(jobs.size()));
  }
}
} // anonymous namespace

//------------------------------------------------------------------------------
vtkSpectralFilter::vtkSpectralFilter()
  : vtkManifoldHarmonicsAlgorithm(POINT_SET_AND_TABLE)
  , ControlPoints(vtkDoubleArray::New())
  , MeshFigures(new vtkManifoldHarmonicsArrays::MeshFiguresCache)
{
  // The core's defaults (spectral::FilterParameters), in the default units (relative cutoffs).
  const spectral::FilterParameters defaults;
  this->FilterKind = LOW_PASS;
  this->CutoffUnits = FRACTION_OF_HIGHEST;
  this->Cutoff = spectral::DefaultCutoffFraction;
  this->UpperCutoff = spectral::DefaultUpperCutoffFraction;
  this->Transition = defaults.Transition;
  this->Gain = defaults.Gain;
  this->Time = defaults.Time;
  this->ReinjectHighFrequencies = true;
  this->ReplaceInput = false;
  vtkManifoldHarmonicsCutoffs::InitialRanges(this->FrequencyRange, this->TimeRange);
  this->ControlPoints->SetNumberOfComponents(2);
  this->AddControlPoint(0.0, 1.0);
  this->AddControlPoint(1.0, 0.0);
}

//------------------------------------------------------------------------------
vtkTable* vtkSpectralFilter::GetSpectrumOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
const char* vtkSpectralFilter::GainColumnName()
{
  return Names::GainColumn;
}

//------------------------------------------------------------------------------
vtkSpectralFilter::~vtkSpectralFilter()
{
  this->ControlPoints->Delete();
}

//------------------------------------------------------------------------------
const char* vtkSpectralFilter::FilteredSuffix()
{
  return Names::FilteredSuffix;
}

//------------------------------------------------------------------------------
void vtkSpectralFilter::SetNumberOfControlPoints(int count)
{
  count = std::max(count, 0);
  const vtkIdType old = this->ControlPoints->GetNumberOfTuples();
  if (count == old)
  {
    return;
  }
  this->ControlPoints->Resize(count);
  this->ControlPoints->SetNumberOfTuples(count);
  for (vtkIdType i = old; i < count; ++i)
  {
    this->ControlPoints->SetTypedComponent(i, 0, 0.0);
    this->ControlPoints->SetTypedComponent(i, 1, 1.0);
  }
  this->Modified();
}

//------------------------------------------------------------------------------
int vtkSpectralFilter::GetNumberOfControlPoints()
{
  return static_cast<int>(this->ControlPoints->GetNumberOfTuples());
}

//------------------------------------------------------------------------------
void vtkSpectralFilter::SetControlPoint(int index, double omega, double gain)
{
  if (index < 0 || index >= this->GetNumberOfControlPoints())
  {
    vtkErrorMacro(<< "Control point " << index << " out of range [0, "
                  << this->GetNumberOfControlPoints() << ").");
    return;
  }
  if (this->ControlPoints->GetTypedComponent(index, 0) == omega &&
    this->ControlPoints->GetTypedComponent(index, 1) == gain)
  {
    return;
  }
  this->ControlPoints->SetTypedComponent(index, 0, omega);
  this->ControlPoints->SetTypedComponent(index, 1, gain);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkSpectralFilter::GetControlPoint(int index, double point[2])
{
  if (index < 0 || index >= this->GetNumberOfControlPoints())
  {
    vtkErrorMacro(<< "Control point " << index << " out of range [0, "
                  << this->GetNumberOfControlPoints() << ").");
    return;
  }
  this->ControlPoints->GetTypedTuple(index, point);
}

//------------------------------------------------------------------------------
void vtkSpectralFilter::AddControlPoint(double omega, double gain)
{
  const double point[2] = { omega, gain };
  this->ControlPoints->InsertNextTypedTuple(point);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkSpectralFilter::RemoveAllControlPoints()
{
  if (this->ControlPoints->GetNumberOfTuples() > 0)
  {
    this->ControlPoints->SetNumberOfTuples(0);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkSpectralFilter::Execute(vtkPointSet* input, vtkPointSet* output, vtkTable* spectrum)
{
  output->ShallowCopy(input);
  // Collective in a distributed run, so before any return: the Nyquist frequency, for the
  // re-injection and for telling zero eigenvalues in the slider ranges.
  vtkMultiProcessController* controller = GetDistributedController();
  this->NyquistFrequency =
    vtkManifoldHarmonicsStages::NyquistFrequency(controller, this->MeshFigures->Of(input).EdgeSums);
  if (input->GetNumberOfPoints() == 0)
  {
    if (!controller)
    {
      vtkWarningMacro(<< "No data to filter!");
    }
    return 1;
  }
  vtkManifoldHarmonicsArrays::Basis basis;
  std::vector<FilterJob> jobs;
  std::string problem = vtkManifoldHarmonicsArrays::FindBasis(input, basis);
  problem = problem.empty() ? FindJobs(this, input, basis, jobs) : problem;
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  this->SetProgressText("Spectral filter");
  const spectral::Vector lambda = basis.EigenvalueVector();
  vtkManifoldHarmonicsCutoffs::SliderRanges(lambda,
    vtkManifoldHarmonicsCutoffs::FirstNonZeroEigenvalue(lambda, this->NyquistFrequency),
    this->CutoffUnits,
    this->FrequencyRange,
    this->TimeRange);
  const vtkManifoldHarmonicsStages::Design design = vtkManifoldHarmonicsStages::DesignFilter(
    Parameters(this), this->CutoffUnits, lambda, this->NyquistFrequency);
  if (!controller || controller->GetLocalProcessId() == 0)
  {
    FillSpectrum(design.Lambda, design.Gains, jobs, spectrum);
  }
  if (jobs.empty())
  {
    vtkWarningMacro(<< "Nothing to filter: no '<Array>" << Names::CoefficientsSuffix
                    << "' field data; apply ManifoldHarmonicTransform upstream.");
    return 1;
  }
  vtkDebugMacro(<< "FilterKind " << this->FilterKind << ", CutoffUnits " << this->CutoffUnits
                << ", Cutoff " << this->Cutoff << " (frequency " << design.Parameters.Cutoff
                << ")");
  FilterSignals(this,
    basis,
    design.Gains,
    vtkManifoldHarmonicsStages::ReinjectionGain(
      this, design, this->NyquistFrequency, this->ReinjectHighFrequencies),
    jobs,
    output);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSpectralFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  namespace Enums = vtkManifoldHarmonicsEnums;
  os << indent << "FilterKind: " << Enums::Name(Enums::FilterKind, this->FilterKind) << "\n";
  os << indent << "CutoffUnits: " << Enums::Name(Enums::CutoffUnits, this->CutoffUnits) << "\n";
  os << indent << "Cutoff: " << this->Cutoff << "\n";
  os << indent << "UpperCutoff: " << this->UpperCutoff << "\n";
  os << indent << "Transition: " << this->Transition << "\n";
  os << indent << "Gain: " << this->Gain << "\n";
  os << indent << "Time: " << this->Time << "\n";
  os << indent << "ControlPoints:";
  for (vtkIdType i = 0; i < this->ControlPoints->GetNumberOfTuples(); ++i)
  {
    os << " (" << this->ControlPoints->GetTypedComponent(i, 0) << ", "
       << this->ControlPoints->GetTypedComponent(i, 1) << ")";
  }
  os << "\n";
  os << indent << "ReinjectHighFrequencies: " << (this->ReinjectHighFrequencies ? "On" : "Off")
     << "\n";
  os << indent << "ReplaceInput: " << (this->ReplaceInput ? "On" : "Off") << "\n";
  os << indent << "NyquistFrequency: " << this->NyquistFrequency << "\n";
}
