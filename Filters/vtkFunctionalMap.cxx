// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkFunctionalMap.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicsArrays.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkManifoldHarmonicsParameters.h"
#include "vtkManifoldHarmonicsStages.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkSmartPointer.h"
#include "vtkTable.h"
#include "vtkWeakPointer.h"

#include "Spectral/Common/Monitor.h"
#include "Spectral/Filtering/FunctionalMap.h"
#include "Spectral/Operators/Operators.h"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

vtkStandardNewMacro(vtkFunctionalMap);

namespace Names = vtkManifoldHarmonicsNames;

namespace
{
// The roles of the two input ports, for the messages.
const char* const RoleOfPort[2] = { "target (input port 0, Input)",
  "source (input port 1, Source)" };

//------------------------------------------------------------------------------
// How a source array reaches the target.
enum class Route
{
  PointMap,      // x_target(j) = x_source(CorrespondingPointIds[j])
  FunctionalMap, // x_target = Phi_target C Phi_source^T M_source x_source
};

struct Transfer
{
  vtkAbstractArray* Array;
  Route Way;
};

//------------------------------------------------------------------------------
bool Contains(const std::vector<std::string>& list, const char* name)
{
  return std::find(list.begin(), list.end(), name) != list.end();
}

//------------------------------------------------------------------------------
// Appends `name` to `list` unless it is null or there already. \return whether it was added.
bool AddName(std::vector<std::string>& list, const char* name)
{
  if (!name || Contains(list, name))
  {
    return false;
  }
  list.emplace_back(name);
  return true;
}

//------------------------------------------------------------------------------
// The name at `index`, or null out of range.
const char* NameAt(const std::vector<std::string>& list, int index)
{
  return index >= 0 && index < static_cast<int>(list.size()) ? list[index].c_str() : nullptr;
}

//------------------------------------------------------------------------------
bool IsFloating(vtkAbstractArray* array)
{
  return array->GetDataType() == VTK_FLOAT || array->GetDataType() == VTK_DOUBLE;
}

//------------------------------------------------------------------------------
// Whether a source point array is one the filter does not transfer: the basis arrays (each
// shape has its own), the ghost array, the arrays this filter writes, unnamed arrays.
bool IsLeftOut(vtkAbstractArray* array)
{
  const char* name = array->GetName();
  if (!name)
  {
    return true;
  }
  const std::string text(name);
  return text == Names::Harmonics || text == Names::Mass ||
    text == vtkDataSetAttributes::GhostArrayName() || text == Names::CorrespondingPointIds ||
    text == Names::AlignedHarmonics;
}

//------------------------------------------------------------------------------
// The transfers the settings ask for, checked before anything is computed.
// \throws spectral::InvalidInput for a list naming an array twice, an unknown array, an integer
// or non-numeric array through the functional map.
std::vector<Transfer> PlanTransfers(vtkPointSet* source,
  bool transferArrays,
  const std::vector<std::string>& smooth,
  const std::vector<std::string>& labels)
{
  vtkPointData* pd = source->GetPointData();
  for (const std::vector<std::string>* list : { &smooth, &labels })
  {
    for (const std::string& name : *list)
    {
      if (Contains(list == &smooth ? labels : smooth, name.c_str()))
      {
        throw spectral::InvalidInput(
          "the array '" + name + "' is in both SmoothArrays and LabelArrays: choose one route");
      }
      if (!pd->GetAbstractArray(name.c_str()))
      {
        throw spectral::InvalidInput("the source has no point array '" + name + "' (named in " +
          (list == &smooth ? "SmoothArrays" : "LabelArrays") + ")");
      }
    }
  }
  std::vector<Transfer> plan;
  for (int a = 0; transferArrays && a < pd->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = pd->GetAbstractArray(a);
    if (IsLeftOut(array))
    {
      continue;
    }
    const bool smoothWanted = Contains(smooth, array->GetName());
    if (smoothWanted && !IsFloating(array))
    {
      throw spectral::InvalidInput(std::string("the array '") + array->GetName() + "' (" +
        array->GetDataTypeAsString() +
        ") is in SmoothArrays: the functional map gives it values between its integers; "
        "transfer it as a label or make it a floating-point array first");
    }
    const bool smoothRoute =
      smoothWanted || (IsFloating(array) && !Contains(labels, array->GetName()));
    plan.push_back({ array, smoothRoute ? Route::FunctionalMap : Route::PointMap });
  }
  return plan;
}

//------------------------------------------------------------------------------
// The landmark pairs (source point, target point) of the two lists.
// \throws spectral::InvalidInput for lists of different lengths or ids out of range.
std::vector<std::pair<int, int>> LandmarkPairs(vtkIdList* sourceIds,
  vtkIdList* targetIds,
  vtkIdType sourcePoints,
  vtkIdType targetPoints)
{
  if (sourceIds->GetNumberOfIds() != targetIds->GetNumberOfIds())
  {
    throw spectral::InvalidInput("SourceLandmarks has " +
      std::to_string(sourceIds->GetNumberOfIds()) + " ids and TargetLandmarks " +
      std::to_string(targetIds->GetNumberOfIds()) + ": landmarks are pairs, one id of each");
  }
  std::vector<std::pair<int, int>> pairs;
  for (vtkIdType l = 0; l < sourceIds->GetNumberOfIds(); ++l)
  {
    const vtkIdType s = sourceIds->GetId(l);
    const vtkIdType t = targetIds->GetId(l);
    if (s < 0 || s >= sourcePoints || t < 0 || t >= targetPoints)
    {
      throw spectral::InvalidInput("landmark " + std::to_string(l) + " (source point " +
        std::to_string(s) + ", target point " + std::to_string(t) +
        ") is out of range: the source has " + std::to_string(sourcePoints) +
        " points, the target " + std::to_string(targetPoints));
    }
    pairs.emplace_back(static_cast<int>(s), static_cast<int>(t));
  }
  return pairs;
}

//------------------------------------------------------------------------------
// One shape as the core takes it, from a point set with basis arrays.
// \throws spectral::InvalidInput when the basis arrays are missing or inconsistent.
spectral::SpectralShape ShapeOf(vtkPointSet* withBasis, const char* role)
{
  vtkManifoldHarmonicsArrays::Basis basis;
  const std::string problem = vtkManifoldHarmonicsArrays::FindBasis(withBasis, basis);
  if (!problem.empty())
  {
    throw spectral::InvalidInput(std::string("the ") + role + ": " + problem);
  }
  spectral::SpectralShape shape;
  const Eigen::Index n = basis.NumberOfPoints;
  const Eigen::Index m = basis.NumberOfHarmonics;
  if (basis.Doubles)
  {
    shape.Harmonics = spectral::BasisView(basis.Doubles, n, m);
  }
  else
  {
    shape.Harmonics = spectral::FloatBasisView(basis.Floats, n, m).cast<double>();
  }
  shape.Eigenvalues = basis.EigenvalueVector();
  // The transform's weights: a welded seam point's mass counts once, on the copy that owns it
  // (the other copies, flagged DUPLICATEPOINT, keep their harmonics and find their own match).
  shape.Mass = vtkManifoldHarmonicsStages::OwnedMass(basis, withBasis);
  spectral::TriangleMesh mesh = vtkManifoldHarmonicsArrays::ToCoreMesh(withBasis).Mesh;
  shape.Vertices = std::move(mesh.Vertices);
  shape.Faces = std::move(mesh.Faces);
  return shape;
}

//------------------------------------------------------------------------------
// `array` through the point map: exact values; the type's NaN or 0 where there is no match.
vtkSmartPointer<vtkAbstractArray> ThroughPoints(vtkAbstractArray* array,
  const std::vector<int>& ids,
  const std::string& name)
{
  auto out = vtk::TakeSmartPointer(array->NewInstance());
  out->SetName(name.c_str());
  out->SetNumberOfComponents(array->GetNumberOfComponents());
  out->CopyComponentNames(array);
  out->SetNumberOfTuples(static_cast<vtkIdType>(ids.size()));
  vtkNew<vtkIdList> to;
  vtkNew<vtkIdList> from;
  vtkDataArray* values = vtkDataArray::SafeDownCast(out);
  const double none = IsFloating(array) ? std::numeric_limits<double>::quiet_NaN() : 0.0;
  for (std::size_t j = 0; j < ids.size(); ++j)
  {
    if (ids[j] >= 0)
    {
      to->InsertNextId(static_cast<vtkIdType>(j));
      from->InsertNextId(ids[j]);
    }
    else if (values)
    {
      for (int c = 0; c < values->GetNumberOfComponents(); ++c)
      {
        values->SetComponent(static_cast<vtkIdType>(j), c, none);
      }
    }
  }
  out->InsertTuples(to, from, array);
  return out;
}

//------------------------------------------------------------------------------
// `array` (floating point) through the functional map; NaN where there is no match.
vtkSmartPointer<vtkAbstractArray> ThroughMap(vtkAbstractArray* array,
  const spectral::SpectralShape& source,
  const spectral::SpectralShape& target,
  const spectral::FunctionalMapResult& result,
  const std::string& name)
{
  vtkDataArray* data = vtkDataArray::SafeDownCast(array);
  const vtkManifoldHarmonicsArrays::Signal signal(data);
  spectral::RowMatrix values =
    spectral::TransferThroughMap(source, target, result.Map, signal.View());
  for (std::size_t j = 0; j < result.CorrespondingPointIds.size(); ++j)
  {
    if (result.CorrespondingPointIds[j] < 0)
    {
      values.row(static_cast<Eigen::Index>(j))
        .setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    else if (!values.row(static_cast<Eigen::Index>(j)).allFinite())
    {
      // One NaN or infinity on the source's surface spreads over all its coefficients.
      throw spectral::InvalidInput(vtkManifoldHarmonicsArrays::NotFiniteOnSurface(array->GetName(),
        "its transfer through the functional map",
        "Transfer it as a label (LabelArrays) or leave it out (TransferArrays off)"));
    }
  }
  return vtkManifoldHarmonicsArrays::NewArrayLike(data, values, name.c_str());
}

//------------------------------------------------------------------------------
// The output array of a transfer: the source's name, or `<name>_Transferred` when the target
// already has a point array of that name.
std::string TransferredName(vtkPointSet* target, vtkAbstractArray* array)
{
  const char* name = array->GetName();
  return target->GetPointData()->GetAbstractArray(name)
    ? Names::Concatenate(name, Names::TransferredSuffix)
    : std::string(name);
}

//------------------------------------------------------------------------------
// The map C as a table: k rows (target harmonics), one column per source harmonic.
void FillMapTable(vtkTable* table, const spectral::DenseMatrix& map)
{
  for (Eigen::Index j = 0; j < map.cols(); ++j)
  {
    const spectral::RowMatrix column = map.col(j);
    table->AddColumn(vtkManifoldHarmonicsArrays::NewDoubleArray(
      column, Names::Concatenate(Names::MapColumnPrefix, std::to_string(j).c_str()).c_str()));
  }
}

//------------------------------------------------------------------------------
// CorrespondingPointIds as a vtkIdTypeArray.
vtkSmartPointer<vtkIdTypeArray> PointIdsArray(const std::vector<int>& ids)
{
  auto array = vtkSmartPointer<vtkIdTypeArray>::New();
  array->SetName(Names::CorrespondingPointIds);
  array->SetNumberOfTuples(static_cast<vtkIdType>(ids.size()));
  std::copy(ids.begin(), ids.end(), array->GetPointer(0));
  return array;
}
} // anonymous namespace

//------------------------------------------------------------------------------
// The internal bases (one per input port, kept between executions), the landmark lists, the
// progress offset of the basis being computed and its error.
struct vtkFunctionalMap::Internals
{
  struct Slot
  {
    vtkSmartPointer<vtkPointSet> Copy;    // shallow copy of the input, replaced when it changes
    vtkWeakPointer<vtkPointSet> Data;     // the input object of that copy
    vtkMTimeType Time = 0;                // and its MTime then
    vtkSmartPointer<vtkManifoldHarmonicBasis> Basis;
  };
  Slot Slots[2];
  vtkNew<vtkIdList> SourceLandmarks;
  vtkNew<vtkIdList> TargetLandmarks;
  double ProgressOffset = 0.0;
  std::string BasisError; // the last error of an internal basis during its update
};

//------------------------------------------------------------------------------
vtkFunctionalMap::vtkFunctionalMap()
  : vtkManifoldHarmonicsAlgorithm(POINT_SET_AND_TABLE)
  , NumberOfHarmonics(vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS)
  , MinimumComponentSize(0)
  , MemoryLimit(0.0)
  , TransferArrays(true)
  , AlignHarmonics(false)
  , Internal(new Internals)
{
  this->SetNumberOfInputPorts(2);
  const spectral::FunctionalMapOptions defaults;
  this->InitialSize = defaults.InitialSize;
  this->FinalSize = defaults.FinalSize;
  this->ZoomOutStep = defaults.ZoomOutStep;
  this->ZoomOutSamples = defaults.ZoomOutSamples;
  this->NumberOfDescriptors = defaults.NumberOfDescriptors;
  this->DescriptorWeight = defaults.DescriptorWeight;
  this->CommutativityWeight = defaults.CommutativityWeight;
  this->LandmarkWeight = defaults.LandmarkWeight;
  this->OrientationWeight = defaults.OrientationWeight;
  this->OrientationTerm = defaults.OrientationTerm;
}

//------------------------------------------------------------------------------
vtkFunctionalMap::~vtkFunctionalMap() = default;

//------------------------------------------------------------------------------
int vtkFunctionalMap::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  if (port == 1)
  {
    // Optional for the executive, so that a missing source is this filter's clear error.
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::SetSourceConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::SetSourceData(vtkDataObject* source)
{
  this->SetInputData(1, source);
}

//------------------------------------------------------------------------------
vtkDataObject* vtkFunctionalMap::GetSource()
{
  return this->GetNumberOfInputConnections(1) > 0 ? this->GetInputDataObject(1, 0) : nullptr;
}

//------------------------------------------------------------------------------
int vtkFunctionalMap::Execute(vtkPointSet* target, vtkPointSet* output, vtkTable* table)
{
  // (The weights, NaN or not, are checked by the core: ComputeFunctionalMap.)
  if (!vtkManifoldHarmonicsParameters::AcceptNumbers(
        this, { { "MemoryLimit", this->MemoryLimit } }))
  {
    return 0;
  }
  vtkPointSet* inputs[2] = { target,
    this->GetNumberOfInputConnections(1) > 0
      ? vtkPointSet::SafeDownCast(this->GetExecutive()->GetInputData(1, 0))
      : nullptr };
  for (int port = 0; port < 2; ++port)
  {
    if (!inputs[port] || inputs[port]->GetNumberOfPoints() == 0)
    {
      vtkErrorMacro(<< "Functional map failed: the " << RoleOfPort[port]
                    << (inputs[port] ? " has no points." : " is missing (SetSourceConnection)."));
      return 0;
    }
  }
  if (GetDistributedController())
  {
    vtkErrorMacro(<< "Functional map failed: it needs both whole surfaces on one process; run it "
                     "in a serial pipeline (or after gathering both shapes on one process).");
    return 0;
  }
  vtkPointSet* source = inputs[1];
  const std::vector<Transfer> plan =
    PlanTransfers(source, this->TransferArrays, this->SmoothArrays, this->LabelArrays);
  spectral::FunctionalMapOptions options;
  options.Landmarks = LandmarkPairs(this->Internal->SourceLandmarks,
    this->Internal->TargetLandmarks,
    source->GetNumberOfPoints(),
    target->GetNumberOfPoints());
  vtkPointSet* withBasis[2] = { nullptr, nullptr };
  for (int port : { 1, 0 })
  {
    this->Internal->ProgressOffset = port == 1 ? 0.0 : 0.25;
    if (!this->UpdateBasis(port, inputs[port], withBasis[port]))
    {
      return 1; // aborted: the base empties the outputs
    }
  }
  const spectral::SpectralShape sourceShape = ShapeOf(withBasis[1], RoleOfPort[1]);
  const spectral::SpectralShape targetShape = ShapeOf(withBasis[0], RoleOfPort[0]);
  for (int port = 0; this->OrientationTerm && port < 2; ++port)
  {
    const long long conflicts =
      spectral::OrientationConflicts((port == 0 ? targetShape : sourceShape).Faces);
    if (conflicts > 0)
    {
      vtkWarningMacro(<< "OrientationTerm: " << conflicts << " edges of the " << RoleOfPort[port]
                      << " have their two triangles oriented alike (triangles turned over, or a "
                         "surface that cannot be oriented), and the term compares orientations: "
                         "the map may be wrong. Orient the triangles consistently first "
                         "(Generate Surface Normals in ParaView, vtkPolyDataNormals, with "
                         "Consistency on), or turn OrientationTerm off.");
    }
  }
  options.InitialSize = this->InitialSize;
  options.FinalSize = this->FinalSize;
  options.ZoomOutStep = this->ZoomOutStep;
  options.ZoomOutSamples = this->ZoomOutSamples;
  options.NumberOfDescriptors = this->NumberOfDescriptors;
  options.DescriptorWeight = this->DescriptorWeight;
  options.CommutativityWeight = this->CommutativityWeight;
  options.LandmarkWeight = this->LandmarkWeight;
  options.OrientationWeight = this->OrientationWeight;
  options.OrientationTerm = this->OrientationTerm;
  options.Threads = this->NumberOfThreads;
  vtkDebugMacro(<< "Functional map of sizes " << options.InitialSize << " to " << options.FinalSize
                << " with " << options.Landmarks.size() << " landmarks");
  spectral::Monitor monitor = this->MakeMonitor();
  monitor.Progress = [this](double fraction) { this->UpdateProgress(0.5 + 0.4 * fraction); };
  const spectral::FunctionalMapResult result =
    spectral::ComputeFunctionalMap(sourceShape, targetShape, options, monitor);
  if (this->AbortRequested())
  {
    return 1;
  }
  this->SetProgressText("Transfer");
  output->ShallowCopy(target);
  for (const Transfer& transfer : plan)
  {
    const std::string name = TransferredName(target, transfer.Array);
    output->GetPointData()->AddArray(transfer.Way == Route::PointMap
        ? ThroughPoints(transfer.Array, result.CorrespondingPointIds, name)
        : ThroughMap(transfer.Array, sourceShape, targetShape, result, name));
  }
  output->GetPointData()->AddArray(PointIdsArray(result.CorrespondingPointIds));
  if (this->AlignHarmonics)
  {
    output->GetPointData()->AddArray(vtkManifoldHarmonicsArrays::NewDoubleArray(
      spectral::AlignModes(sourceShape, targetShape, result.Map), Names::AlignedHarmonics));
  }
  FillMapTable(table, result.Map);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
vtkTable* vtkFunctionalMap::GetMapOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
// MemoryLimit less what the other port's internal basis holds (its harmonics and mass); at
// least one byte, since 0 would mean the system's memory.
double vtkFunctionalMap::BasisMemoryLimit(int port) const
{
  double limit = this->MemoryLimit;
  const Internals::Slot& other = this->Internal->Slots[1 - port];
  if (limit <= 0.0 || !other.Basis)
  {
    return limit;
  }
  if (vtkDataSet* held =
        vtkDataSet::SafeDownCast(vtkDataObject::GetData(other.Basis->GetOutputInformation(0))))
  {
    for (const char* name : { Names::Harmonics, Names::Mass })
    {
      if (vtkDataArray* array = held->GetPointData()->GetArray(name))
      {
        limit -= static_cast<double>(array->GetActualMemorySize()) / 1024.0; // KiB
      }
    }
  }
  return std::max(limit, 1.0 / 1048576.0);
}

//------------------------------------------------------------------------------
bool vtkFunctionalMap::UpdateBasis(int port, vtkPointSet* input, vtkPointSet*& withBasis)
{
  if (input->GetPointData()->GetArray(Names::Harmonics))
  {
    withBasis = input; // its own basis (checked by ShapeOf)
    return true;
  }
  Internals::Slot& slot = this->Internal->Slots[port];
  if (!slot.Basis)
  {
    slot.Basis = vtkSmartPointer<vtkManifoldHarmonicBasis>::New();
    slot.Basis->AddObserver(vtkCommand::ProgressEvent, this, &vtkFunctionalMap::ForwardProgress);
    slot.Basis->AddObserver(vtkCommand::WarningEvent, this, &vtkFunctionalMap::ForwardWarning);
    slot.Basis->AddObserver(vtkCommand::ErrorEvent, this, &vtkFunctionalMap::RecordBasisError);
    // Its executive's "returned failure" follows the basis's own error: kept if alone.
    slot.Basis->GetExecutive()->AddObserver(
      vtkCommand::ErrorEvent, this, &vtkFunctionalMap::RecordBasisError);
  }
  // A new input (or the same one modified) solves again; new map settings alone do not.
  if (input != slot.Data.GetPointer() || input->GetMTime() != slot.Time)
  {
    if (!slot.Copy || !slot.Copy->IsA(input->GetClassName()))
    {
      slot.Copy = vtk::TakeSmartPointer(input->NewInstance());
      slot.Basis->SetInputData(slot.Copy);
    }
    slot.Copy->ShallowCopy(input);
    slot.Data = input;
    slot.Time = input->GetMTime();
  }
  this->SetProgressText(port == 1 ? "Basis of the source" : "Basis of the target");
  slot.Basis->SetNumberOfHarmonics(this->NumberOfHarmonics);
  slot.Basis->SetMinimumComponentSize(this->MinimumComponentSize);
  slot.Basis->SetNumberOfThreads(this->NumberOfThreads);
  slot.Basis->SetMemoryLimit(this->BasisMemoryLimit(port));
  slot.Basis->SetAbortExecute(this->GetAbortExecute());
  this->Internal->BasisError.clear();
  slot.Basis->Update();
  if (this->GetAbortExecute() || slot.Basis->GetAbortExecute())
  {
    slot.Basis->Modified(); // incomplete: solved afresh next time
    return false;
  }
  if (!this->Internal->BasisError.empty())
  {
    // The internal basis's error as this filter's one message (it names the input).
    throw spectral::InvalidInput(std::string("the basis of the ") + RoleOfPort[port] +
      " failed: " + this->Internal->BasisError);
  }
  withBasis = slot.Basis->GetOutput();
  return true;
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::ForwardProgress(vtkObject* caller, unsigned long, void* data)
{
  this->UpdateProgress(this->Internal->ProgressOffset + 0.25 * *static_cast<double*>(data));
  if (this->GetAbortExecute())
  {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  }
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::RecordBasisError(vtkObject*, unsigned long, void* data)
{
  if (this->Internal->BasisError.empty())
  {
    this->Internal->BasisError = data ? static_cast<const char*>(data) : "unknown error";
  }
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::SetNumberOfHarmonics(int m)
{
  if (vtkManifoldHarmonicsParameters::AcceptNumberOfHarmonics(this, m, this->NumberOfHarmonics) &&
    m != this->NumberOfHarmonics)
  {
    this->NumberOfHarmonics = m;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::SetSourceLandmarks(vtkIdList* ids)
{
  this->Internal->SourceLandmarks->DeepCopy(ids);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::SetTargetLandmarks(vtkIdList* ids)
{
  this->Internal->TargetLandmarks->DeepCopy(ids);
  this->Modified();
}

//------------------------------------------------------------------------------
vtkIdList* vtkFunctionalMap::GetSourceLandmarks()
{
  return this->Internal->SourceLandmarks;
}

//------------------------------------------------------------------------------
vtkIdList* vtkFunctionalMap::GetTargetLandmarks()
{
  return this->Internal->TargetLandmarks;
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::AddSourceLandmark(vtkIdType id)
{
  this->Internal->SourceLandmarks->InsertNextId(id);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::AddTargetLandmark(vtkIdType id)
{
  this->Internal->TargetLandmarks->InsertNextId(id);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::RemoveAllSourceLandmarks()
{
  if (this->Internal->SourceLandmarks->GetNumberOfIds() > 0)
  {
    this->Internal->SourceLandmarks->Reset();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::RemoveAllTargetLandmarks()
{
  if (this->Internal->TargetLandmarks->GetNumberOfIds() > 0)
  {
    this->Internal->TargetLandmarks->Reset();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkMTimeType vtkFunctionalMap::GetMTime()
{
  return std::max({ this->Superclass::GetMTime(), this->Internal->SourceLandmarks->GetMTime(),
    this->Internal->TargetLandmarks->GetMTime() });
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::AddSmoothArray(const char* name)
{
  if (AddName(this->SmoothArrays, name))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::RemoveAllSmoothArrays()
{
  if (!this->SmoothArrays.empty())
  {
    this->SmoothArrays.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkFunctionalMap::GetNumberOfSmoothArrays()
{
  return static_cast<int>(this->SmoothArrays.size());
}

//------------------------------------------------------------------------------
const char* vtkFunctionalMap::GetSmoothArray(int index)
{
  return NameAt(this->SmoothArrays, index);
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::AddLabelArray(const char* name)
{
  if (AddName(this->LabelArrays, name))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::RemoveAllLabelArrays()
{
  if (!this->LabelArrays.empty())
  {
    this->LabelArrays.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkFunctionalMap::GetNumberOfLabelArrays()
{
  return static_cast<int>(this->LabelArrays.size());
}

//------------------------------------------------------------------------------
const char* vtkFunctionalMap::GetLabelArray(int index)
{
  return NameAt(this->LabelArrays, index);
}

//------------------------------------------------------------------------------
const char* vtkFunctionalMap::CorrespondingPointIdsArrayName()
{
  return Names::CorrespondingPointIds;
}

//------------------------------------------------------------------------------
const char* vtkFunctionalMap::AlignedHarmonicsArrayName()
{
  return Names::AlignedHarmonics;
}

//------------------------------------------------------------------------------
const char* vtkFunctionalMap::TransferredSuffix()
{
  return Names::TransferredSuffix;
}

//------------------------------------------------------------------------------
const char* vtkFunctionalMap::MapColumnPrefix()
{
  return Names::MapColumnPrefix;
}

//------------------------------------------------------------------------------
void vtkFunctionalMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const auto onOff = [](bool value) { return value ? "On" : "Off"; };
  const auto ids = [&os](vtkIdList* list) {
    for (vtkIdType l = 0; l < list->GetNumberOfIds(); ++l)
    {
      os << " " << list->GetId(l);
    }
    os << "\n";
  };
  const auto names = [&os](const std::vector<std::string>& list) {
    for (const std::string& name : list)
    {
      os << " " << name;
    }
    os << "\n";
  };
  os << indent << "NumberOfHarmonics: " << this->NumberOfHarmonics << "\n";
  os << indent << "MinimumComponentSize: " << this->MinimumComponentSize << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB"
     << (this->MemoryLimit > 0.0 ? "\n" : " (the memory the system reports available)\n");
  os << indent << "InitialSize: " << this->InitialSize << "\n";
  os << indent << "FinalSize: " << this->FinalSize << "\n";
  os << indent << "ZoomOutStep: " << this->ZoomOutStep << "\n";
  os << indent << "ZoomOutSamples: " << this->ZoomOutSamples << "\n";
  os << indent << "NumberOfDescriptors: " << this->NumberOfDescriptors << "\n";
  os << indent << "DescriptorWeight: " << this->DescriptorWeight << "\n";
  os << indent << "CommutativityWeight: " << this->CommutativityWeight << "\n";
  os << indent << "LandmarkWeight: " << this->LandmarkWeight << "\n";
  os << indent << "OrientationWeight: " << this->OrientationWeight << "\n";
  os << indent << "OrientationTerm: " << onOff(this->OrientationTerm) << "\n";
  os << indent << "SourceLandmarks:";
  ids(this->Internal->SourceLandmarks);
  os << indent << "TargetLandmarks:";
  ids(this->Internal->TargetLandmarks);
  os << indent << "TransferArrays: " << onOff(this->TransferArrays) << "\n";
  os << indent << "SmoothArrays:";
  names(this->SmoothArrays);
  os << indent << "LabelArrays:";
  names(this->LabelArrays);
  os << indent << "AlignHarmonics: " << onOff(this->AlignHarmonics) << "\n";
}
