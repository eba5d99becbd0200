// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSpectralFilter.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkManifoldHarmonicsArrays.h"
#include "vtkManifoldHarmonicsCutoffs.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkManifoldHarmonicsParallel.h"
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

/// The core's FilterKind of a vtkSpectralFilter::FilterKinds value: the checked conversion
/// between the two declarations (the XML's EnumerationDomain is checked against the C++ enum by
/// Testing/ParaView/TestManifoldHarmonicsXMLDefaults.py.in).
/// \throws spectral::InvalidInput for a value that is none of the kinds.
spectral::FilterKind ToFilterKind(int kind)
{
  switch (kind)
  {
    case vtkSpectralFilter::LOW_PASS:
      return spectral::FilterKind::LowPass;
    case vtkSpectralFilter::HIGH_PASS:
      return spectral::FilterKind::HighPass;
    case vtkSpectralFilter::BAND_PASS:
      return spectral::FilterKind::BandPass;
    case vtkSpectralFilter::BAND_STOP:
      return spectral::FilterKind::BandStop;
    case vtkSpectralFilter::ENHANCEMENT:
      return spectral::FilterKind::Enhancement;
    case vtkSpectralFilter::BAND_EXAGGERATION:
      return spectral::FilterKind::BandExaggeration;
    case vtkSpectralFilter::HEAT_DIFFUSION:
      return spectral::FilterKind::HeatDiffusion;
    case vtkSpectralFilter::CUSTOM:
      return spectral::FilterKind::Custom;
    default:
      throw spectral::InvalidInput("FilterKind " + std::to_string(kind) + " is none of the kinds");
  }
}

/// The parameters of the core transfer function, in the filter's CutoffUnits.
spectral::FilterParameters Parameters(vtkSpectralFilter* self)
{
  spectral::FilterParameters parameters;
  parameters.Kind = ToFilterKind(self->GetFilterKind());
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

/// The Nyquist frequency (spectral::NyquistFrequency) of the whole mesh from the
/// vtkManifoldHarmonicsArrays::EdgeSums of this process (ghost cells left out): in a distributed
/// run the sums of all processes are added up (collective).
/// \return 0 when the mesh (on every process) has no triangle of non-zero, finite size.
double NyquistFrequency(vtkMultiProcessController* controller, std::vector<double> sums)
{
  if (controller)
  {
    vtkManifoldHarmonicsParallel::SumOverRanks(controller, sums);
  }
  return spectral::NyquistFrequency(sums[0], sums[1]);
}

/// Mean gain of F over [omega_m, omega_Nyquist], eq. 10 of Vallet and Levy.
double HighFrequencyGain(const spectral::FilterParameters& parameters,
  double nyquist,
  const spectral::Vector& lambda)
{
  if (nyquist <= 0.0)
  {
    throw spectral::InvalidInput(
      "the Nyquist frequency needs a mesh with triangles of non-zero, finite edge length");
  }
  return spectral::MeanGain(parameters, spectral::HighestFrequency(lambda), nyquist);
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
} // anonymous namespace

//------------------------------------------------------------------------------
vtkSpectralFilter::vtkSpectralFilter()
  : ControlPoints(vtkDoubleArray::New())
{
  this->FilterKind = LOW_PASS;
  this->CutoffUnits = FRACTION_OF_HIGHEST;
  this->Cutoff = spectral::DefaultCutoffFraction;
  this->UpperCutoff = 1.0;
  this->Transition = 0.1;
  this->Gain = 2.0;
  this->Time = 0.0;
  this->ReinjectHighFrequencies = true;
  this->ReplaceInput = false;
  this->NumberOfThreads = 0;
  vtkManifoldHarmonicsCutoffs::InitialRanges(this->FrequencyRange, this->TimeRange);
  this->SetNumberOfOutputPorts(2);
  this->ControlPoints->SetNumberOfComponents(2);
  this->AddControlPoint(0.0, 1.0);
  this->AddControlPoint(1.0, 0.0);
}

//------------------------------------------------------------------------------
int vtkSpectralFilter::RequestDataObject(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vtkManifoldHarmonicsArrays::OutputLikeInput(inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkSpectralFilter::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
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
int vtkSpectralFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPointSet* output = vtkPointSet::GetData(outputVector, 0);
  vtkTable* spectrum = vtkTable::GetData(outputVector, 1);
  output->ShallowCopy(input);
  // Collective in a distributed run, so before any return.
  vtkMultiProcessController* controller = vtkManifoldHarmonicsParallel::DistributedController();
  // The Nyquist frequency, for the re-injection and for telling zero eigenvalues in the slider
  // ranges (the edge sums are kept while the input does not change).
  this->UpdateEdgeSums(input);
  const double nyquist = ::NyquistFrequency(controller, { this->EdgeSums[0], this->EdgeSums[1] });
  this->NyquistFrequency = nyquist;
  const bool writeSpectrum = !controller || controller->GetLocalProcessId() == 0;
  if (input->GetNumberOfPoints() == 0)
  {
    if (!controller)
    {
      vtkWarningMacro(<< "No data to filter!");
    }
    return 1;
  }

  vtkManifoldHarmonicsArrays::Basis basis;
  const std::string problem = vtkManifoldHarmonicsArrays::FindBasis(input, basis);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }

  std::vector<FilterJob> jobs;
  const std::string mismatch = FindJobs(this, input, basis, jobs);
  if (!mismatch.empty())
  {
    vtkErrorMacro(<< mismatch);
    return 0;
  }
  this->SetProgressText("Spectral filter");
  try
  {
    const spectral::Vector lambda = basis.EigenvalueVector();
    const double firstNonZero = vtkManifoldHarmonicsCutoffs::FirstNonZeroEigenvalue(lambda, nyquist);
    vtkManifoldHarmonicsCutoffs::SliderRanges(
      lambda, firstNonZero, this->CutoffUnits, this->FrequencyRange, this->TimeRange);
    // The parameters in the filter's units, validated there, then in frequencies.
    const spectral::FilterParameters given = Parameters(this);
    const spectral::FilterParameters parameters = spectral::ToAbsoluteUnits(
      given, vtkManifoldHarmonicsCutoffs::ToFrequencyUnits(this->CutoffUnits), lambda, firstNonZero);
    const spectral::Vector gains = spectral::Gains(parameters, lambda);
    if (writeSpectrum)
    {
      FillSpectrum(lambda, gains, jobs, spectrum);
    }
    if (jobs.empty())
    {
      vtkWarningMacro(<< "Nothing to filter: no '<Array>" << Names::CoefficientsSuffix
                      << "' field data; apply ManifoldHarmonicTransform upstream.");
      return 1;
    }
    const double highFrequencyGain =
      this->ReinjectHighFrequencies ? HighFrequencyGain(parameters, nyquist, lambda) : 0.0;
    vtkManifoldHarmonicsCutoffs::WarnAboutCutoffs(
      this, given, parameters, lambda, nyquist, gains, highFrequencyGain);
    vtkDebugMacro(<< "FilterKind " << this->FilterKind << ", CutoffUnits " << this->CutoffUnits
                  << ", Cutoff " << this->Cutoff << " (frequency " << parameters.Cutoff << ")"
                  << ", UpperCutoff " << this->UpperCutoff << ", Transition " << this->Transition
                  << ", Gain " << this->Gain << ", Time " << this->Time << ", high-frequency gain "
                  << highFrequencyGain);
    const spectral::Vector mass = basis.MassVector();
    for (std::size_t j = 0; j < jobs.size(); ++j)
    {
      // The points no triangle uses (zero mass) keep their input values.
      const vtkManifoldHarmonicsArrays::Signal x(jobs[j].Source);
      const vtkManifoldHarmonicsArrays::Signal coefficients(jobs[j].Coefficients);
      const spectral::RowMatrix y = basis.FilterSignal(
        mass, gains, coefficients.View(), x.View(), highFrequencyGain, this->NumberOfThreads);
      WriteSignal(jobs[j], y, gains.asDiagonal() * coefficients.View(), this->ReplaceInput, output);
      this->UpdateProgress(static_cast<double>(j + 1) / static_cast<double>(jobs.size()));
      if (this->GetAbortExecute())
      {
        // An aborted filter's output is empty (as VTK's executive has it), on both ports.
        output->Initialize();
        spectrum->Initialize();
        return 1;
      }
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Spectral filter failed: " << e.what());
    return 0;
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkSpectralFilter::UpdateEdgeSums(vtkPointSet* input)
{
  // The mesh is walked again only when the input changed (a new upstream execution, or another
  // input object, which may have the same MTime): changing the filter's settings alone re-uses
  // the sums.
  if (input != this->EdgeSumsInput.GetPointer() || input->GetMTime() != this->EdgeSumsTime)
  {
    const std::vector<double> sums = vtkManifoldHarmonicsArrays::EdgeSums(input);
    this->EdgeSums[0] = sums[0];
    this->EdgeSums[1] = sums[1];
    this->EdgeSumsInput = input;
    this->EdgeSumsTime = input->GetMTime();
  }
}

//------------------------------------------------------------------------------
void vtkSpectralFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FilterKind: " << this->FilterKind << " (default 0, LOW_PASS)\n";
  os << indent << "CutoffUnits: " << this->CutoffUnits << " (default 1, FRACTION_OF_HIGHEST)\n";
  os << indent << "Cutoff: " << this->Cutoff << " (default " << spectral::DefaultCutoffFraction
     << ")\n";
  os << indent << "UpperCutoff: " << this->UpperCutoff << " (default 1)\n";
  os << indent << "Transition: " << this->Transition << " (default 0.1)\n";
  os << indent << "Gain: " << this->Gain << " (default 2)\n";
  os << indent << "Time: " << this->Time << " (default 0)\n";
  os << indent << "ControlPoints:";
  for (vtkIdType i = 0; i < this->ControlPoints->GetNumberOfTuples(); ++i)
  {
    os << " (" << this->ControlPoints->GetTypedComponent(i, 0) << ", "
       << this->ControlPoints->GetTypedComponent(i, 1) << ")";
  }
  os << " (default (0, 1) (1, 0))\n";
  os << indent << "ReinjectHighFrequencies: " << (this->ReinjectHighFrequencies ? "On" : "Off")
     << " (default On)\n";
  os << indent << "ReplaceInput: " << (this->ReplaceInput ? "On" : "Off") << " (default Off)\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << " (default 0, all cores)\n";
}
