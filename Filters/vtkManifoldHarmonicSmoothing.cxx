// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicSmoothing.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkSpectralFilter.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkManifoldHarmonicSmoothing);

static_assert(static_cast<int>(vtkManifoldHarmonicSmoothing::FLOAT) ==
      static_cast<int>(vtkManifoldHarmonicBasis::FLOAT) &&
    static_cast<int>(vtkManifoldHarmonicSmoothing::DOUBLE) ==
      static_cast<int>(vtkManifoldHarmonicBasis::DOUBLE),
  "BasisPrecision is passed on to vtkManifoldHarmonicBasis as is");

namespace
{
//------------------------------------------------------------------------------
// omega_max = sqrt(lambda_{m-1}) from the basis output, 0 when it has no eigenvalues (an empty
// piece of a distributed run).
double HighestFrequency(vtkPolyData* basisOutput)
{
  vtkDataArray* lambda =
    basisOutput->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  if (!lambda || lambda->GetNumberOfTuples() == 0)
  {
    return 0.0;
  }
  return std::sqrt(std::max(lambda->GetTuple1(lambda->GetNumberOfTuples() - 1), 0.0));
}
} // anonymous namespace

//------------------------------------------------------------------------------
vtkManifoldHarmonicSmoothing::vtkManifoldHarmonicSmoothing()
  : NumberOfHarmonics(100)
  , CutoffFraction(0.5)
  , BasisPrecision(DOUBLE)
{
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicSmoothing::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  vtkDebugMacro(<< "Smoothing with " << this->NumberOfHarmonics << " harmonics, cutoff fraction "
                << this->CutoffFraction << ", basis precision " << this->BasisPrecision);

  // The three stages on a shallow copy, so that the internal pipeline does not touch the input.
  // In a distributed run every process executes each stage (they are collective).
  vtkNew<vtkPolyData> copy;
  copy->ShallowCopy(input);
  this->SetProgressText("Basis");
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetNumberOfHarmonics(this->NumberOfHarmonics);
  basis->SetBasisPrecision(this->BasisPrecision);
  basis->SetInputData(copy);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputConnection(basis->GetOutputPort());
  transform->Update();
  this->UpdateProgress(0.9);
  if (this->GetAbortExecute())
  {
    return 1;
  }

  this->SetProgressText("Spectral filter");
  vtkNew<vtkSpectralFilter> filter;
  filter->SetFilterKindToLowPass();
  filter->SetCutoff(this->CutoffFraction * HighestFrequency(basis->GetOutput()));
  filter->SetInputConnection(transform->GetOutputPort());
  filter->Update();

  output->ShallowCopy(input);
  vtkPolyData* filtered = filter->GetOutput();
  if (filtered->GetNumberOfPoints() != input->GetNumberOfPoints())
  {
    if (input->GetNumberOfPoints() == 0)
    {
      return 1;
    }
    vtkErrorMacro(<< "Manifold harmonic smoothing failed (see the errors above).");
    output->Initialize();
    return 0;
  }
  output->SetPoints(filtered->GetPoints());
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicSmoothing::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfHarmonics: " << this->NumberOfHarmonics << " (default 100)\n";
  os << indent << "CutoffFraction: " << this->CutoffFraction << " (default 0.5)\n";
  os << indent << "BasisPrecision: " << (this->BasisPrecision == FLOAT ? "Float" : "Double")
     << " (default Double)\n";
}
