// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicBasis.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"
#include "vtkVersionMacros.h"

#include "Spectral/EigenSolver.h"
#include "Spectral/Operators.h"

#include <algorithm>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkManifoldHarmonicBasis);

namespace
{
//------------------------------------------------------------------------------
// Copies point coordinates of any value type into the core's #V by 3 double matrix.
struct CopyPointsWorker
{
  template<typename ArrayT>
  void operator()(ArrayT* array, spectral::Points& out) const
  {
    const auto tuples = vtk::DataArrayTupleRange<3>(array);
    vtkSMPTools::For(0,
      array->GetNumberOfTuples(),
      [&tuples, &out](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          out.row(i) << tuples[i][0], tuples[i][1], tuples[i][2];
        }
      });
  }
};

//------------------------------------------------------------------------------
// Writes row r of an #used by m column-major matrix into row Ids[r] of a row-major buffer with
// m values per row (the layout of a vtkDoubleArray with m components).
struct ScatterRows
{
  const spectral::DenseMatrix& Values;
  const std::vector<int>& Ids;
  double* Out;

  void operator()(vtkIdType begin, vtkIdType end) const
  {
    const vtkIdType m = static_cast<vtkIdType>(this->Values.cols());
    for (vtkIdType r = begin; r < end; ++r)
    {
      double* row = this->Out + static_cast<vtkIdType>(this->Ids[r]) * m;
      for (vtkIdType k = 0; k < m; ++k)
      {
        row[k] = this->Values(r, k);
      }
    }
  }
};

//------------------------------------------------------------------------------
// An n by m point data array, zero on the points that Ids does not reach.
vtkSmartPointer<vtkDoubleArray> ScatterToPoints(const char* name,
  const spectral::DenseMatrix& values,
  const std::vector<int>& ids,
  vtkIdType numPts)
{
  auto array = vtkSmartPointer<vtkDoubleArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(static_cast<int>(values.cols()));
  array->SetNumberOfTuples(numPts);
  array->FillValue(0.0);
  ScatterRows scatter{ values, ids, array->GetPointer(0) };
  vtkSMPTools::For(0, static_cast<vtkIdType>(ids.size()), scatter);
  return array;
}

//------------------------------------------------------------------------------
// Adds the harmonics and the lumped mass (point data, zero on unused points) and the eigenvalues
// (field data) to the output. Ids maps the rows of the core's matrices to output points.
void AddBasisArrays(vtkPolyData* output,
  const spectral::EigenResult& result,
  const std::vector<int>& ids,
  const spectral::Vector& lumped)
{
  const vtkIdType numPts = output->GetNumberOfPoints();
  const int m = static_cast<int>(result.Eigenvalues.size());
  auto harmonics = ScatterToPoints(
    vtkManifoldHarmonicBasis::HarmonicsArrayName(), result.Eigenvectors, ids, numPts);
  for (int k = 0; k < m; ++k)
  {
    harmonics->SetComponentName(k, ("Phi_" + std::to_string(k)).c_str());
  }
  output->GetPointData()->AddArray(harmonics);
  output->GetPointData()->AddArray(
    ScatterToPoints(vtkManifoldHarmonicBasis::MassArrayName(), lumped, ids, numPts));

  vtkNew<vtkDoubleArray> eigenvalues;
  eigenvalues->SetName(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  eigenvalues->SetNumberOfTuples(m);
  std::copy(result.Eigenvalues.data(), result.Eigenvalues.data() + m, eigenvalues->GetPointer(0));
  output->GetFieldData()->AddArray(eigenvalues);
}

//------------------------------------------------------------------------------
// The polygons and strips of the input as triangles, through an internal vtkTriangleFilter
// when the input holds anything but triangles. Vertices and lines are dropped.
vtkSmartPointer<vtkPolyData> Triangulate(vtkManifoldHarmonicBasis* self, vtkPolyData* input)
{
  if (input->GetNumberOfStrips() == 0 && input->GetPolys()->IsHomogeneous() == 3)
  {
    return input;
  }
  vtkWarningWithObjectMacro(self, << "Triangulating polygons and triangle strips.");
  vtkNew<vtkTriangleFilter> triangulate;
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 20230111)
  triangulate->SetContainerAlgorithm(self);
#endif
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->SetInputData(input);
  triangulate->Update();
  return triangulate->GetOutput();
}

//------------------------------------------------------------------------------
// Points and triangles of an all-triangle vtkPolyData in the core's form.
spectral::TriangleMesh ToTriangleMesh(vtkPolyData* surface)
{
  spectral::TriangleMesh mesh;
  mesh.Vertices.resize(surface->GetNumberOfPoints(), 3);
  vtkDataArray* coordinates = surface->GetPoints()->GetData();
  CopyPointsWorker worker;
  if (!vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>::Execute(
        coordinates, worker, mesh.Vertices))
  {
    worker(coordinates, mesh.Vertices);
  }

  vtkCellArray* polys = surface->GetPolys();
  mesh.Faces.resize(polys->GetNumberOfCells(), 3);
  auto cells = vtk::TakeSmartPointer(polys->NewIterator());
  Eigen::Index row = 0;
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell(), ++row)
  {
    vtkIdType npts;
    const vtkIdType* pts;
    cells->GetCurrentCell(npts, pts);
    mesh.Faces.row(row) << static_cast<int>(pts[0]), static_cast<int>(pts[1]),
      static_cast<int>(pts[2]);
  }
  return mesh;
}

//------------------------------------------------------------------------------
// Warns about what PrepareMesh left out and about several components; returns the number of
// harmonics to compute, clamped to the number of usable points.
int CheckPreparedMesh(vtkManifoldHarmonicBasis* self,
  const spectral::PreparedMesh& prepared,
  int requested)
{
  if (prepared.DegenerateTriangles > 0)
  {
    vtkWarningWithObjectMacro(
      self, << "Left out " << prepared.DegenerateTriangles << " degenerate (zero-area) triangles.");
  }
  if (prepared.UnusedPoints > 0)
  {
    vtkWarningWithObjectMacro(
      self, << prepared.UnusedPoints << " points are used by no triangle; their harmonics are 0.");
  }
  const int components = spectral::ConnectedComponents(prepared.Mesh);
  if (components > 1)
  {
    vtkWarningWithObjectMacro(self,
      << "The surface has " << components << " connected components: the first " << components
      << " eigenvalues are zero.");
  }
  const int usable = static_cast<int>(prepared.Mesh.Vertices.rows());
  if (requested > usable)
  {
    vtkWarningWithObjectMacro(self,
      << "NumberOfHarmonics " << requested << " clamped to " << usable
      << ", the number of points triangles use.");
    return usable;
  }
  return requested;
}
} // anonymous namespace

//------------------------------------------------------------------------------
vtkManifoldHarmonicBasis::vtkManifoldHarmonicBasis()
  : NumberOfHarmonics(100)
  , MassMatrix(LUMPED)
  , BandSize(0)
  , Tolerance(1e-11)
  , MaxIterations(1000)
{
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicBasis::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  vtkDebugMacro(<< "Computing " << this->NumberOfHarmonics << " harmonics, mass matrix "
                << this->MassMatrix << ", band size " << this->BandSize << ", tolerance "
                << this->Tolerance << ", max iterations " << this->MaxIterations);

  const vtkIdType numPts = input->GetNumberOfPoints();
  if (numPts == 0 || input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    vtkWarningMacro(<< "No polygons to compute manifold harmonics on; passing the input through.");
    output->ShallowCopy(input);
    return 1;
  }
  if (numPts > VTK_INT_MAX)
  {
    vtkErrorMacro(<< "Too many points: " << numPts << " (at most " << VTK_INT_MAX << ").");
    return 0;
  }

  try
  {
    // Validate and convert.
    this->SetProgressText("Assemble");
    vtkSmartPointer<vtkPolyData> surface = ::Triangulate(this, input);
    const spectral::PreparedMesh prepared = spectral::PrepareMesh(::ToTriangleMesh(surface));
    if (prepared.Mesh.Vertices.rows() == 0)
    {
      vtkErrorMacro(<< "Every triangle of the input is degenerate (zero area).");
      return 0;
    }
    const int m = ::CheckPreparedMesh(this, prepared, this->NumberOfHarmonics);

    // Assemble the operators.
    const spectral::SparseMatrix L = spectral::CotanStiffness(prepared.Mesh);
    const spectral::Vector lumped = spectral::LumpedMass(prepared.Mesh);
    const spectral::SparseMatrix M = this->MassMatrix == CONSISTENT
      ? spectral::ConsistentMass(prepared.Mesh)
      : spectral::Diagonal(lumped);
    this->UpdateProgress(0.1);
    if (this->GetAbortExecute())
    {
      return 1;
    }

    // Solve.
    this->SetProgressText("Eigensolve");
    spectral::EigenOptions options;
    options.NumberOfEigenpairs = m;
    options.BandSize = this->BandSize;
    options.Tolerance = this->Tolerance;
    options.MaxIterations = this->MaxIterations;
    spectral::Monitor monitor;
    monitor.Progress = [this](double fraction) { this->UpdateProgress(0.1 + 0.85 * fraction); };
    monitor.Cancelled = [this]() { return this->GetAbortExecute() != 0; };
    const spectral::EigenResult result = spectral::SmallestEigenpairs(L, M, options, monitor);
    if (this->GetAbortExecute())
    {
      return 1;
    }

    // Write the arrays.
    this->SetProgressText("Write");
    output->ShallowCopy(input);
    ::AddBasisArrays(output, result, prepared.InputPointIds, lumped);
    this->UpdateProgress(1.0);
    return 1;
  }
  catch (const spectral::Cancelled&)
  {
    output->Initialize();
    return 1;
  }
  catch (const spectral::InvalidInput& e)
  {
    vtkErrorMacro(<< "Invalid input: " << e.what());
  }
  catch (const spectral::SolverFailure& e)
  {
    vtkErrorMacro(<< "Eigensolver failed (" << e.Converged << " pairs converged): " << e.what());
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Manifold harmonics failed: " << e.what());
  }
  output->Initialize();
  return 0;
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicBasis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Number Of Harmonics: " << this->NumberOfHarmonics << " (default 100)\n";
  os << indent << "Mass Matrix: " << (this->MassMatrix == CONSISTENT ? "Consistent" : "Lumped")
     << " (default Lumped)\n";
  os << indent << "Band Size: " << this->BandSize << " (default 0, automatic)\n";
  os << indent << "Tolerance: " << this->Tolerance << " (default 1e-11)\n";
  os << indent << "Max Iterations: " << this->MaxIterations << " (default 1000)\n";
}
