// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsGhosts.h
 * @brief Private helper, the one home of the ghost rules of the filters: which cells make the
 *        surface and which points a sum over points counts.
 *
 * A piece of a distributed data set may carry ghost cells and ghost points (the cell and point
 * arrays vtkDataSetAttributes::GhostArrayName(), as D3 then ExtractSurface gives them): copies
 * of cells and points that another process owns, there to make each piece complete for
 * rendering and neighbourhood queries. The filters
 * - leave ghost cells out of everything they assemble or measure (stiffness, mass, edge
 *   lengths): every cell ghost flag except vtkDataSetAttributes::EXTERIORCELL, which marks a
 *   real cell on the boundary of the data set;
 * - count a point flagged vtkDataSetAttributes::DUPLICATEPOINT zero times in sums over points
 *   (its owner counts it), while still giving it its harmonics and filtered values.
 * vtkManifoldHarmonicBasis sets DUPLICATEPOINT itself on the copies of a point that several
 * pieces hold, so that exactly one process counts it (vtkManifoldHarmonicsParallel.h).
 * Not installed and not wrapped. Tests: Filters/Testing/Cxx/TestGhostCells.cxx (serial),
 * Testing/ParaView/TestParallelGhostCells.py.in (2 and 3 processes).
 */
#ifndef vtkManifoldHarmonicsGhosts_h
#define vtkManifoldHarmonicsGhosts_h

#include "Spectral/Common/Mesh.h"

#include "vtkDataSetAttributes.h"
#include "vtkSmartPointer.h"

class vtkDataSet;
class vtkPolyData;
class vtkUnsignedCharArray;

namespace vtkManifoldHarmonicsGhosts
{
/// The cell ghost flags that leave a cell out: all but EXTERIORCELL.
constexpr unsigned char IgnoredCellFlags = vtkDataSetAttributes::DUPLICATECELL |
  vtkDataSetAttributes::HIGHCONNECTIVITYCELL | vtkDataSetAttributes::LOWCONNECTIVITYCELL |
  vtkDataSetAttributes::REFINEDCELL | vtkDataSetAttributes::HIDDENCELL;

/// The point ghost flag of a point that another process owns (and counts).
constexpr unsigned char NotOwnedPointFlag = vtkDataSetAttributes::DUPLICATEPOINT;

/// The cell ghost array of a data set, nullptr if it has none (or one of another size or type).
vtkUnsignedCharArray* CellGhosts(vtkDataSet* input);

/// The point ghost array of a data set, nullptr if it has none (or one of another size or type).
vtkUnsignedCharArray* PointGhosts(vtkDataSet* input);

/**
 * The cells of `input` that make the surface: `input` itself when no cell carries an ignored
 * ghost flag, otherwise a polydata with the same points (same ids) and point data, and the
 * vertices, lines, polygons and strips of `input` without the ghost cells (no cell data).
 */
vtkSmartPointer<vtkPolyData> CountedCells(vtkPolyData* input);

/**
 * 1 for the points to count in sums over points, 0 for those flagged NotOwnedPointFlag.
 * Length n; all ones without a point ghost array.
 */
spectral::Vector OwnedPoints(vtkDataSet* input);
} // namespace vtkManifoldHarmonicsGhosts

#endif
