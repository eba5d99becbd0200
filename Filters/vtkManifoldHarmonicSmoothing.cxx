// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicSmoothing.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicsArrays.h"
#include "vtkManifoldHarmonicsEnums.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkManifoldHarmonicsParallel.h"
#include "vtkManifoldHarmonicsParameters.h"
#include "vtkManifoldHarmonicsStages.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSpectralFilter.h"

#include "Spectral/Common/Defaults.h"
#include "Spectral/Common/Eigenvalues.h"
#include "Spectral/Solver/Memory.h"
#include "vtkManifoldHarmonicsStreaming.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

vtkStandardNewMacro(vtkManifoldHarmonicSmoothing);

namespace
{
//------------------------------------------------------------------------------
// Whether a basis with eigenvalues has none but the zero ones of its constant harmonics (one per
// connected component), by the spectral filter's rule (the scale of the Nyquist frequency).
bool OnlyConstantHarmonics(const spectral::Vector& lambda, double nyquist)
{
  if (lambda.size() == 0)
  {
    return false; // no basis (an empty piece of a distributed run)
  }
  const double top = lambda[lambda.size() - 1];
  return spectral::IsZeroEigenvalue(top, nyquist * nyquist) || !std::isfinite(top);
}

//------------------------------------------------------------------------------
// What the transform and filter stages need of the basis: collective in a distributed run
// (every process calls it once, with or without a basis of its own).
struct Transformed
{
  vtkManifoldHarmonicsArrays::Basis Basis;
  spectral::RowMatrix Coefficients; // of the points, added over the processes
  spectral::Vector Lambda;
  double Nyquist = 0.0;
  std::string Problem;
};

//------------------------------------------------------------------------------
// The transform stage of the points of `withBasis` (the internal basis's output) and the
// Nyquist frequency of the whole mesh, in the order the transform and the spectral filter take
// them (vtkManifoldHarmonicsStages).
Transformed TransformPoints(vtkPointSet* withBasis,
  int threads,
  vtkMultiProcessController* controller,
  vtkManifoldHarmonicsArrays::MeshFiguresCache& figures)
{
  Transformed out;
  std::vector<vtkManifoldHarmonicsParallel::NamedMatrix> sums;
  if (withBasis->GetNumberOfPoints() > 0)
  {
    out.Problem = vtkManifoldHarmonicsArrays::FindBasis(withBasis, out.Basis);
    if (out.Problem.empty())
    {
      out.Lambda = out.Basis.EigenvalueVector();
      sums.push_back({ vtkManifoldHarmonicsNames::Points,
        vtkManifoldHarmonicsStages::LocalCoefficients(out.Basis,
          vtkManifoldHarmonicsStages::OwnedMass(out.Basis, withBasis),
          withBasis->GetPoints()->GetData(),
          threads) });
    }
  }
  if (controller && !vtkManifoldHarmonicsParallel::SumOverRanks(controller, sums, out.Lambda))
  {
    out.Problem = "Processes disagree on the number of harmonics.";
  }
  out.Coefficients = sums.empty() ? spectral::RowMatrix() : sums.front().Values;
  out.Nyquist =
    vtkManifoldHarmonicsStages::NyquistFrequency(controller, figures.Of(withBasis).EdgeSums);
  return out;
}

//------------------------------------------------------------------------------
// The low pass at `fraction` of the highest computed frequency (the spectral filter's defaults
// otherwise) for the eigenvalues `lambda` (ascending: only the last sets the frequencies).
vtkManifoldHarmonicsStages::Design LowPassDesign(double fraction,
  const spectral::Vector& lambda,
  double nyquist)
{
  spectral::FilterParameters given;
  given.Kind = spectral::FilterKind::LowPass;
  given.Cutoff = fraction;
  given.UpperCutoff = spectral::DefaultUpperCutoffFraction;
  return vtkManifoldHarmonicsStages::DesignFilter(
    given, vtkSpectralFilter::FRACTION_OF_HIGHEST, lambda, nyquist);
}

//------------------------------------------------------------------------------
// The gains of LowPassDesign, and its re-injection gain in `highFrequencyGain` (after the cutoff
// warnings, `self`'s).
spectral::Vector LowPassGains(vtkManifoldHarmonicSmoothing* self,
  double fraction,
  const spectral::Vector& lambda,
  double nyquist,
  double& highFrequencyGain)
{
  const vtkManifoldHarmonicsStages::Design design = LowPassDesign(fraction, lambda, nyquist);
  highFrequencyGain = vtkManifoldHarmonicsStages::ReinjectionGain(self, design, nyquist, true);
  return design.Gains;
}

//------------------------------------------------------------------------------
// The error of a basis whose harmonics are all constant.
std::string NothingToSmooth(int m)
{
  return "The " + std::to_string(m) +
    " harmonic(s) are all constant (one per connected component of the surface, frequency 0): "
    "there is nothing to smooth. Raise NumberOfHarmonics.";
}

//------------------------------------------------------------------------------
// The input with the smoothed point coordinates, in the input's precision.
void SetSmoothedPoints(vtkPointSet* input, vtkPointSet* output, const spectral::RowMatrix& smoothed)
{
  output->ShallowCopy(input);
  vtkNew<vtkPoints> points;
  points->SetData(vtkManifoldHarmonicsArrays::NewArrayLike(
    input->GetPoints()->GetData(), smoothed, input->GetPoints()->GetData()->GetName()));
  output->SetPoints(points);
}

//------------------------------------------------------------------------------
// The memory of the streamed low pass beside the core's stream (spectral::StreamedFilter): the
// coordinates, their weighted copy, the sum, the result and the output points, in doubles.
std::uint64_t StreamedFilterBytes(std::uint64_t n)
{
  return 5 * n * 3 * 8;
}

//------------------------------------------------------------------------------
// The memory a streamed solve of n points may take, in bytes: `available` (MemoryLimit or the
// system's) less the filter's own arrays (spectral::MemoryShare).
std::uint64_t StreamedSolveBytes(std::uint64_t available, std::uint64_t n)
{
  return spectral::MemoryShare(available, StreamedFilterBytes(n));
}

//------------------------------------------------------------------------------
// The low pass at `fraction` of the highest computed frequency, with re-injection: the new
// coordinates of the points of `withBasis`.
spectral::RowMatrix LowPass(vtkManifoldHarmonicSmoothing* self,
  const Transformed& transformed,
  vtkPointSet* withBasis,
  double fraction)
{
  double highFrequencyGain = 0.0;
  const spectral::Vector gains =
    LowPassGains(self, fraction, transformed.Lambda, transformed.Nyquist, highFrequencyGain);
  const vtkManifoldHarmonicsArrays::Signal points(withBasis->GetPoints()->GetData());
  return transformed.Basis.FilterSignal(transformed.Basis.MassVector(),
    gains,
    spectral::ConstRowView(transformed.Coefficients.data(),
      transformed.Coefficients.rows(),
      transformed.Coefficients.cols()),
    points.View(),
    highFrequencyGain,
    self->GetNumberOfThreads());
}
} // anonymous namespace

//------------------------------------------------------------------------------
vtkManifoldHarmonicSmoothing::vtkManifoldHarmonicSmoothing()
  : NumberOfHarmonics(vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS)
  , CutoffFraction(spectral::DefaultCutoffFraction)
  , BasisPrecision(vtkManifoldHarmonicBasis::DOUBLE)
  , BoundaryCondition(vtkManifoldHarmonicBasis::NEUMANN)
  , NumberOfNeighbors(vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_NEIGHBORS)
  , Solver(vtkManifoldHarmonicBasis::BUILT_IN)
  , SlepcPartitions(1)
  , WeldSeams(true)
  , SeamTolerance(vtkManifoldHarmonicsParallel::SeamTolerance)
  , MemoryLimit(0.0)
  , Storage(AUTOMATIC)
  , ChosenStorage(AUTOMATIC)
  , Basis(vtkSmartPointer<vtkManifoldHarmonicBasis>::New())
  , MeshFigures(new vtkManifoldHarmonicsArrays::MeshFiguresCache)
{
  // The basis of a shallow copy of the input (made in Execute, of the input's type), kept
  // between executions; the transform and filter stages run on it directly.
  this->Basis->AddObserver(
    vtkCommand::ProgressEvent, this, &vtkManifoldHarmonicSmoothing::ForwardProgress);
  this->Basis->AddObserver(
    vtkCommand::WarningEvent, this, &vtkManifoldHarmonicSmoothing::ForwardWarning);
  this->Basis->AddObserver(
    vtkCommand::ErrorEvent, this, &vtkManifoldHarmonicSmoothing::ForwardWarning);
}

//------------------------------------------------------------------------------
vtkManifoldHarmonicSmoothing::~vtkManifoldHarmonicSmoothing() = default;

//------------------------------------------------------------------------------
void vtkManifoldHarmonicSmoothing::ForwardProgress(vtkObject*, unsigned long, void* data)
{
  this->UpdateProgress(0.9 * *static_cast<double*>(data));
  if (this->GetAbortExecute())
  {
    this->Basis->SetAbortExecute(1);
  }
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicSmoothing::Execute(vtkPointSet* input,
  vtkPointSet* output,
  vtkTable* vtkNotUsed(table))
{
  vtkDebugMacro(<< "Smoothing with " << this->NumberOfHarmonics << " harmonics, cutoff fraction "
                << this->CutoffFraction << ", basis precision " << this->BasisPrecision);
  if (!vtkManifoldHarmonicsParameters::AcceptNumbers(this,
        { { "CutoffFraction", this->CutoffFraction },
          { "SeamTolerance", this->SeamTolerance },
          { "MemoryLimit", this->MemoryLimit } }))
  {
    return 0;
  }
  // Nothing to smooth without polygons: pass the input on, as the basis does, rather than let
  // the internal stages report errors about a basis they did not get. (In a distributed run the
  // stages are collective and every process runs them.)
  if (!vtkManifoldHarmonicsArrays::HasCellsOrIsPointCloud(input) && !GetDistributedController())
  {
    if (input->GetNumberOfPoints() > 0)
    {
      vtkWarningMacro(<< "The input has no polygons or volume cells: passed on unchanged.");
    }
    output->ShallowCopy(input);
    return 1;
  }
  const int storage = this->ChooseStorage(input);
  if (storage < 0)
  {
    return 0;
  }
  this->ChosenStorage = storage;
  if (storage == STREAMED)
  {
    return this->ExecuteStreamed(input, output);
  }
  this->UpdateBasisInput(input);
  if (!this->UpdateBasis())
  {
    return 1; // aborted: the output stays empty
  }
  vtkPointSet* withBasis = this->Basis->GetOutput();
  // Collective in a distributed run: before any process returns.
  this->SetProgressText("Spectral filter");
  const Transformed transformed = TransformPoints(
    withBasis, this->NumberOfThreads, GetDistributedController(), *this->MeshFigures);
  this->UpdateProgress(0.9);
  if (!transformed.Problem.empty() || withBasis->GetNumberOfPoints() != input->GetNumberOfPoints())
  {
    vtkErrorMacro(<< "Manifold harmonic smoothing failed"
                  << (transformed.Problem.empty() ? " (see the errors above)."
                                                  : ": " + transformed.Problem));
    return 0;
  }
  if (this->AbortRequested() || input->GetNumberOfPoints() == 0)
  {
    output->ShallowCopy(input);
    return 1;
  }
  if (OnlyConstantHarmonics(transformed.Lambda, transformed.Nyquist))
  {
    vtkErrorMacro(<< NothingToSmooth(this->NumberOfHarmonics));
    return 0;
  }
  SetSmoothedPoints(input, output, LowPass(this, transformed, withBasis, this->CutoffFraction));
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicSmoothing::ChooseStorage(vtkPointSet* input)
{
  using vtkManifoldHarmonicsParameters::Bytes;
  const bool serial =
    !GetDistributedController() && this->Solver == vtkManifoldHarmonicBasis::BUILT_IN;
  if (!serial)
  {
    if (this->Storage == STREAMED)
    {
      vtkErrorMacro(<< "Storage Streamed runs serially with the Built-in solver only: choose "
                       "Automatic or In Memory (the basis is then kept in memory), or run "
                       "serially with the Built-in solver.");
      return -1;
    }
    return IN_MEMORY;
  }
  // The estimates of the basis filter's check (Solver/Memory.h) on every input point.
  const std::uint64_t n = static_cast<std::uint64_t>(input->GetNumberOfPoints());
  const int m = this->NumberOfHarmonics;
  const bool volume = !vtkPolyData::SafeDownCast(input);
  const std::uint64_t limit = vtkManifoldHarmonicsParameters::MemoryLimitBytes(this->MemoryLimit);
  const std::uint64_t available = limit > 0 ? limit : spectral::AvailableMemory();
  const char* from = limit > 0 ? "MemoryLimit" : "reported by the system";
  // In the bands the solve's memory plan would choose (Solver/Memory.h); streamed, in the share
  // ExecuteStreamed gives the solve (StreamedSolveBytes).
  const std::uint64_t inMemory = spectral::PlanBasisMemory(n,
    n,
    m,
    0,
    vtkManifoldHarmonicsEnums::To(
      vtkManifoldHarmonicsEnums::BasisPrecision, this->BasisPrecision, "BasisPrecision"),
    true,
    volume,
    available)
                                   .Estimate.Total();
  const std::uint64_t streamed =
    spectral::PlanStreamedMemory(n, n, m, 0, volume, StreamedSolveBytes(available, n))
      .Estimate.Total() +
    StreamedFilterBytes(n);
  if (this->Storage == IN_MEMORY && available != 0 && inMemory > available)
  {
    vtkErrorMacro(<< "Not enough memory for the basis of " << m << " harmonics on " << n
                  << " points in memory: about " << Bytes(inMemory) << " needed, "
                  << Bytes(available) << " available (" << from
                  << "). Set Storage to Automatic or Streamed (about " << Bytes(streamed)
                  << ", whatever the number of harmonics), raise MemoryLimit, compute fewer "
                     "harmonics or set BasisPrecision to Float.");
    return -1;
  }
  if (this->Storage == IN_MEMORY ||
    (this->Storage == AUTOMATIC && (available == 0 || inMemory <= available)))
  {
    return IN_MEMORY;
  }
  if (available != 0 && streamed > available)
  {
    vtkErrorMacro(<< "Not enough memory to smooth " << n << " points even with the basis "
                  << "streamed: about " << Bytes(streamed) << " needed (the sparse factor, the "
                  << "Lanczos workspace and three bands of vectors in bands of "
                  << spectral::SmallestPlannedBand
                  << " eigenpairs, the smallest, whatever the number of harmonics), "
                  << Bytes(available) << " available (" << from
                  << "). Raise MemoryLimit to at least " << (streamed >> 20) + 1
                  << " MiB, free memory, or simplify the mesh.");
    return -1;
  }
  if (this->Storage == AUTOMATIC)
  {
    vtkWarningMacro(<< "The basis of " << m << " harmonics on " << n << " points needs about "
                    << Bytes(inMemory) << " in memory, more than the " << Bytes(available)
                    << " available (" << from
                    << "): it is streamed instead (Storage Automatic), in about " << Bytes(streamed)
                    << ", and every execution, a new CutoffFraction "
                    << "included, solves again. Raise MemoryLimit to keep it in memory, or set "
                    << "Storage to Streamed.");
  }
  return STREAMED;
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicSmoothing::ExecuteStreamed(vtkPointSet* input, vtkPointSet* output)
{
  // No basis to keep: let go of one kept by an in-memory execution (the next one recomputes).
  // (Read without an update: the basis may never have had an input.)
  if (vtkDataObject* kept = vtkDataObject::GetData(this->Basis->GetOutputInformation(0)))
  {
    kept->Initialize();
  }
  this->Basis->Modified();
  // The core's limit leaves room for the filter's own arrays (StreamedFilterBytes).
  const std::uint64_t limit = vtkManifoldHarmonicsParameters::MemoryLimitBytes(this->MemoryLimit);
  const std::uint64_t available = limit > 0 ? limit : spectral::AvailableMemory();
  this->ConfigureBasis(static_cast<double>(StreamedSolveBytes(
                         available, static_cast<std::uint64_t>(input->GetNumberOfPoints()))) /
    1048576.0);
  this->SetProgressText("Basis");
  vtkManifoldHarmonicsArrays::MeshFiguresCache figures;
  const double nyquist =
    vtkManifoldHarmonicsStages::NyquistFrequency(nullptr, figures.Of(input).EdgeSums);
  vtkManifoldHarmonicBasis::StreamRequest request;
  const double fraction = this->CutoffFraction;
  const int m = this->NumberOfHarmonics;
  // Given the highest eigenvalue alone (the stream solves the others later, or never when
  // their gain is 0); the warnings about the cutoff come once the stream knows the spectrum.
  request.Design = [fraction, nyquist, m](double highest, double& hfGain)
  {
    const spectral::Vector top = spectral::Vector::Constant(1, highest);
    if (OnlyConstantHarmonics(top, nyquist))
    {
      throw spectral::InvalidInput(NothingToSmooth(m));
    }
    const vtkManifoldHarmonicsStages::Design design = LowPassDesign(fraction, top, nyquist);
    hfGain = vtkManifoldHarmonicsStages::MeanGainAbove(design, nyquist);
    return design.Parameters;
  };
  const int solved = this->Basis->SolveStreamed(input, request);
  if (this->GetAbortExecute() || this->Basis->GetAbortExecute())
  {
    return 1; // aborted: the output stays empty
  }
  if (!solved)
  {
    vtkErrorMacro(<< "Manifold harmonic smoothing failed (see the errors above).");
    return 0;
  }
  if (request.Filtered.rows() != input->GetNumberOfPoints())
  {
    output->ShallowCopy(input); // no cells to solve on (the basis warned)
    return 1;
  }
  if (request.Eigenvalues.size() > 0)
  {
    // The cutoff warnings of the in-memory path, from the eigenvalues the stream knows: those
    // it skipped lie above the low pass's transition, where the highest one lies too.
    double hfGain = 0.0;
    LowPassGains(this, fraction, request.Eigenvalues, nyquist, hfGain);
  }
  SetSmoothedPoints(input, output, request.Filtered);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicSmoothing::UpdateBasisInput(vtkPointSet* input)
{
  // A new input (or the same one modified) recomputes the basis; a new cutoff alone does not.
  // In a distributed run every process executes each stage (they are collective), and every
  // process sees the same parameters and the same kind of input change.
  if (input != this->InputData.GetPointer() || input->GetMTime() != this->InputTime)
  {
    if (!this->Input || !this->Input->IsA(input->GetClassName()))
    {
      this->Input = vtk::TakeSmartPointer(input->NewInstance());
      this->Basis->SetInputData(this->Input);
    }
    this->Input->ShallowCopy(input);
    this->InputData = input;
    this->InputTime = input->GetMTime();
  }
}

//------------------------------------------------------------------------------
bool vtkManifoldHarmonicSmoothing::UpdateBasis()
{
  this->SetProgressText("Basis");
  this->ConfigureBasis(this->MemoryLimit);
  this->Basis->Update();
  if (this->GetAbortExecute() || this->Basis->GetAbortExecute())
  {
    // The aborted basis is incomplete: the next execution computes it afresh.
    this->Basis->Modified();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicSmoothing::ConfigureBasis(double memoryLimit)
{
  this->Basis->SetMemoryLimit(memoryLimit);
  this->Basis->SetNumberOfHarmonics(this->NumberOfHarmonics);
  this->Basis->SetBasisPrecision(this->BasisPrecision);
  this->Basis->SetNumberOfThreads(this->NumberOfThreads);
  this->Basis->SetBoundaryCondition(this->BoundaryCondition);
  this->Basis->SetNumberOfNeighbors(this->NumberOfNeighbors);
  this->Basis->SetSolver(this->Solver);
  this->Basis->SetSlepcPartitions(this->SlepcPartitions);
  this->Basis->SetSlepcOptions(this->SlepcOptions.c_str());
  this->Basis->SetWeldSeams(this->WeldSeams);
  this->Basis->SetSeamTolerance(this->SeamTolerance);
  // The smoothing's own Storage decided between memory and streaming: its cached basis is in
  // memory, never in a file of the basis filter's choosing.
  this->Basis->SetStorageToInMemory();
  // The pipeline does not clear AbortExecute after an abort: the basis follows this filter's flag.
  this->Basis->SetAbortExecute(this->GetAbortExecute());
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicSmoothing::SetNumberOfHarmonics(int m)
{
  if (vtkManifoldHarmonicsParameters::AcceptNumberOfHarmonics(this, m, this->NumberOfHarmonics) &&
    m != this->NumberOfHarmonics)
  {
    this->NumberOfHarmonics = m;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicSmoothing::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  namespace Enums = vtkManifoldHarmonicsEnums;
  os << indent << "NumberOfHarmonics: " << this->NumberOfHarmonics << "\n";
  os << indent << "CutoffFraction: " << this->CutoffFraction << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent
     << "BoundaryCondition: " << Enums::Name(Enums::BoundaryCondition, this->BoundaryCondition)
     << "\n";
  os << indent << "BasisPrecision: " << Enums::Name(Enums::BasisPrecision, this->BasisPrecision)
     << "\n";
  os << indent << "Solver: " << Enums::Name(Enums::Solver, this->Solver) << "\n";
  os << indent << "SlepcPartitions: " << this->SlepcPartitions << "\n";
  os << indent << "SlepcOptions: \"" << this->SlepcOptions << "\"\n";
  os << indent << "WeldSeams: " << (this->WeldSeams ? "On" : "Off") << "\n";
  os << indent << "SeamTolerance: " << this->SeamTolerance << " of the bounding box diagonal\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB"
     << (this->MemoryLimit > 0.0 ? "\n" : " (the memory the system reports available)\n");
  os << indent << "Storage: " << Enums::Name(Enums::SmoothingStorage, this->Storage) << "\n";
  os << indent << "ChosenStorage: " << Enums::Name(Enums::SmoothingStorage, this->ChosenStorage) << "\n";
}
