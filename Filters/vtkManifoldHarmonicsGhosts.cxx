// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicsGhosts.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

namespace
{
//------------------------------------------------------------------------------
// The ghost array of point or cell data if it has `count` values.
vtkUnsignedCharArray* GhostArray(vtkDataSetAttributes* attributes, vtkIdType count)
{
  vtkUnsignedCharArray* ghosts = vtkArrayDownCast<vtkUnsignedCharArray>(
    attributes->GetArray(vtkDataSetAttributes::GhostArrayName()));
  return ghosts && ghosts->GetNumberOfComponents() == 1 && ghosts->GetNumberOfTuples() == count
    ? ghosts
    : nullptr;
}

//------------------------------------------------------------------------------
// Copies the cells of `cells` that no ignored flag marks into `counted`; `cellId` is the id of
// the first cell of `cells` in the data set (vertices, lines, polygons, strips in that order).
void CopyCountedCells(vtkCellArray* cells,
  vtkUnsignedCharArray* ghosts,
  vtkIdType& cellId,
  vtkCellArray* counted)
{
  auto iterator = vtk::TakeSmartPointer(cells->NewIterator());
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal();
       iterator->GoToNextCell(), ++cellId)
  {
    if (!(ghosts->GetValue(cellId) & vtkManifoldHarmonicsGhosts::IgnoredCellFlags))
    {
      vtkIdType npts;
      const vtkIdType* pts;
      iterator->GetCurrentCell(npts, pts);
      counted->InsertNextCell(npts, pts);
    }
  }
}
} // anonymous namespace

namespace vtkManifoldHarmonicsGhosts
{
//------------------------------------------------------------------------------
vtkUnsignedCharArray* CellGhosts(vtkDataSet* input)
{
  return GhostArray(input->GetCellData(), input->GetNumberOfCells());
}

//------------------------------------------------------------------------------
vtkUnsignedCharArray* PointGhosts(vtkDataSet* input)
{
  return GhostArray(input->GetPointData(), input->GetNumberOfPoints());
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> CountedCells(vtkPolyData* input)
{
  vtkUnsignedCharArray* ghosts = CellGhosts(input);
  bool ignored = false;
  for (vtkIdType c = 0; ghosts && !ignored && c < ghosts->GetNumberOfTuples(); ++c)
  {
    ignored = (ghosts->GetValue(c) & IgnoredCellFlags) != 0;
  }
  if (!ignored)
  {
    return input;
  }
  auto counted = vtkSmartPointer<vtkPolyData>::New();
  counted->SetPoints(input->GetPoints());
  counted->GetPointData()->ShallowCopy(input->GetPointData());
  vtkIdType cellId = 0;
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  CopyCountedCells(input->GetVerts(), ghosts, cellId, verts);
  CopyCountedCells(input->GetLines(), ghosts, cellId, lines);
  CopyCountedCells(input->GetPolys(), ghosts, cellId, polys);
  CopyCountedCells(input->GetStrips(), ghosts, cellId, strips);
  counted->SetVerts(verts);
  counted->SetLines(lines);
  counted->SetPolys(polys);
  counted->SetStrips(strips);
  return counted;
}

//------------------------------------------------------------------------------
spectral::Vector OwnedPoints(vtkDataSet* input)
{
  const vtkIdType n = input->GetNumberOfPoints();
  spectral::Vector owned = spectral::Vector::Ones(n);
  vtkUnsignedCharArray* ghosts = PointGhosts(input);
  for (vtkIdType i = 0; ghosts && i < n; ++i)
  {
    if (ghosts->GetValue(i) & NotOwnedPointFlag)
    {
      owned[i] = 0.0;
    }
  }
  return owned;
}
} // namespace vtkManifoldHarmonicsGhosts
