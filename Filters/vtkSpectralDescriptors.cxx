// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSpectralDescriptors.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkManifoldHarmonicsArrays.h"
#include "vtkManifoldHarmonicsEnums.h"
#include "vtkManifoldHarmonicsGhosts.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkManifoldHarmonicsParallel.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include "Spectral/Common/Eigenvalues.h"
#include "Spectral/Filtering/Descriptors.h"
#include "Spectral/Operators/Operators.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSpectralDescriptors);

namespace
{
/// A point-data array to add: its name, its values (n by c) and its component labels.
struct Descriptor
{
  const char* Name;
  spectral::RowMatrix Values;
  std::vector<std::string> Components;
};

/// The sums over the surface (volume) of this process: the area (volume) (the mass of the points
/// it owns, see vtkManifoldHarmonicsGhosts), the edge sums of its cells and 1 if they are a
/// volume (`figures`), in that order; in a distributed run added over all processes
/// (collective), so that they are the whole mesh's. An input without the mass array adds no area
/// (FindBasis reports it).
std::vector<double> SurfaceSums(vtkMultiProcessController* controller,
  vtkPointSet* input,
  const vtkManifoldHarmonicsArrays::MeshFigures& figures)
{
  std::vector<double> sums = {
    0.0, figures.EdgeSums[0], figures.EdgeSums[1], figures.IsVolume ? 1.0 : 0.0
  };
  vtkDataArray* mass = input->GetPointData()->GetArray(vtkManifoldHarmonicsNames::Mass);
  if (mass && mass->GetNumberOfTuples() == input->GetNumberOfPoints())
  {
    sums[0] = vtkManifoldHarmonicsArrays::Signal(mass).View().col(0).dot(
      vtkManifoldHarmonicsGhosts::OwnedPoints(input));
  }
  if (controller)
  {
    vtkManifoldHarmonicsParallel::SumOverRanks(controller, sums);
  }
  return sums;
}

/// The dimension of the mesh whose SurfaceSums are `sums`: 3 for a volume, else 2.
int Dimension(const std::vector<double>& sums)
{
  return sums[3] > 0.0 ? 3 : 2;
}

/// The eigenvalues with the module's rule for zero ones (Spectral/Common/Eigenvalues.h), on the
/// scale of the Nyquist frequency from the EdgeSums of the whole surface (`sums` of SurfaceSums).
spectral::Spectrum ToSpectrum(const spectral::Vector& lambda, const std::vector<double>& sums)
{
  const double nyquist = spectral::NyquistFrequency(sums[1], sums[2]);
  if (sums[2] > 0.0 && !(nyquist > 0.0))
  {
    throw spectral::InvalidInput(
      "the Nyquist frequency needs a mesh with triangles of non-zero, finite edge length");
  }
  spectral::Spectrum spectrum;
  spectrum.Lambda = lambda;
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
  {
    spectrum.NonZero.push_back(!spectral::IsZeroEigenvalue(lambda[k], nyquist * nyquist));
  }
  return spectrum;
}

/// f(view) on the harmonics in place, as doubles or floats (the basis' own precision).
template<typename Function>
auto OnBasis(const vtkManifoldHarmonicsArrays::Basis& basis, const Function& f)
{
  if (basis.Floats)
  {
    return f(spectral::FloatBasisView(basis.Floats, basis.NumberOfPoints, basis.NumberOfHarmonics));
  }
  return f(spectral::BasisView(basis.Doubles, basis.NumberOfPoints, basis.NumberOfHarmonics));
}

/// Component labels "<prefix><value>" for a list of times or energies.
std::vector<std::string> Labels(const char* prefix, const spectral::Vector& values)
{
  std::vector<std::string> labels;
  for (Eigen::Index j = 0; j < values.size(); ++j)
  {
    char text[64];
    std::snprintf(text, sizeof(text), "%s%.4g", prefix, values[j]);
    labels.emplace_back(text);
  }
  return labels;
}

/// The array of a descriptor, NaN at the points of zero mass (no harmonics there).
vtkSmartPointer<vtkDoubleArray> ToArray(Descriptor& descriptor, const spectral::Vector& mass)
{
  for (Eigen::Index i = 0; i < mass.size(); ++i)
  {
    if (!(mass[i] > 0.0))
    {
      descriptor.Values.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }
  auto array = vtkManifoldHarmonicsArrays::NewDoubleArray(descriptor.Values, descriptor.Name);
  for (std::size_t c = 0; c < descriptor.Components.size(); ++c)
  {
    array->SetComponentName(static_cast<vtkIdType>(c), descriptor.Components[c].c_str());
  }
  return array;
}

/// Warns when the harmonics miss more than 1% of the heat trace at time t (Weyl estimate for the
/// area or volume `measure` of dimension 2 or 3).
void WarnTruncation(vtkSpectralDescriptors* self,
  const spectral::Spectrum& spectrum,
  double measure,
  int dimension,
  double time,
  vtkIdType points,
  const char* what)
{
  const int needed = spectral::HeatKernelHarmonicsNeeded(spectrum, measure, dimension, time);
  if (needed > spectrum.Lambda.size())
  {
    std::ostringstream count;
    count << "about " << needed;
    vtkWarningWithObjectMacro(self,
      << what << " at time " << time << " needs "
      << (needed >= points ? std::string("every harmonic") : count.str())
      << " for a truncation error below 1% of the heat trace (Weyl estimate); the basis has "
      << spectrum.Lambda.size() << ". Compute more harmonics or use larger times.");
  }
}

/// The source point of the distance, or -1 after an error.
vtkIdType FindSource(vtkSpectralDescriptors* self, vtkPointSet* input, const spectral::Vector& mass)
{
  vtkIdType source = self->GetSourcePoint();
  if (self->GetUseSourceLocation())
  {
    source = input->FindPoint(self->GetSourceLocation());
  }
  else if (source < 0 || source >= input->GetNumberOfPoints())
  {
    vtkErrorWithObjectMacro(self,
      << "SourcePoint " << source << " is outside the point ids [0, " << input->GetNumberOfPoints()
      << ").");
    return -1;
  }
  if (source < 0 || !(mass[source] > 0.0))
  {
    vtkErrorWithObjectMacro(
      self, << "Source point " << source << " is used by no triangle: it has no harmonics.");
    return -1;
  }
  return source;
}

/// The parameters that the setters cannot refuse: negative times, a source location that is not
/// a point. \return An error or "".
std::string CheckSettings(vtkSpectralDescriptors* self)
{
  std::ostringstream problem;
  const double* location = self->GetSourceLocation();
  if (self->GetComputeSpectralDistance() && self->GetUseSourceLocation() &&
    !(std::isfinite(location[0]) && std::isfinite(location[1]) && std::isfinite(location[2])))
  {
    problem << "SourceLocation (" << location[0] << ", " << location[1] << ", " << location[2]
            << ") is not a finite point.";
    return problem.str();
  }
  for (int j = 0; j < self->GetNumberOfHeatKernelTimes(); ++j)
  {
    if (!(self->GetHeatKernelTime(j) >= 0.0 && std::isfinite(self->GetHeatKernelTime(j))))
    {
      problem << "HeatKernelTimes[" << j << "] = " << self->GetHeatKernelTime(j)
              << " is not a finite time >= 0.";
      return problem.str();
    }
  }
  if (!(self->GetDiffusionTime() >= 0.0 && std::isfinite(self->GetDiffusionTime())))
  {
    problem << "DiffusionTime " << self->GetDiffusionTime() << " is not a finite time >= 0.";
  }
  return problem.str();
}

/// The ShapeDNA table: Index, Eigenvalue, ScaledEigenvalue = lambda |Omega|^(2/d), with the
/// measure (area or volume) and the dimension d of the input (2, or 3 for a volume).
void FillShapeDNA(const spectral::Vector& lambda, double measure, int dimension, vtkTable* table)
{
  const spectral::Vector scaled = spectral::ShapeDNA(lambda, measure, dimension);
  vtkNew<vtkIdTypeArray> index;
  index->SetName(vtkManifoldHarmonicsNames::IndexColumn);
  index->SetNumberOfTuples(lambda.size());
  for (vtkIdType k = 0; k < lambda.size(); ++k)
  {
    index->SetValue(k, k);
  }
  table->AddColumn(index);
  table->AddColumn(vtkManifoldHarmonicsArrays::NewDoubleArray(
    lambda, vtkManifoldHarmonicsNames::EigenvalueColumn));
  table->AddColumn(vtkManifoldHarmonicsArrays::NewDoubleArray(
    scaled, vtkManifoldHarmonicsNames::ScaledEigenvalueColumn));
}
/// What the descriptors need of the shape: its spectrum, its area or volume (measure), its
/// dimension (2 or 3) and its number of points.
struct Shape
{
  spectral::Spectrum Spectrum;
  double Measure;
  int Dimension;
  vtkIdType Points;
};

/// The descriptors computed, and their parameters (field data: times, energies).
struct Results
{
  std::vector<Descriptor> Descriptors;
  vtkNew<vtkFieldData> Parameters;
};

/// The heat kernel signature at the given times, or at the default ones.
void AddHeatKernelSignature(vtkSpectralDescriptors* self,
  const vtkManifoldHarmonicsArrays::Basis& basis,
  const Shape& shape,
  Results& results)
{
  spectral::Vector times = spectral::DefaultHeatKernelTimes(shape.Spectrum);
  if (self->GetNumberOfHeatKernelTimes() > 0)
  {
    times.resize(self->GetNumberOfHeatKernelTimes());
    for (int j = 0; j < self->GetNumberOfHeatKernelTimes(); ++j)
    {
      times[j] = self->GetHeatKernelTime(j);
    }
  }
  for (Eigen::Index j = 0; j < times.size(); ++j)
  {
    WarnTruncation(self,
      shape.Spectrum,
      shape.Measure,
      shape.Dimension,
      times[j],
      shape.Points,
      "The heat kernel signature");
  }
  const bool scaleNormalize = self->GetScaleNormalizeHeatKernel();
  results.Descriptors.push_back({ vtkManifoldHarmonicsNames::HeatKernelSignature,
    OnBasis(basis,
      [&shape, &times, scaleNormalize](const auto& H)
      { return spectral::HeatKernelSignature(H, shape.Spectrum, times, scaleNormalize); }),
    Labels("t=", times) });
  results.Parameters->AddArray(
    vtkManifoldHarmonicsArrays::NewDoubleArray(times, vtkManifoldHarmonicsNames::HeatKernelTimes));
}

/// The wave kernel signature at the default energies.
void AddWaveKernelSignature(vtkSpectralDescriptors* self,
  const vtkManifoldHarmonicsArrays::Basis& basis,
  const Shape& shape,
  Results& results)
{
  const spectral::WaveKernelEnergies energies = spectral::DefaultWaveKernelEnergies(
    shape.Spectrum, self->GetNumberOfEnergies(), self->GetWaveKernelSigma());
  results.Descriptors.push_back({ vtkManifoldHarmonicsNames::WaveKernelSignature,
    OnBasis(basis,
      [&shape, &energies](const auto& H)
      { return spectral::WaveKernelSignature(H, shape.Spectrum, energies); }),
    Labels("e=", energies.Energies) });
  results.Parameters->AddArray(vtkManifoldHarmonicsArrays::NewDoubleArray(
    energies.Energies, vtkManifoldHarmonicsNames::WaveKernelEnergies));
}

/// The global point signature, its components clamped to the non-constant harmonics.
void AddGlobalPointSignature(vtkSpectralDescriptors* self,
  const vtkManifoldHarmonicsArrays::Basis& basis,
  const Shape& shape,
  Results& results)
{
  const int available = static_cast<int>(spectral::NonZeroIndices(shape.Spectrum).size());
  int components = self->GetNumberOfGPSComponents();
  if (components > available)
  {
    vtkWarningWithObjectMacro(self,
      << "NumberOfGPSComponents " << components << " clamped to " << available
      << ", the non-constant harmonics of the basis.");
    components = available;
  }
  results.Descriptors.push_back({ vtkManifoldHarmonicsNames::GlobalPointSignature,
    OnBasis(basis,
      [&shape, components](const auto& H)
      { return spectral::GlobalPointSignature(H, shape.Spectrum, components); }),
    {} });
}

/// The spectral distance of the chosen kind from `source`.
void AddSpectralDistance(vtkSpectralDescriptors* self,
  const vtkManifoldHarmonicsArrays::Basis& basis,
  const Shape& shape,
  vtkIdType source,
  Results& results)
{
  const spectral::DistanceKind kind = vtkManifoldHarmonicsEnums::To(
    vtkManifoldHarmonicsEnums::DistanceKind, self->GetDistanceKind(), "DistanceKind");
  double time = self->GetDiffusionTime();
  if (kind == spectral::DistanceKind::Diffusion)
  {
    time = time > 0.0 ? time : spectral::DefaultHeatKernelTimes(shape.Spectrum, 1)[0];
    WarnTruncation(self,
      shape.Spectrum,
      shape.Measure,
      shape.Dimension,
      2.0 * time,
      shape.Points,
      "The diffusion distance (a heat kernel at twice its time)");
  }
  const spectral::Vector weights = spectral::DistanceWeights(shape.Spectrum, kind, time);
  results.Descriptors.push_back({ vtkManifoldHarmonicsNames::SpectralDistance,
    OnBasis(basis,
      [&weights, source](const auto& H)
      { return spectral::RowMatrix(spectral::SpectralDistance(H, weights, source)); }),
    {} });
}

/// The descriptors the filter asks for, a quarter of the progress each.
/// \return false after an abort.
bool ComputeDescriptors(vtkSpectralDescriptors* self,
  const vtkManifoldHarmonicsArrays::Basis& basis,
  const Shape& shape,
  vtkIdType source,
  Results& results)
{
  const std::pair<bool, std::function<void()>> steps[] = {
    { self->GetComputeHeatKernelSignature(),
      [&]() { AddHeatKernelSignature(self, basis, shape, results); } },
    { self->GetComputeWaveKernelSignature(),
      [&]() { AddWaveKernelSignature(self, basis, shape, results); } },
    { self->GetComputeGlobalPointSignature(),
      [&]() { AddGlobalPointSignature(self, basis, shape, results); } },
    { self->GetComputeSpectralDistance(),
      [&]() { AddSpectralDistance(self, basis, shape, source, results); } },
  };
  for (std::size_t k = 0; k < 4; ++k)
  {
    if (steps[k].first)
    {
      steps[k].second();
    }
    self->UpdateProgress(0.25 * static_cast<double>(k + 1));
    if (self->AbortRequested())
    {
      return false;
    }
  }
  return true;
}

/// The output: the input with the descriptors (point data, the first one active) and their
/// parameters (field data).
void WriteDescriptors(vtkPointSet* input,
  vtkPointSet* output,
  Results& results,
  const spectral::Vector& mass)
{
  output->ShallowCopy(input);
  for (Descriptor& descriptor : results.Descriptors)
  {
    output->GetPointData()->AddArray(ToArray(descriptor, mass));
  }
  for (int a = 0; a < results.Parameters->GetNumberOfArrays(); ++a)
  {
    output->GetFieldData()->AddArray(results.Parameters->GetAbstractArray(a));
  }
  if (!results.Descriptors.empty())
  {
    output->GetPointData()->SetActiveScalars(results.Descriptors.front().Name);
  }
}
} // anonymous namespace

//------------------------------------------------------------------------------
vtkSpectralDescriptors::vtkSpectralDescriptors()
  : vtkManifoldHarmonicsAlgorithm(POINT_SET_AND_TABLE)
  , HeatKernelTimes(vtkDoubleArray::New())
  , MeshFigures(new vtkManifoldHarmonicsArrays::MeshFiguresCache)
{
  this->ComputeHeatKernelSignature = true;
  this->ScaleNormalizeHeatKernel = false;
  this->ComputeWaveKernelSignature = false;
  this->NumberOfEnergies = spectral::DefaultNumberOfEnergies;
  this->WaveKernelSigma = 0.0;
  this->ComputeGlobalPointSignature = false;
  this->NumberOfGPSComponents = 10;
  this->ComputeSpectralDistance = false;
  this->DistanceKind = BIHARMONIC;
  this->DiffusionTime = 0.0;
  this->SourcePoint = 0;
  this->UseSourceLocation = false;
  this->SourceLocation[0] = this->SourceLocation[1] = this->SourceLocation[2] = 0.0;
}

//------------------------------------------------------------------------------
vtkSpectralDescriptors::~vtkSpectralDescriptors()
{
  this->HeatKernelTimes->Delete();
}

//------------------------------------------------------------------------------
void vtkSpectralDescriptors::SetNumberOfHeatKernelTimes(int count)
{
  count = std::max(count, 0);
  const vtkIdType old = this->HeatKernelTimes->GetNumberOfTuples();
  if (count == old)
  {
    return;
  }
  this->HeatKernelTimes->Resize(count);
  this->HeatKernelTimes->SetNumberOfTuples(count);
  for (vtkIdType j = old; j < count; ++j)
  {
    this->HeatKernelTimes->SetValue(j, 0.0);
  }
  this->Modified();
}

//------------------------------------------------------------------------------
int vtkSpectralDescriptors::GetNumberOfHeatKernelTimes()
{
  return static_cast<int>(this->HeatKernelTimes->GetNumberOfTuples());
}

//------------------------------------------------------------------------------
void vtkSpectralDescriptors::SetHeatKernelTime(int index, double time)
{
  if (index < 0 || index >= this->GetNumberOfHeatKernelTimes())
  {
    vtkErrorMacro(<< "Heat kernel time " << index << " out of range [0, "
                  << this->GetNumberOfHeatKernelTimes() << ").");
    return;
  }
  if (this->HeatKernelTimes->GetValue(index) != time)
  {
    this->HeatKernelTimes->SetValue(index, time);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
double vtkSpectralDescriptors::GetHeatKernelTime(int index)
{
  if (index < 0 || index >= this->GetNumberOfHeatKernelTimes())
  {
    vtkErrorMacro(<< "Heat kernel time " << index << " out of range [0, "
                  << this->GetNumberOfHeatKernelTimes() << ").");
    return 0.0;
  }
  return this->HeatKernelTimes->GetValue(index);
}

//------------------------------------------------------------------------------
void vtkSpectralDescriptors::AddHeatKernelTime(double time)
{
  this->HeatKernelTimes->InsertNextValue(time);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkSpectralDescriptors::RemoveAllHeatKernelTimes()
{
  if (this->HeatKernelTimes->GetNumberOfTuples() > 0)
  {
    this->HeatKernelTimes->SetNumberOfTuples(0);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkSpectralDescriptors::ShapeDNAOnly(vtkPointSet* input,
  double area,
  int dimension,
  vtkPointSet* output,
  vtkTable* table)
{
  if (this->ComputeHeatKernelSignature || this->ComputeWaveKernelSignature ||
    this->ComputeGlobalPointSignature || this->ComputeSpectralDistance)
  {
    // The spectrum is what a basis without harmonics is for: ShapeDNA is computed, and the
    // point descriptors are left out with a warning rather than failing the whole filter.
    vtkWarningMacro(<< "The basis holds eigenvalues only (ManifoldHarmonicBasis with "
                       "EigenvaluesOnly): ShapeDNA is computed, the point descriptors (which "
                       "need the harmonics) are not. Turn them off to silence this warning, or "
                       "compute the harmonics.");
  }
  const spectral::Vector lambda = vtkManifoldHarmonicsArrays::Signal(
    input->GetFieldData()->GetArray(vtkManifoldHarmonicsNames::Eigenvalues))
                                    .View()
                                    .col(0);
  FillShapeDNA(lambda, area, dimension, table);
  output->ShallowCopy(input);
  return 1;
}

//------------------------------------------------------------------------------
vtkTable* vtkSpectralDescriptors::GetShapeDNAOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
const char* vtkSpectralDescriptors::HeatKernelSignatureArrayName()
{
  return vtkManifoldHarmonicsNames::HeatKernelSignature;
}

//------------------------------------------------------------------------------
const char* vtkSpectralDescriptors::WaveKernelSignatureArrayName()
{
  return vtkManifoldHarmonicsNames::WaveKernelSignature;
}

//------------------------------------------------------------------------------
const char* vtkSpectralDescriptors::GlobalPointSignatureArrayName()
{
  return vtkManifoldHarmonicsNames::GlobalPointSignature;
}

//------------------------------------------------------------------------------
const char* vtkSpectralDescriptors::SpectralDistanceArrayName()
{
  return vtkManifoldHarmonicsNames::SpectralDistance;
}

//------------------------------------------------------------------------------
const char* vtkSpectralDescriptors::HeatKernelTimesArrayName()
{
  return vtkManifoldHarmonicsNames::HeatKernelTimes;
}

//------------------------------------------------------------------------------
const char* vtkSpectralDescriptors::WaveKernelEnergiesArrayName()
{
  return vtkManifoldHarmonicsNames::WaveKernelEnergies;
}

//------------------------------------------------------------------------------
const char* vtkSpectralDescriptors::ScaledEigenvalueColumnName()
{
  return vtkManifoldHarmonicsNames::ScaledEigenvalueColumn;
}

//------------------------------------------------------------------------------
int vtkSpectralDescriptors::Execute(vtkPointSet* input, vtkPointSet* output, vtkTable* shapeDNA)
{
  this->UsedSourcePoint = -1;
  // Collective in a distributed run, so before any return: the area and edge sums of the whole
  // surface. ParaView appends the tables of all processes: process 0 alone fills ShapeDNA.
  vtkMultiProcessController* controller = GetDistributedController();
  const std::vector<double> sums = SurfaceSums(controller, input, this->MeshFigures->Of(input));
  vtkNew<vtkTable> unshown;
  vtkTable* table = !controller || controller->GetLocalProcessId() == 0 ? shapeDNA : unshown;
  if (input->GetNumberOfPoints() == 0)
  {
    if (!controller)
    {
      vtkWarningMacro(<< "No data to describe!");
    }
    output->ShallowCopy(input);
    return 1;
  }
  if (vtkManifoldHarmonicsArrays::IsSpectrumOnly(input))
  {
    return this->ShapeDNAOnly(input, sums[0], Dimension(sums), output, table);
  }
  vtkManifoldHarmonicsArrays::Basis basis;
  std::string problem = vtkManifoldHarmonicsArrays::FindBasis(input, basis);
  problem = problem.empty() ? CheckSettings(this) : problem;
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  const spectral::Vector mass = basis.MassVector();
  vtkIdType source = -1;
  if (this->ComputeSpectralDistance && (source = FindSource(this, input, mass)) < 0)
  {
    return 0;
  }
  vtkDebugMacro(<< "HKS " << this->ComputeHeatKernelSignature << ", WKS "
                << this->ComputeWaveKernelSignature << ", GPS " << this->ComputeGlobalPointSignature
                << ", distance " << this->ComputeSpectralDistance << " from " << source);
  this->SetProgressText("Spectral descriptors");
  const Shape shape{
    ToSpectrum(basis.EigenvalueVector(), sums), sums[0], Dimension(sums), input->GetNumberOfPoints()
  };
  Results results;
  if (!ComputeDescriptors(this, basis, shape, source, results))
  {
    return 1; // aborted
  }
  this->UsedSourcePoint = source;
  FillShapeDNA(shape.Spectrum.Lambda, shape.Measure, shape.Dimension, table);
  WriteDescriptors(input, output, results, mass);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSpectralDescriptors::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const auto onOff = [](bool value) { return value ? "On" : "Off"; };
  os << indent << "ComputeHeatKernelSignature: " << onOff(this->ComputeHeatKernelSignature) << "\n";
  os << indent << "HeatKernelTimes:";
  for (vtkIdType j = 0; j < this->HeatKernelTimes->GetNumberOfTuples(); ++j)
  {
    os << " " << this->HeatKernelTimes->GetValue(j);
  }
  os << (this->HeatKernelTimes->GetNumberOfTuples() == 0 ? " (the default times)\n" : "\n");
  os << indent << "ScaleNormalizeHeatKernel: " << onOff(this->ScaleNormalizeHeatKernel) << "\n";
  os << indent << "ComputeWaveKernelSignature: " << onOff(this->ComputeWaveKernelSignature) << "\n";
  os << indent << "NumberOfEnergies: " << this->NumberOfEnergies << "\n";
  os << indent << "WaveKernelSigma: " << this->WaveKernelSigma << "\n";
  os << indent << "ComputeGlobalPointSignature: " << onOff(this->ComputeGlobalPointSignature)
     << "\n";
  os << indent << "NumberOfGPSComponents: " << this->NumberOfGPSComponents << "\n";
  os << indent << "ComputeSpectralDistance: " << onOff(this->ComputeSpectralDistance) << "\n";
  os << indent << "DistanceKind: "
     << vtkManifoldHarmonicsEnums::Name(vtkManifoldHarmonicsEnums::DistanceKind, this->DistanceKind)
     << "\n";
  os << indent << "DiffusionTime: " << this->DiffusionTime << "\n";
  os << indent << "SourcePoint: " << this->SourcePoint << "\n";
  os << indent << "UseSourceLocation: " << onOff(this->UseSourceLocation) << "\n";
  os << indent << "SourceLocation: (" << this->SourceLocation[0] << ", " << this->SourceLocation[1]
     << ", " << this->SourceLocation[2] << ")\n";
  os << indent << "UsedSourcePoint: " << this->UsedSourcePoint << "\n";
}
