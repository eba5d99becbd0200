// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicsParallel.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCommunicator.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkManifoldHarmonicsGhosts.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>

namespace
{
// Message tags, distinct from those of ParaView (which uses small numbers and multiples of 1000).
constexpr int PieceTag = 718201;
constexpr int BasisTag = 718202;
constexpr int SumTag = 718203;

//------------------------------------------------------------------------------
// Points (n by 3 doubles), their ownership (1 for a point the piece owns, 0 for a ghost copy of
// another process's point) and triangles (3-component ids) of a piece, exact copies.
void PieceArrays(vtkPolyData* piece,
  vtkDoubleArray* points,
  vtkUnsignedCharArray* owned,
  vtkIdTypeArray* triangles)
{
  points->SetNumberOfComponents(3);
  triangles->SetNumberOfComponents(3);
  if (!piece || !piece->GetPoints())
  {
    return;
  }
  points->DeepCopy(piece->GetPoints()->GetData());
  const spectral::Vector ownedPoints = vtkManifoldHarmonicsGhosts::OwnedPoints(piece);
  owned->SetNumberOfTuples(ownedPoints.size());
  for (vtkIdType i = 0; i < owned->GetNumberOfTuples(); ++i)
  {
    owned->SetValue(i, ownedPoints[i] > 0.0 ? 1 : 0);
  }
  auto cells = vtk::TakeSmartPointer(piece->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType npts;
    const vtkIdType* pts;
    cells->GetCurrentCell(npts, pts);
    if (npts == 3)
    {
      triangles->InsertNextTypedTuple(pts);
    }
  }
}

//------------------------------------------------------------------------------
// Point-to-point exchange of a data array that may be empty: a count, then the array if any.
void SendArray(vtkMultiProcessController* controller, vtkDataArray* array, int remote, int tag)
{
  vtkIdType count = array->GetNumberOfTuples();
  controller->Send(&count, 1, remote, tag);
  if (count > 0)
  {
    controller->Send(array, remote, tag);
  }
}

//------------------------------------------------------------------------------
void ReceiveArray(vtkMultiProcessController* controller, vtkDataArray* array, int remote, int tag)
{
  vtkIdType count = 0;
  controller->Receive(&count, 1, remote, tag);
  if (count > 0)
  {
    controller->Receive(array, remote, tag);
  }
  else
  {
    array->SetNumberOfTuples(0);
  }
}

//------------------------------------------------------------------------------
// Adds the triangles of one piece to the merged mesh, renumbered by the piece's point map.
void AddTriangles(vtkIdTypeArray* triangles,
  const std::vector<vtkIdType>& map,
  vtkCellArray* mergedTriangles)
{
  for (vtkIdType t = 0; t < triangles->GetNumberOfTuples(); ++t)
  {
    const vtkIdType ids[3] = { map[triangles->GetTypedComponent(t, 0)],
      map[triangles->GetTypedComponent(t, 1)],
      map[triangles->GetTypedComponent(t, 2)] };
    mergedTriangles->InsertNextCell(3, ids);
  }
}

//------------------------------------------------------------------------------
// The rows of the points of one piece, and their duplicate flags (owned by another rank).
void PieceRows(int rank,
  const vtkManifoldHarmonicsParallel::MergedMesh& merged,
  const spectral::RowMatrix& harmonics,
  const spectral::Vector& mass,
  vtkManifoldHarmonicsParallel::PieceBasis& piece)
{
  const std::vector<vtkIdType>& map = merged.PointMaps[rank];
  const vtkIdType n = static_cast<vtkIdType>(map.size());
  const int m = static_cast<int>(harmonics.cols());
  piece.Harmonics->SetNumberOfComponents(m);
  piece.Harmonics->SetNumberOfTuples(n);
  piece.Mass->SetNumberOfTuples(n);
  piece.Duplicates->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const vtkIdType j = map[i];
    std::copy(
      harmonics.row(j).data(), harmonics.row(j).data() + m, piece.Harmonics->GetPointer(i * m));
    piece.Mass->SetValue(i, mass[j]);
    piece.Duplicates->SetValue(
      i, merged.Counted[rank][i] ? 0 : vtkManifoldHarmonicsGhosts::NotOwnedPointFlag);
  }
}

//------------------------------------------------------------------------------
// A named m by c matrix as a vtkDoubleArray and back.
vtkSmartPointer<vtkDoubleArray> ToArray(const std::string& name, const spectral::RowMatrix& values)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(static_cast<int>(std::max<Eigen::Index>(values.cols(), 1)));
  array->SetNumberOfTuples(values.rows());
  std::copy(values.data(), values.data() + values.size(), array->GetPointer(0));
  return array;
}

spectral::RowMatrix FromArray(vtkDoubleArray* array)
{
  return Eigen::Map<const spectral::RowMatrix>(
    array->GetPointer(0), array->GetNumberOfTuples(), array->GetNumberOfComponents());
}

//------------------------------------------------------------------------------
// Sends a list of named matrices (the eigenvalues as one more, under their array name).
void SendMatrices(vtkMultiProcessController* controller,
  const std::vector<vtkManifoldHarmonicsParallel::NamedMatrix>& matrices,
  const spectral::Vector& eigenvalues,
  int remote)
{
  int count = static_cast<int>(matrices.size()) + 1;
  controller->Send(&count, 1, remote, SumTag);
  for (const auto& matrix : matrices)
  {
    SendArray(controller, ToArray(matrix.Name, matrix.Values), remote, SumTag);
  }
  SendArray(
    controller, ToArray(vtkManifoldHarmonicsNames::Eigenvalues, eigenvalues), remote, SumTag);
}

//------------------------------------------------------------------------------
void ReceiveMatrices(vtkMultiProcessController* controller,
  std::vector<vtkManifoldHarmonicsParallel::NamedMatrix>& matrices,
  spectral::Vector& eigenvalues,
  int remote)
{
  int count = 0;
  controller->Receive(&count, 1, remote, SumTag);
  matrices.clear();
  for (int a = 0; a < count; ++a)
  {
    vtkNew<vtkDoubleArray> array;
    ReceiveArray(controller, array, remote, SumTag);
    const std::string name = array->GetName() ? array->GetName() : "";
    if (a + 1 == count)
    {
      eigenvalues = FromArray(array).col(0);
    }
    else
    {
      matrices.push_back({ name, FromArray(array) });
    }
  }
}

//------------------------------------------------------------------------------
// Adds the matrices of one process into the running sums; false on a shape mismatch.
bool Accumulate(const std::vector<vtkManifoldHarmonicsParallel::NamedMatrix>& matrices,
  const spectral::Vector& eigenvalues,
  std::vector<vtkManifoldHarmonicsParallel::NamedMatrix>& sums,
  spectral::Vector& firstEigenvalues)
{
  if (firstEigenvalues.size() == 0)
  {
    firstEigenvalues = eigenvalues;
  }
  bool ok = true;
  for (const auto& matrix : matrices)
  {
    auto found = std::find_if(sums.begin(),
      sums.end(),
      [&matrix](const vtkManifoldHarmonicsParallel::NamedMatrix& s)
      { return s.Name == matrix.Name; });
    if (found == sums.end())
    {
      sums.push_back(matrix);
    }
    else if (found->Values.rows() == matrix.Values.rows() &&
      found->Values.cols() == matrix.Values.cols())
    {
      found->Values += matrix.Values;
    }
    else
    {
      ok = false;
    }
  }
  return ok;
}
} // anonymous namespace

namespace vtkManifoldHarmonicsParallel
{
//------------------------------------------------------------------------------
vtkMultiProcessController* DistributedController()
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return controller && controller->GetNumberOfProcesses() > 1 ? controller : nullptr;
}

//------------------------------------------------------------------------------
int CountRanks(vtkMultiProcessController* controller, bool hasData)
{
  const int local = hasData ? 1 : 0;
  int total = 0;
  controller->AllReduce(&local, &total, 1, vtkCommunicator::SUM_OP);
  return total;
}

//------------------------------------------------------------------------------
MergedMesh GatherAndMerge(vtkMultiProcessController* controller,
  vtkPolyData* piece,
  double tolerance)
{
  MergedMesh merged;
  vtkNew<vtkDoubleArray> points;
  vtkNew<vtkUnsignedCharArray> owned;
  vtkNew<vtkIdTypeArray> triangles;
  PieceArrays(piece, points, owned, triangles);
  const int rank = controller->GetLocalProcessId();
  if (rank != 0)
  {
    SendArray(controller, points, 0, PieceTag);
    SendArray(controller, owned, 0, PieceTag);
    SendArray(controller, triangles, 0, PieceTag);
    return merged;
  }

  // All points in rank order, with their ownership (1 where a piece has no ghost array).
  const int size = controller->GetNumberOfProcesses();
  std::vector<vtkSmartPointer<vtkIdTypeArray>> allTriangles(size);
  std::vector<vtkIdType> offsets(size + 1, 0);
  vtkNew<vtkDoubleArray> allPoints;
  allPoints->SetNumberOfComponents(3);
  std::vector<unsigned char> allOwned;
  for (int r = 0; r < size; ++r)
  {
    vtkSmartPointer<vtkDoubleArray> rankPoints = points;
    vtkSmartPointer<vtkUnsignedCharArray> rankOwned = owned;
    allTriangles[r] = triangles;
    if (r > 0)
    {
      rankPoints = vtkSmartPointer<vtkDoubleArray>::New();
      rankPoints->SetNumberOfComponents(3);
      rankOwned = vtkSmartPointer<vtkUnsignedCharArray>::New();
      allTriangles[r] = vtkSmartPointer<vtkIdTypeArray>::New();
      allTriangles[r]->SetNumberOfComponents(3);
      ReceiveArray(controller, rankPoints, r, PieceTag);
      ReceiveArray(controller, rankOwned, r, PieceTag);
      ReceiveArray(controller, allTriangles[r], r, PieceTag);
    }
    const vtkIdType n = rankPoints->GetNumberOfTuples();
    offsets[r + 1] = offsets[r] + n;
    const bool hasOwnership = rankOwned->GetNumberOfTuples() == n;
    for (vtkIdType i = 0; i < n; ++i)
    {
      allPoints->InsertNextTuple(i, rankPoints);
      allOwned.push_back(hasOwnership ? rankOwned->GetValue(i) : 1);
    }
  }
  // The first copy of a merged point gives its coordinates.
  const Welding welding = WeldPoints(
    allPoints->GetPointer(0), allPoints->GetNumberOfTuples(), nullptr, tolerance, allOwned);
  vtkNew<vtkPoints> mergedPoints;
  mergedPoints->SetDataTypeToDouble();
  mergedPoints->SetNumberOfPoints(static_cast<vtkIdType>(welding.First.size()));
  for (std::size_t j = 0; j < welding.First.size(); ++j)
  {
    mergedPoints->SetPoint(static_cast<vtkIdType>(j), allPoints->GetTuple3(welding.First[j]));
  }
  vtkNew<vtkCellArray> mergedTriangles;
  merged.PointMaps.resize(size);
  merged.Counted.resize(size);
  for (int r = 0; r < size; ++r)
  {
    for (vtkIdType g = offsets[r]; g < offsets[r + 1]; ++g)
    {
      merged.PointMaps[r].push_back(welding.Map[g]);
      merged.Counted[r].push_back(welding.Counted[welding.Map[g]] == g);
    }
    AddTriangles(allTriangles[r], merged.PointMaps[r], mergedTriangles);
  }
  merged.Surface = vtkSmartPointer<vtkPolyData>::New();
  merged.Surface->SetPoints(mergedPoints);
  merged.Surface->SetPolys(mergedTriangles);
  return merged;
}

//------------------------------------------------------------------------------
bool ScatterBasis(vtkMultiProcessController* controller,
  bool ok,
  const MergedMesh& merged,
  const spectral::RowMatrix& harmonics,
  const spectral::Vector& mass,
  const spectral::Vector& eigenvalues,
  const std::array<double, 2>& figures,
  PieceBasis& piece)
{
  const int rank = controller->GetLocalProcessId();
  int header[2] = { ok ? 1 : 0, static_cast<int>(eigenvalues.size()) };
  controller->Broadcast(header, 2, 0);
  if (header[0] == 0)
  {
    return false;
  }
  piece.Eigenvalues = eigenvalues;
  piece.Eigenvalues.resize(header[1]);
  if (rank == 0)
  {
    piece.Eigenvalues = eigenvalues;
  }
  controller->Broadcast(piece.Eigenvalues.data(), header[1], 0);
  std::array<double, 2> worst = figures;
  controller->Broadcast(worst.data(), 2, 0);
  piece.MaxBackwardError = worst[0];
  piece.MaxResidual = worst[1];

  piece.Harmonics = vtkSmartPointer<vtkDoubleArray>::New();
  piece.Harmonics->SetNumberOfComponents(header[1]);
  piece.Mass = vtkSmartPointer<vtkDoubleArray>::New();
  piece.Duplicates = vtkSmartPointer<vtkUnsignedCharArray>::New();
  if (rank != 0)
  {
    ReceiveArray(controller, piece.Harmonics, 0, BasisTag);
    ReceiveArray(controller, piece.Mass, 0, BasisTag);
    ReceiveArray(controller, piece.Duplicates, 0, BasisTag);
    return true;
  }
  for (int r = controller->GetNumberOfProcesses() - 1; r >= 0; --r)
  {
    PieceBasis rows;
    rows.Harmonics = r == 0 ? piece.Harmonics : vtkSmartPointer<vtkDoubleArray>::New();
    rows.Mass = r == 0 ? piece.Mass : vtkSmartPointer<vtkDoubleArray>::New();
    rows.Duplicates = r == 0 ? piece.Duplicates : vtkSmartPointer<vtkUnsignedCharArray>::New();
    PieceRows(r, merged, harmonics, mass, rows);
    if (r > 0)
    {
      SendArray(controller, rows.Harmonics, r, BasisTag);
      SendArray(controller, rows.Mass, r, BasisTag);
      SendArray(controller, rows.Duplicates, r, BasisTag);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool SumOverRanks(vtkMultiProcessController* controller,
  std::vector<NamedMatrix>& matrices,
  spectral::Vector& eigenvalues)
{
  const int rank = controller->GetLocalProcessId();
  int ok = 1;
  if (rank != 0)
  {
    SendMatrices(controller, matrices, eigenvalues, 0);
  }
  else
  {
    std::vector<NamedMatrix> sums = matrices;
    spectral::Vector first = eigenvalues;
    for (int r = 1; r < controller->GetNumberOfProcesses(); ++r)
    {
      std::vector<NamedMatrix> received;
      spectral::Vector receivedEigenvalues;
      ReceiveMatrices(controller, received, receivedEigenvalues, r);
      ok = Accumulate(received, receivedEigenvalues, sums, first) ? ok : 0;
    }
    matrices = sums;
    eigenvalues = first;
  }
  controller->Broadcast(&ok, 1, 0);
  if (rank == 0)
  {
    for (int r = 1; r < controller->GetNumberOfProcesses(); ++r)
    {
      SendMatrices(controller, matrices, eigenvalues, r);
    }
  }
  else
  {
    ReceiveMatrices(controller, matrices, eigenvalues, 0);
  }
  return ok != 0;
}

//------------------------------------------------------------------------------
void SumOverRanks(vtkMultiProcessController* controller, std::vector<double>& values)
{
  std::vector<double> sums(values.size(), 0.0);
  controller->AllReduce(
    values.data(), sums.data(), static_cast<vtkIdType>(values.size()), vtkCommunicator::SUM_OP);
  values = sums;
}

} // namespace vtkManifoldHarmonicsParallel
