// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicsAlgorithm.h"

#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkManifoldHarmonicsArrays.h"
#include "vtkManifoldHarmonicsParallel.h"
#include "vtkObject.h"
#include "vtkOutputWindow.h"
#include "vtkPointSet.h"
#include "vtkTable.h"

#include "Spectral/Common/Mesh.h"
#include "Spectral/Common/Monitor.h"

//------------------------------------------------------------------------------
vtkManifoldHarmonicsAlgorithm::vtkManifoldHarmonicsAlgorithm(OutputPorts ports)
  : NumberOfThreads(0)
  , CancelRequested(false)
{
  this->SetNumberOfOutputPorts(static_cast<int>(ports));
}

//------------------------------------------------------------------------------
vtkManifoldHarmonicsAlgorithm::~vtkManifoldHarmonicsAlgorithm() = default;

//------------------------------------------------------------------------------
int vtkManifoldHarmonicsAlgorithm::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicsAlgorithm::RequestDataObject(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  return vtkManifoldHarmonicsArrays::OutputLikeInput(inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicsAlgorithm::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPointSet* output = vtkPointSet::GetData(outputVector, 0);
  vtkTable* table =
    this->GetNumberOfOutputPorts() > 1 ? vtkTable::GetData(outputVector, 1) : nullptr;
  this->CancelRequested = false;
  // An abort stops the request it was asked in, not the next one: VTK 9.2's executive leaves the
  // flag set after an aborted run (later versions clear it), which would empty every later output.
  this->AbortExecute = 0;
  int status = 0;
  const bool returned = this->Guard(
    [this, input, output, table, &status]() { status = this->Execute(input, output, table); });
  const bool aborted = this->CancelRequested || (returned && this->AbortRequested());
  const bool failed = !aborted && (!returned || status == 0);
  if (aborted)
  {
    this->AbortTime.Modified();
    this->AbortedOutput = outputVector->GetInformationObject(0)->Get(vtkDataObject::DATA_OBJECT());
  }
  if (aborted || failed)
  {
    // One rule for every filter: after an error or an abort, every output port is empty.
    for (int port = 0; port < this->GetNumberOfOutputPorts(); ++port)
    {
      if (vtkDataObject* data =
            outputVector->GetInformationObject(port)->Get(vtkDataObject::DATA_OBJECT()))
      {
        data->Initialize();
      }
    }
  }
  return failed ? 0 : 1;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkManifoldHarmonicsAlgorithm::GetMTime()
{
  // The executive marks the emptied outputs of an aborted request as generated after
  // RequestData, later than the settings: the next request would find them up to date.
  if (this->AbortedOutput && this->AbortedOutput->GetUpdateTime() > this->AbortTime.GetMTime())
  {
    this->AbortedOutput = nullptr;
    this->Modified();
  }
  return this->Superclass::GetMTime();
}

//------------------------------------------------------------------------------
std::string vtkManifoldHarmonicsAlgorithm::DescribeFailure(const std::exception& e)
{
  return std::string(this->GetWorkName()) + " failed: " + e.what();
}

//------------------------------------------------------------------------------
bool vtkManifoldHarmonicsAlgorithm::Guard(const std::function<void()>& work)
{
  try
  {
    work();
    return true;
  }
  catch (const spectral::Cancelled&)
  {
    this->CancelRequested = true;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< this->DescribeFailure(e));
  }
  return false;
}

//------------------------------------------------------------------------------
spectral::Monitor vtkManifoldHarmonicsAlgorithm::MakeMonitor(double scale)
{
  spectral::Monitor monitor;
  monitor.Progress = [this, scale](double fraction) { this->UpdateProgress(scale * fraction); };
  monitor.Cancelled = [this]() { return this->GetAbortExecute() != 0; };
  monitor.Stage = [this](const char* stage) { this->SetProgressText(stage); };
  monitor.Warning = [this](const std::string& text) { vtkWarningMacro(<< text); };
  return monitor;
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicsAlgorithm::ForwardWarning(vtkObject*, unsigned long event, void* data)
{
  // What vtkWarningMacro (vtkErrorMacro) does with a message: to the observers, or else to the
  // output window.
  if (this->HasObserver(event))
  {
    this->InvokeEvent(event, data);
  }
  else if (event == vtkCommand::ErrorEvent)
  {
    vtkOutputWindowDisplayErrorText(static_cast<const char*>(data));
  }
  else if (vtkObject::GetGlobalWarningDisplay())
  {
    vtkOutputWindowDisplayWarningText(static_cast<const char*>(data));
  }
}

//------------------------------------------------------------------------------
vtkMultiProcessController* vtkManifoldHarmonicsAlgorithm::GetDistributedController()
{
  return vtkManifoldHarmonicsParallel::DistributedController();
}

//------------------------------------------------------------------------------
bool vtkManifoldHarmonicsAlgorithm::AbortRequested()
{
  return this->GetAbortExecute() != 0 && !GetDistributedController();
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicsAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
