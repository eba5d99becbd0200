// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicSmoothing.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkManifoldHarmonicsArrays.h"
#include "vtkManifoldHarmonicsEnums.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkManifoldHarmonicsParallel.h"
#include "vtkManifoldHarmonicsParameters.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointSet.h"
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
// connected component), by the rule of the spectral filter that ran on it.
bool OnlyConstantHarmonics(vtkPointSet* basisOutput, vtkSpectralFilter* filter)
{
  vtkDataArray* lambda =
    basisOutput->GetFieldData()->GetArray(vtkManifoldHarmonicsNames::Eigenvalues);
  if (!lambda || lambda->GetNumberOfTuples() == 0)
  {
    return false; // no basis (an empty piece of a distributed run)
  }
  const double top = lambda->GetTuple1(lambda->GetNumberOfTuples() - 1);
  const double nyquist = filter->GetNyquistFrequency();
  return spectral::IsZeroEigenvalue(top, nyquist * nyquist) || !std::isfinite(top);
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
  , Transform(vtkSmartPointer<vtkManifoldHarmonicTransform>::New())
  , Filter(vtkSmartPointer<vtkSpectralFilter>::New())
{
  // The three stages on a shallow copy (made in RequestData, of the input's type), so that the
  // internal pipeline does not touch the input.
  this->Basis->AddObserver(
    vtkCommand::ProgressEvent, this, &vtkManifoldHarmonicSmoothing::ForwardProgress);
  this->Basis->AddObserver(
    vtkCommand::WarningEvent, this, &vtkManifoldHarmonicSmoothing::ForwardWarning);
  this->Filter->AddObserver(
    vtkCommand::WarningEvent, this, &vtkManifoldHarmonicSmoothing::ForwardWarning);
  this->Transform->SetInputConnection(this->Basis->GetOutputPort());
  this->Filter->SetFilterKindToLowPass();
  // CutoffFraction is the filter's Cutoff in fractions of the highest computed frequency: one
  // rule (spectral::ToAbsoluteUnits).
  this->Filter->SetCutoffUnitsToFractionOfHighest();
  this->Filter->SetInputConnection(this->Transform->GetOutputPort());
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
void vtkManifoldHarmonicSmoothing::ForwardWarning(vtkObject*, unsigned long, void* data)
{
  // What vtkWarningMacro does with a message: to the observers, or else to the output window.
  if (this->HasObserver(vtkCommand::WarningEvent))
  {
    this->InvokeEvent(vtkCommand::WarningEvent, data);
  }
  else if (vtkObject::GetGlobalWarningDisplay())
  {
    vtkOutputWindowDisplayWarningText(static_cast<const char*>(data));
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
  this->UpdateFilter(); // collective: before any process returns
  if (this->AbortRequested())
  {
    return 1;
  }
  if (OnlyConstantHarmonics(this->Basis->GetOutput(), this->Filter))
  {
    vtkErrorMacro(<< "The " << this->NumberOfHarmonics
                  << " harmonic(s) are all constant (one per connected component of the surface, "
                     "frequency 0): there is nothing to smooth. Raise NumberOfHarmonics.");
    return 0;
  }
  output->ShallowCopy(input);
  vtkPointSet* filtered = this->Filter->GetOutput();
  if (filtered->GetNumberOfPoints() != input->GetNumberOfPoints())
  {
    if (input->GetNumberOfPoints() == 0)
    {
      return 1;
    }
    vtkErrorMacro(<< "Manifold harmonic smoothing failed (see the errors above).");
    return 0;
  }
  output->SetPoints(filtered->GetPoints());
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
void vtkManifoldHarmonicSmoothing::UpdateFilter()
{
  this->Transform->SetNumberOfThreads(this->NumberOfThreads);
  this->Transform->Update();
  this->UpdateProgress(0.9);
  this->SetProgressText("Spectral filter");
  this->Filter->SetNumberOfThreads(this->NumberOfThreads);
  this->Filter->SetCutoff(this->CutoffFraction);
  this->Filter->Update();
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
