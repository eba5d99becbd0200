// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicsSlepc.h"

#include "vtkDoubleArray.h"
#include "vtkManifoldHarmonicsGhosts.h"
#include "vtkMultiProcessController.h"
#include "vtkUnsignedCharArray.h"

#include "Spectral/Distributed/Petsc.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace vtkManifoldHarmonicsSlepc
{
//------------------------------------------------------------------------------
Result Solve(vtkMultiProcessController* controller,
  const spectral::TriangleMesh& piece,
  const Settings& settings)
{
  spectral::distributed::Initialize();
  const MPI_Comm comm = PETSC_COMM_WORLD;
  int size = 1;
  MPI_Comm_size(comm, &size);
  const int processes = controller ? controller->GetNumberOfProcesses() : 1;
  if (processes != size)
  {
    // Decided alike on every process: the sizes are the same everywhere.
    throw std::runtime_error("the SLEPc solver needs every MPI process of the run (" +
      std::to_string(size) + ") in the pipeline, which has " + std::to_string(processes));
  }
  // The harmonics go straight into the output array.
  Result result;
  vtkManifoldHarmonicsParallel::PieceBasis& rows = result.Rows;
  spectral::DistributedOptions options = settings;
  options.HarmonicsStorage = [&rows](Eigen::Index n, int m)
  {
    rows.Harmonics = vtkSmartPointer<vtkDoubleArray>::New();
    rows.Harmonics->SetNumberOfComponents(std::max(m, 1));
    rows.Harmonics->SetNumberOfTuples(static_cast<vtkIdType>(n));
    return rows.Harmonics->GetPointer(0);
  };
  static_cast<spectral::DistributedResult&>(result) =
    spectral::SolveDistributed(comm, piece, options, settings);

  // The mass and the DUPLICATEPOINT flags of this piece's points.
  const vtkIdType n = static_cast<vtkIdType>(piece.Vertices.rows());
  rows.Eigenvalues = result.Eigenvalues;
  rows.MaxBackwardError = result.MaxBackwardError;
  rows.MaxResidual = result.MaxResidual;
  rows.Mass = vtkSmartPointer<vtkDoubleArray>::New();
  rows.Mass->SetNumberOfTuples(n);
  rows.Duplicates = vtkSmartPointer<vtkUnsignedCharArray>::New();
  rows.Duplicates->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    rows.Mass->SetValue(i, result.Mass[i]);
    rows.Duplicates->SetValue(
      i, result.Duplicate[i] ? vtkManifoldHarmonicsGhosts::NotOwnedPointFlag : 0);
  }
  return result;
}
} // namespace vtkManifoldHarmonicsSlepc
