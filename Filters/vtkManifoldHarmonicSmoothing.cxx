// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicSmoothing.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
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

#include <algorithm>
#include <cmath>

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
// otherwise), with re-injection: the new coordinates of the points of `withBasis`.
spectral::RowMatrix LowPass(vtkManifoldHarmonicSmoothing* self,
  const Transformed& transformed,
  vtkPointSet* withBasis,
  double fraction)
{
  spectral::FilterParameters given;
  given.Kind = spectral::FilterKind::LowPass;
  given.Cutoff = fraction;
  given.UpperCutoff = spectral::DefaultUpperCutoffFraction;
  const vtkManifoldHarmonicsStages::Design design = vtkManifoldHarmonicsStages::DesignFilter(
    given, vtkSpectralFilter::FRACTION_OF_HIGHEST, transformed.Lambda, transformed.Nyquist);
  const double highFrequencyGain =
    vtkManifoldHarmonicsStages::ReinjectionGain(self, design, transformed.Nyquist, true);
  const vtkManifoldHarmonicsArrays::Signal points(withBasis->GetPoints()->GetData());
  return transformed.Basis.FilterSignal(transformed.Basis.MassVector(),
    design.Gains,
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
  , Basis(vtkSmartPointer<vtkManifoldHarmonicBasis>::New())
  , MeshFigures(new vtkManifoldHarmonicsArrays::MeshFiguresCache)
{
  // The basis of a shallow copy of the input (made in Execute, of the input's type), kept
  // between executions; the transform and filter stages run on it directly.
  this->Basis->AddObserver(
    vtkCommand::ProgressEvent, this, &vtkManifoldHarmonicSmoothing::ForwardProgress);
  this->Basis->AddObserver(
    vtkCommand::WarningEvent, this, &vtkManifoldHarmonicSmoothing::ForwardWarning);
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
    vtkErrorMacro(<< "The " << this->NumberOfHarmonics
                  << " harmonic(s) are all constant (one per connected component of the surface, "
                     "frequency 0): there is nothing to smooth. Raise NumberOfHarmonics.");
    return 0;
  }
  const spectral::RowMatrix smoothed = LowPass(this, transformed, withBasis, this->CutoffFraction);
  output->ShallowCopy(input);
  vtkNew<vtkPoints> points;
  points->SetData(vtkManifoldHarmonicsArrays::NewArrayLike(
    input->GetPoints()->GetData(), smoothed, input->GetPoints()->GetData()->GetName()));
  output->SetPoints(points);
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
  // The pipeline does not clear AbortExecute after an abort: the basis follows this filter's flag.
  this->Basis->SetAbortExecute(this->GetAbortExecute());
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
}
