// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicBasis.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArrayRange.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkManifoldHarmonicsArrays.h"
#include "vtkManifoldHarmonicsBasisFile.h"
#include "vtkManifoldHarmonicsEnums.h"
#include "vtkManifoldHarmonicsGhosts.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkManifoldHarmonicsParallel.h"
#include "vtkManifoldHarmonicsParameters.h"
#include "vtkManifoldHarmonicsStreaming.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVersionMacros.h"

#include "Spectral/Basis.h"
#include "Spectral/Common/BasisFile.h"
#include "Spectral/Operators/Operators.h"

#ifdef MANIFOLDHARMONICS_HAS_SLEPC
#include "vtkManifoldHarmonicsSlepc.h"
#endif

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkManifoldHarmonicBasis);

// The wrapped constant repeats the core's default for Python and the XML: they must agree.
static_assert(
  vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS == spectral::DefaultNumberOfHarmonics,
  "the default number of harmonics has its home in Spectral/Common/Defaults.h");
static_assert(
  vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_NEIGHBORS == spectral::DefaultNumberOfNeighbors,
  "the default number of neighbours has its home in Spectral/Common/Defaults.h");
namespace
{
//------------------------------------------------------------------------------
// Where the rows of the core's result go: row Rows[e] of the result is written onto output
// point Ids[e]. A row goes to several points when the point was welded (each copy gets it).
struct RowsToPoints
{
  std::vector<int> Rows;
  std::vector<std::int64_t> Ids;
};

//------------------------------------------------------------------------------
// Writes row Rows[e] of an #used by m column-major matrix into row Ids[e] of a row-major buffer
// with m values per row (the layout of a vtkDoubleArray or vtkFloatArray with m components).
template<typename ValueT>
struct ScatterRows
{
  const spectral::DenseMatrix& Values;
  const RowsToPoints& Targets;
  ValueT* Out;

  void operator()(vtkIdType begin, vtkIdType end) const
  {
    const vtkIdType m = static_cast<vtkIdType>(this->Values.cols());
    for (vtkIdType e = begin; e < end; ++e)
    {
      ValueT* row = this->Out + this->Targets.Ids[e] * m;
      const Eigen::Index r = this->Targets.Rows[e];
      for (vtkIdType k = 0; k < m; ++k)
      {
        row[k] = static_cast<ValueT>(this->Values(r, k));
      }
    }
  }
};

//------------------------------------------------------------------------------
// An n by m point data array (vtkDoubleArray or vtkFloatArray), zero on the points that the
// targets do not reach.
template<typename ArrayT>
vtkSmartPointer<ArrayT> ScatterToPoints(const char* name,
  const spectral::DenseMatrix& values,
  const RowsToPoints& targets,
  vtkIdType numPts)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(static_cast<int>(values.cols()));
  array->SetNumberOfTuples(numPts);
  array->FillValue(0);
  ScatterRows<typename ArrayT::ValueType> scatter{ values, targets, array->GetPointer(0) };
  vtkSMPTools::For(0, static_cast<vtkIdType>(targets.Ids.size()), scatter);
  return array;
}

//------------------------------------------------------------------------------
// The targets of the core's rows: `inputPointIds` maps row r to a point of the solved mesh,
// `welded` (empty without welding) maps each output point to its point of the solved mesh.
RowsToPoints Targets(const std::vector<int>& inputPointIds,
  const std::vector<vtkIdType>& welded,
  vtkIdType numPts)
{
  RowsToPoints targets;
  if (welded.empty())
  {
    targets.Rows.resize(inputPointIds.size());
    std::iota(targets.Rows.begin(), targets.Rows.end(), 0);
    targets.Ids.assign(inputPointIds.begin(), inputPointIds.end());
    return targets;
  }
  std::vector<int> rowOf(welded.size(), -1);
  for (std::size_t r = 0; r < inputPointIds.size(); ++r)
  {
    rowOf[inputPointIds[r]] = static_cast<int>(r);
  }
  for (vtkIdType i = 0; i < numPts; ++i)
  {
    const int r = rowOf[welded[i]];
    if (r >= 0)
    {
      targets.Rows.push_back(r);
      targets.Ids.push_back(i);
    }
  }
  return targets;
}

//------------------------------------------------------------------------------
// Adds the harmonics (point data, zero on the points Ids does not reach; floats when `floats`)
// to the output. Ids maps the rows of the core's matrix to output points.
void AddHarmonicsArray(vtkDataSet* output,
  const spectral::DenseMatrix& H,
  const RowsToPoints& ids,
  bool floats)
{
  const vtkIdType numPts = output->GetNumberOfPoints();
  const char* name = vtkManifoldHarmonicBasis::HarmonicsArrayName();
  vtkSmartPointer<vtkDataArray> harmonics;
  if (floats)
  {
    harmonics = ScatterToPoints<vtkFloatArray>(name, H, ids, numPts);
  }
  else
  {
    harmonics = ScatterToPoints<vtkDoubleArray>(name, H, ids, numPts);
  }
  vtkManifoldHarmonicsBasisFile::NameHarmonics(harmonics);
  output->GetPointData()->AddArray(harmonics);
}

//------------------------------------------------------------------------------
// Adds the harmonics (when the result has them: not with EigenvaluesOnly) and the lumped mass
// (point data, zero on unused points) and the eigenvalues (field data) to the output.
void AddBasisArrays(vtkDataSet* output,
  const spectral::EigenResult& result,
  const RowsToPoints& ids,
  const spectral::Vector& lumped,
  bool floats)
{
  const vtkIdType numPts = output->GetNumberOfPoints();
  const int m = static_cast<int>(result.Eigenvalues.size());
  if (result.Eigenvectors.cols() == m && m > 0)
  {
    AddHarmonicsArray(output, result.Eigenvectors, ids, floats);
  }
  output->GetPointData()->AddArray(ScatterToPoints<vtkDoubleArray>(
    vtkManifoldHarmonicBasis::MassArrayName(), lumped, ids, numPts));
  vtkManifoldHarmonicsBasisFile::AddSpectrumArrays(
    output, result.Eigenvalues.data(), m, result.MaxBackwardError, result.MaxResidual);
}

//------------------------------------------------------------------------------
// The polygons and strips of a piece as triangles, for the gather of a distributed run
// (GatherAndMerge takes triangles), through an internal vtkTriangleFilter when the piece holds
// anything but triangles: it splits polygons by vtkPolygon::Triangulate, the rule of ToCoreMesh.
// Vertices and lines are passed on, for ToCoreMesh to leave out with a warning; ghost cells are
// dropped (vtkManifoldHarmonicsGhosts: another process owns them). The points are the piece's.
vtkSmartPointer<vtkPolyData> Triangulate(vtkManifoldHarmonicBasis* self, vtkPolyData* input)
{
  vtkSmartPointer<vtkPolyData> counted = vtkManifoldHarmonicsGhosts::CountedCells(input);
  if (counted->GetNumberOfStrips() == 0 && counted->GetPolys()->IsHomogeneous() == 3)
  {
    return counted;
  }
  vtkWarningWithObjectMacro(self, << "Triangulating polygons and triangle strips.");
  vtkNew<vtkTriangleFilter> triangulate;
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 20230111)
  triangulate->SetContainerAlgorithm(self);
#endif
  triangulate->PassVertsOn();
  triangulate->PassLinesOn();
  triangulate->SetInputData(counted);
  triangulate->Update();
  return triangulate->GetOutput();
}

//------------------------------------------------------------------------------
// The point ghost array of the output: the merge of the points (WeldPoints) decides which copy
// of a point counts (`duplicates`: NotOwnedPointFlag on the others); the input's other flags
// stay.
void AddPointGhosts(vtkPointSet* output, vtkPointSet* input, vtkUnsignedCharArray* duplicates)
{
  vtkNew<vtkUnsignedCharArray> ghosts;
  ghosts->DeepCopy(duplicates);
  ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
  vtkUnsignedCharArray* existing = vtkManifoldHarmonicsGhosts::PointGhosts(input);
  const unsigned char kept =
    static_cast<unsigned char>(~vtkManifoldHarmonicsGhosts::NotOwnedPointFlag);
  for (vtkIdType i = 0; existing && i < ghosts->GetNumberOfTuples(); ++i)
  {
    ghosts->SetValue(i, ghosts->GetValue(i) | (existing->GetValue(i) & kept));
  }
  output->GetPointData()->AddArray(ghosts);
}

//------------------------------------------------------------------------------
// Welds the points of `mesh` (WeldPoints, `owned` from the input's point ghost flags): `welding`
// says which points became one. When some did, `welded` is the mesh to solve on, its cells
// renumbered, and the return value is true.
bool WeldMesh(const spectral::TriangleMesh& mesh,
  vtkPointSet* input,
  double tolerance,
  vtkManifoldHarmonicsParallel::Welding& welding,
  spectral::TriangleMesh& welded)
{
  const vtkIdType n = static_cast<vtkIdType>(mesh.Vertices.rows());
  const spectral::Vector ownedPoints = vtkManifoldHarmonicsGhosts::OwnedPoints(input);
  std::vector<unsigned char> owned(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    owned[i] = ownedPoints[i] > 0.0 ? 1 : 0;
  }
  welding =
    vtkManifoldHarmonicsParallel::WeldPoints(mesh.Vertices.data(), n, nullptr, tolerance, owned);
  if (!welding.Merged())
  {
    return false;
  }
  welded.Vertices.resize(static_cast<Eigen::Index>(welding.First.size()), 3);
  for (std::size_t j = 0; j < welding.First.size(); ++j)
  {
    welded.Vertices.row(j) = mesh.Vertices.row(welding.First[j]);
  }
  const auto renumber = [&welding](int id) { return static_cast<int>(welding.Map[id]); };
  welded.Faces = mesh.Faces.unaryExpr(renumber);
  welded.Tets = mesh.Tets.unaryExpr(renumber);
  return true;
}

//------------------------------------------------------------------------------
// NotOwnedPointFlag on every copy of a welded point but the one that counts.
vtkSmartPointer<vtkUnsignedCharArray> WeldedDuplicates(
  const vtkManifoldHarmonicsParallel::Welding& welding)
{
  auto duplicates = vtkSmartPointer<vtkUnsignedCharArray>::New();
  duplicates->SetNumberOfTuples(static_cast<vtkIdType>(welding.Map.size()));
  for (vtkIdType i = 0; i < duplicates->GetNumberOfTuples(); ++i)
  {
    duplicates->SetValue(
      i, welding.Counted[welding.Map[i]] == i ? 0 : vtkManifoldHarmonicsGhosts::NotOwnedPointFlag);
  }
  return duplicates;
}

//------------------------------------------------------------------------------
// The arrays of a distributed run on the output of one process: its rows of the harmonics and
// mass (also on its ghost points: the owner's rows), the eigenvalues and the worst pair's figures
// (AddSpectrumArrays, as on every basis output), and the point ghost array:
// DUPLICATEPOINT on the points another process owns, the input's other flags kept. The cell
// ghost array is the input's. The harmonics are converted to floats when
// `floats` is true.
void AddPieceArrays(vtkPointSet* output,
  vtkPointSet* input,
  const vtkManifoldHarmonicsParallel::PieceBasis& rows,
  bool floats)
{
  output->ShallowCopy(input);
  const int m = static_cast<int>(rows.Eigenvalues.size());
  vtkSmartPointer<vtkDataArray> harmonics = rows.Harmonics;
  if (floats)
  {
    harmonics = vtkSmartPointer<vtkFloatArray>::New();
    harmonics->DeepCopy(rows.Harmonics);
  }
  vtkManifoldHarmonicsBasisFile::NameHarmonics(harmonics);
  rows.Mass->SetName(vtkManifoldHarmonicBasis::MassArrayName());
  output->GetPointData()->AddArray(harmonics);
  output->GetPointData()->AddArray(rows.Mass);
  AddPointGhosts(output, input, rows.Duplicates);
  vtkManifoldHarmonicsBasisFile::AddSpectrumArrays(
    output, rows.Eigenvalues.data(), m, rows.MaxBackwardError, rows.MaxResidual);
}

//------------------------------------------------------------------------------
// The error message of a computation that does not fit in memory: what is needed, what is
// available, what to change.
std::string MemoryProblem(vtkManifoldHarmonicBasis* self,
  vtkIdType numPts,
  const spectral::InsufficientMemory& e)
{
  using vtkManifoldHarmonicsParameters::Bytes;
  const int m = e.Harmonics;
  const bool floats = self->GetBasisPrecision() == vtkManifoldHarmonicBasis::FLOAT;
  const bool limited = self->GetMemoryLimit() > 0.0;
  const spectral::MemoryEstimate& need = e.Needed;
  std::ostringstream message;
  // A streamed basis keeps no output basis: its Basis term is the blocks handed over, in
  // doubles whatever BasisPrecision.
  message << "Not enough memory for " << m << (e.Streamed ? " streamed" : "") << " harmonics on "
          << numPts << " points: about " << spectral::ByteCount(need.Total()) << " needed ("
          << (e.Streamed ? "harmonics in delivery " : "basis ") << spectral::ByteCount(need.Basis)
          << ", solver eigenvectors " << spectral::ByteCount(need.Eigenvectors)
          << ", Lanczos workspace and operators " << spectral::ByteCount(need.Krylov)
          << ", sparse factor " << spectral::ByteCount(need.Factor) << ", the process's own "
          << spectral::ByteCount(need.Overhead) << "), " << spectral::ByteCount(e.Available)
          << " available (" << (limited ? "MemoryLimit" : "reported by the system");
  // A basis file streamed into leaves the solve what its writer does not take (WriterBytes).
  const std::uint64_t limit =
    vtkManifoldHarmonicsParameters::MemoryLimitBytes(self->GetMemoryLimit());
  if (limited && e.Available < limit)
  {
    message << " " << spectral::ByteCount(limit) << ", less "
            << spectral::ByteCount(limit - e.Available) << " for the basis file's writer";
  }
  message << "). Compute fewer harmonics";
  if (!floats && !e.Streamed)
  {
    message << ", set BasisPrecision to Float (saves " << spectral::ByteCount(need.Basis / 2)
            << ")";
  }
  // Only where the automatic bands could be smaller than the ones asked for.
  if (self->GetBandSize() > spectral::SmallestPlannedBand)
  {
    message << ", set BandSize to 0 (automatic: bands as small as " << spectral::SmallestPlannedBand
            << " eigenpairs where the memory needs it; now " << self->GetBandSize() << ")";
  }
  message << (limited ? " or raise MemoryLimit." : " or free memory.");
  if (self->GetBandSize() <= 0 && spectral::EffectiveBandSize(m, 0) > spectral::SmallestPlannedBand)
  {
    message << " (The estimate is for bands of " << spectral::SmallestPlannedBand
            << " eigenpairs, the smallest that BandSize 0, automatic, goes down to.)";
  }
  return message.str();
}

//------------------------------------------------------------------------------
// The warning of an input without points, or with points only lines or vertices use.
constexpr const char* NothingToSolve =
  "No polygons or volume cells to compute manifold harmonics on";

//------------------------------------------------------------------------------
// The warning of a distributed run with WeldSeams off.
constexpr const char* KeptSeamsIgnored =
  "WeldSeams is off, but a distributed run merges the points that coincide within SeamTolerance "
  "(it cannot tell a seam inside a piece from one between pieces): keep seams open in a serial "
  "run.";

//------------------------------------------------------------------------------
// What the conversion of the cells changed or left out, and how a point cloud is solved.
void WarnAboutCells(vtkManifoldHarmonicBasis* self,
  const vtkManifoldHarmonicsArrays::CoreMesh& cells)
{
  for (const std::string& warning : cells.Warnings())
  {
    vtkWarningWithObjectMacro(self, << warning);
  }
  const std::string cloud = cells.PointCloudWarning(self->GetNumberOfNeighbors());
  if (!cloud.empty())
  {
    vtkWarningWithObjectMacro(self, << cloud);
  }
}

//------------------------------------------------------------------------------
// With WeldSeams on: boundary points nearly on top of each other that the weld left apart
// (spectral::FindOpenSeams), which make the harmonics those of a cut surface.
void WarnAboutOpenSeams(vtkManifoldHarmonicBasis* self, const spectral::TriangleMesh& solved)
{
  if (!self->GetWeldSeams() || solved.Faces.rows() == 0)
  {
    return;
  }
  const spectral::OpenSeams open = spectral::FindOpenSeams(solved);
  if (open.Pairs > 0)
  {
    vtkWarningWithObjectMacro(self,
      << open.Pairs << " pairs of boundary points lie within " << spectral::OpenSeamGap
      << " of the mean edge length of each other (up to " << open.LargestGap
      << " of the bounding box diagonal apart) without sharing an edge: seams left open, so the "
         "harmonics are those of a surface cut there. If they are copies of one point, raise "
         "SeamTolerance above "
      << open.LargestGap << " (it is " << self->GetSeamTolerance()
      << "), or merge them first (Clean in ParaView, vtkCleanPolyData, with a tolerance).");
  }
}

//------------------------------------------------------------------------------
// The settings of the filter as options of the core's entry point.
spectral::BasisOptions CoreOptions(vtkManifoldHarmonicBasis* self)
{
  spectral::BasisOptions options;
  options.NumberOfHarmonics = self->GetNumberOfHarmonics();
  namespace Enums = vtkManifoldHarmonicsEnums;
  options.Operators.Laplacian = Enums::To(Enums::Laplacian, self->GetLaplacian(), "Laplacian");
  options.Operators.Boundary =
    Enums::To(Enums::BoundaryCondition, self->GetBoundaryCondition(), "BoundaryCondition");
  options.Operators.Mass = Enums::To(Enums::MassMatrix, self->GetMassMatrix(), "MassMatrix");
  options.Solver.BandSize = self->GetBandSize();
  options.Solver.Tolerance = self->GetTolerance();
  options.Solver.MaxIterations = self->GetMaxIterations();
  options.MinimumComponentSize = self->GetMinimumComponentSize();
  options.NumberOfNeighbors = self->GetNumberOfNeighbors();
  options.Solver.Threads = self->GetNumberOfThreads();
  options.EigenvaluesOnly = self->GetEigenvaluesOnly();
  options.LowerFrequency = self->GetFrequencyWindow()[0];
  options.UpperFrequency = self->GetFrequencyWindow()[1];
  options.BytesPerValue =
    Enums::To(Enums::BasisPrecision, self->GetBasisPrecision(), "BasisPrecision");
  options.MemoryLimit = vtkManifoldHarmonicsParameters::MemoryLimitBytes(self->GetMemoryLimit());
  return options;
}

//------------------------------------------------------------------------------
// The first setting the SLEPc solver does not support, or "".
std::string SlepcUnsupported(vtkManifoldHarmonicBasis* self)
{
  if (self->GetLaplacian() != vtkManifoldHarmonicBasis::COTANGENT)
  {
    return "Laplacian Intrinsic Delaunay";
  }
  if (self->GetEigenvaluesOnly())
  {
    return "EigenvaluesOnly";
  }
  if (self->GetMinimumComponentSize() > 0)
  {
    return "MinimumComponentSize";
  }
  if (self->GetBoundaryCondition() != vtkManifoldHarmonicBasis::NEUMANN)
  {
    return "BoundaryCondition Dirichlet";
  }
  return std::string();
}

#ifdef MANIFOLDHARMONICS_HAS_SLEPC
//------------------------------------------------------------------------------
// Whether every process's piece can be used (collective): pieces that cannot be, and point
// clouds (points on some process, cells on none), are refused on every process alike.
bool SlepcPiecesUsable(vtkManifoldHarmonicBasis* self,
  vtkMultiProcessController* controller,
  const vtkManifoldHarmonicsArrays::CoreMesh& cells,
  vtkPointSet* input)
{
  const bool distributed = controller && controller->GetNumberOfProcesses() > 1;
  if (distributed && !self->GetWeldSeams() && controller->GetLocalProcessId() == 0)
  {
    vtkWarningWithObjectMacro(self, << KeptSeamsIgnored);
  }
  const auto count = [controller, distributed](bool flag) {
    return distributed ? vtkManifoldHarmonicsParallel::CountRanks(controller, flag) : flag ? 1 : 0;
  };
  const std::string problem = cells.Problem();
  const int unusable = count(!problem.empty());
  const int withCells = count(cells.HasCells());
  const int withPoints = count(input->GetNumberOfPoints() > 0);
  if (unusable > 0)
  {
    if (!problem.empty())
    {
      vtkErrorWithObjectMacro(self, << "The SLEPc solver cannot use this piece: " << problem);
    }
    else
    {
      vtkErrorWithObjectMacro(
        self, << "The SLEPc solver stopped: another process's piece cannot be used.");
    }
    return false;
  }
  if (withCells == 0 && withPoints > 0)
  {
    vtkErrorWithObjectMacro(self,
      << "The SLEPc solver does not take point clouds (points without triangles or "
         "tetrahedra) yet: choose the Built-in solver in a serial run.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
// The settings of the filter as the SLEPc solver's, with the filter's monitor (its progress,
// steps, warnings and abort flag).
vtkManifoldHarmonicsSlepc::Settings SlepcSettings(vtkManifoldHarmonicBasis* self,
  vtkPointSet* input,
  const spectral::Monitor& monitor)
{
  vtkManifoldHarmonicsSlepc::Settings settings;
  static_cast<spectral::Monitor&>(settings) = monitor;
  settings.NumberOfHarmonics = self->GetNumberOfHarmonics();
  settings.ConsistentMass = self->GetMassMatrix() == vtkManifoldHarmonicBasis::CONSISTENT;
  settings.Partitions = self->GetSlepcPartitions();
  settings.Options = self->GetSlepcOptions();
  settings.Tolerance = self->GetTolerance();
  settings.MaxIterations = self->GetMaxIterations();
  settings.WeldSeams = self->GetWeldSeams();
  settings.SeamTolerance = self->GetSeamTolerance();
  settings.LowerFrequency = self->GetFrequencyWindow()[0];
  settings.UpperFrequency = self->GetFrequencyWindow()[1];
  // The owner rule of every path (Spectral/Common/Seams.h) reads the input's point ghost flags.
  const spectral::Vector ownedPoints = vtkManifoldHarmonicsGhosts::OwnedPoints(input);
  for (Eigen::Index i = 0; i < ownedPoints.size(); ++i)
  {
    settings.OwnedPoints.push_back(ownedPoints[i] > 0.0 ? 1 : 0);
  }
  return settings;
}

//------------------------------------------------------------------------------
// The SLEPc solve of this process's piece (collective) and its rows on the output; the quality
// figures as field data. \throws spectral::Cancelled after an abort, std::exception on errors.
void SolveWithSlepc(vtkManifoldHarmonicBasis* self,
  vtkMultiProcessController* controller,
  const spectral::TriangleMesh& mesh,
  vtkPointSet* input,
  vtkPointSet* output,
  const spectral::Monitor& monitor)
{
  const vtkManifoldHarmonicsSlepc::Result result =
    vtkManifoldHarmonicsSlepc::Solve(controller, mesh, SlepcSettings(self, input, monitor));
  AddPieceArrays(
    output, input, result.Rows, self->GetBasisPrecision() == vtkManifoldHarmonicBasis::FLOAT);
  for (const auto& figure :
    { std::make_pair(vtkManifoldHarmonicsNames::OrthonormalityError, result.OrthonormalityError),
      std::make_pair(
        vtkManifoldHarmonicsNames::InertiaCount, static_cast<double>(result.InertiaCount)) })
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(figure.first);
    array->InsertNextValue(figure.second);
    output->GetFieldData()->AddArray(array);
  }
  vtkDebugWithObjectMacro(self,
    << "SLEPc: " << result.GlobalPoints << " points, " << result.OwnedPoints << " owned here, "
    << result.Computed << " pairs in [0, " << result.UpperEnd << "), " << result.Shifts
    << " shifts");
  self->UpdateProgress(1.0);
}
#endif

//------------------------------------------------------------------------------
// The basis of the core on `output` (a shallow copy of `input`): each row on its point, or on
// every copy of a welded point (the copies but one flagged as duplicates).
// A basis kept in a file (`plan.Path`) is mapped from it instead (its header read back and
// checked, or the reused file's); a temporary file is unlinked once mapped.
void WriteBasis(vtkPointSet* output,
  vtkPointSet* input,
  const spectral::BasisResult* basis,
  const vtkManifoldHarmonicsBasisFile::Plan& plan,
  const vtkManifoldHarmonicsParallel::Welding& welding,
  bool floats)
{
  const vtkIdType numPts = input->GetNumberOfPoints();
  if (!plan.Path.empty())
  {
    // A temporary file goes once mapped, and also when it cannot be.
    struct Remover
    {
      const vtkManifoldHarmonicsBasisFile::Plan& File;
      ~Remover()
      {
        if (this->File.Temporary)
        {
          std::remove(this->File.Path.c_str());
        }
      }
    } remover{ plan };
    vtkManifoldHarmonicsBasisFile::AddFileArrays(
      output, plan.Path, plan.Reuse ? plan.Header : spectral::ReadBasisFileHeader(plan.Path));
  }
  else
  {
    AddBasisArrays(output,
      basis->Pairs,
      Targets(
        basis->InputPointIds, welding.Merged() ? welding.Map : std::vector<vtkIdType>(), numPts),
      basis->LumpedMass,
      floats);
  }
  if (welding.Merged())
  {
    AddPointGhosts(output, input, WeldedDuplicates(welding));
  }
}

//------------------------------------------------------------------------------
// The header of a new basis file of `plan`: n, b, digest and options (m comes with the basis).
spectral::BasisFileHeader FileHeader(const vtkManifoldHarmonicsBasisFile::Plan& plan,
  vtkIdType numPts,
  int bytesPerValue)
{
  spectral::BasisFileHeader header;
  header.Rows = static_cast<std::uint64_t>(numPts);
  header.BytesPerValue = static_cast<std::uint32_t>(bytesPerValue);
  header.MeshDigest = plan.Digest;
  header.Options = plan.Options;
  return header;
}

//------------------------------------------------------------------------------
// Completes a basis file: the eigenvalues, the mass on the output's points, the figures and the
// warnings of `basis` in its header, then the atomic commit.
void CommitBasisFile(spectral::BasisFileWriter& writer,
  spectral::BasisFileHeader& header,
  const spectral::BasisResult& basis,
  const RowsToPoints& targets,
  const spectral::Monitor& monitor = spectral::Monitor())
{
  header.Eigenvalues.assign(
    basis.Pairs.Eigenvalues.data(), basis.Pairs.Eigenvalues.data() + header.Columns);
  header.Mass.assign(header.Rows, 0.0);
  for (std::size_t e = 0; e < targets.Ids.size(); ++e)
  {
    header.Mass[targets.Ids[e]] = basis.LumpedMass[targets.Rows[e]];
  }
  header.BackwardError = basis.Pairs.MaxBackwardError;
  header.Residual = basis.Pairs.MaxResidual;
  header.Warnings = basis.Warnings;
  writer.Commit(header, monitor);
}

//------------------------------------------------------------------------------
// Writes the core's basis (computed in memory: a frequency window, which is not streamed) into
// the file of `plan`, each row on its point or on every copy of a welded point, then frees the
// harmonics in memory.
void WriteBasisFile(spectral::BasisResult& basis,
  const vtkManifoldHarmonicsBasisFile::Plan& plan,
  const vtkManifoldHarmonicsParallel::Welding& welding,
  vtkIdType numPts,
  int bytesPerValue)
{
  spectral::DenseMatrix& H = basis.Pairs.Eigenvectors;
  const RowsToPoints targets =
    Targets(basis.InputPointIds, welding.Merged() ? welding.Map : std::vector<vtkIdType>(), numPts);
  spectral::BasisFileHeader header = FileHeader(plan, numPts, bytesPerValue);
  header.Columns = static_cast<std::uint64_t>(H.cols());
  spectral::BasisFileWriter writer(plan.Path, header, spectral::BasisFileWriting::Whole);
  writer.WriteColumns(0, header.Columns, H.data(), H.rows(), targets.Rows, targets.Ids);
  CommitBasisFile(writer, header, basis, targets);
  H.resize(0, 0);
}

//------------------------------------------------------------------------------
// Computes the basis of `mesh` streamed into the file of `plan` (spectral::BasisSink): each
// verified block of harmonics is written as it comes, and the n x m basis is never in memory.
// The file is sized when the stream begins: m is the number of eigenvalues when the core knows
// them, else the requested number clamped to the usable points (ClampHarmonics, Problem.h),
// checked against what came at the end. Returns the basis without harmonics.
spectral::BasisResult StreamBasisToFile(const spectral::TriangleMesh& mesh,
  spectral::BasisOptions options,
  const spectral::Monitor& monitor,
  const vtkManifoldHarmonicsBasisFile::Plan& plan,
  const vtkManifoldHarmonicsParallel::Welding& welding,
  vtkIdType numPts,
  int bytesPerValue)
{
  std::unique_ptr<spectral::BasisFileWriter> writer;
  RowsToPoints targets;
  spectral::BasisFileHeader header = FileHeader(plan, numPts, bytesPerValue);
  const int requested = options.NumberOfHarmonics;
  options.Sink.Begin = [&](const spectral::BasisResult& begun)
  {
    targets = Targets(
      begun.InputPointIds, welding.Merged() ? welding.Map : std::vector<vtkIdType>(), numPts);
    const long long usable =
      static_cast<long long>(begun.InputPointIds.size()) - begun.BoundaryPoints;
    header.Columns = static_cast<std::uint64_t>(begun.Pairs.Eigenvalues.size() > 0
        ? static_cast<long long>(begun.Pairs.Eigenvalues.size())
        : std::min<long long>(requested, usable));
    writer.reset(
      new spectral::BasisFileWriter(plan.Path, header, spectral::BasisFileWriting::InBands));
  };
  options.Sink.Harmonics =
    [&](int first, const spectral::Vector& values, const spectral::DenseMatrix& harmonics)
  {
    writer->WriteColumns(static_cast<std::uint64_t>(first),
      static_cast<std::uint64_t>(values.size()),
      harmonics.data(),
      static_cast<std::uint64_t>(harmonics.rows()),
      targets.Rows,
      targets.Ids);
  };
  // Every harmonic comes again: the file's columns are overwritten.
  options.Sink.Restart = []() {};
  // The commit moves the basis through the disk twice: the last tenth of the progress, its own
  // stage.
  spectral::BasisResult basis = spectral::ComputeBasis(mesh, options, monitor.Scaled(0.0, 0.9));
  if (!writer || static_cast<std::uint64_t>(basis.Pairs.Eigenvalues.size()) != header.Columns)
  {
    throw std::runtime_error("the streamed basis has " +
      std::to_string(basis.Pairs.Eigenvalues.size()) + " harmonics, its file was sized for " +
      std::to_string(header.Columns) + " (please report this)");
  }
  monitor.Begin("Write basis file");
  CommitBasisFile(*writer, header, basis, targets, monitor.Scaled(0.9, 1.0));
  return basis;
}

//------------------------------------------------------------------------------
// The basis of `solved` (the input's `mesh`, welded by `welding` when not null) streamed into a
// filter of the input's point coordinates: each solved row's signal is the coordinates of the
// copy the transform counts (Welding::Counted), and every copy of a welded point re-injects its
// own, as the in-memory stages do with the ghost flags the basis writes. `eigenvalues` receives
// those the stream knows: of the harmonics it solved, and the highest (ascending, mesh units).
spectral::RowMatrix StreamInto(const spectral::StreamedDesign& design,
  const spectral::TriangleMesh& mesh,
  const spectral::TriangleMesh& solved,
  const vtkManifoldHarmonicsParallel::Welding* welding,
  spectral::BasisOptions options,
  const spectral::Monitor& monitor,
  spectral::Vector& eigenvalues)
{
  const Eigen::Index n = mesh.Vertices.rows();
  const Eigen::Index rows = solved.Vertices.rows();
  spectral::RowMatrix signals(rows, 3);
  std::vector<long long> rowOf(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i)
  {
    rowOf[static_cast<std::size_t>(i)] = welding ? welding->Map[static_cast<std::size_t>(i)] : i;
  }
  for (Eigen::Index w = 0; w < rows; ++w)
  {
    signals.row(w) = mesh.Vertices.row(welding ? welding->Counted[static_cast<std::size_t>(w)] : w);
  }
  spectral::StreamedFilter filter(spectral::ConstRowView(signals.data(), rows, 3), design);
  options.Sink = filter.Sink();
  const spectral::Vector lambda =
    spectral::ComputeBasis(solved, options, monitor).Pairs.Eigenvalues;
  std::vector<double> known;
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
  {
    if (!std::isnan(lambda[k]))
    {
      known.push_back(lambda[k]);
    }
  }
  eigenvalues =
    Eigen::Map<const spectral::Vector>(known.data(), static_cast<Eigen::Index>(known.size()));
  return filter.ResultOn(spectral::ConstRowView(mesh.Vertices.data(), n, 3), rowOf);
}

//------------------------------------------------------------------------------
// The harmonics and lumped mass of the core's basis as rows of every point of a mesh of
// `numPts` points (zero on the points no cell uses), for the scatter of a distributed run.
void FullRows(const spectral::BasisResult& basis,
  vtkIdType numPts,
  spectral::RowMatrix& harmonics,
  spectral::Vector& mass)
{
  const spectral::DenseMatrix& H = basis.Pairs.Eigenvectors;
  harmonics = spectral::RowMatrix::Zero(numPts, H.cols());
  mass = spectral::Vector::Zero(numPts);
  for (std::size_t r = 0; r < basis.InputPointIds.size(); ++r)
  {
    harmonics.row(basis.InputPointIds[r]) = H.row(static_cast<Eigen::Index>(r));
    mass[basis.InputPointIds[r]] = basis.LumpedMass[static_cast<Eigen::Index>(r)];
  }
}
} // anonymous namespace

//------------------------------------------------------------------------------
struct vtkManifoldHarmonicBasis::Solution
{
  std::unique_ptr<spectral::BasisResult> Basis; // null: no cells, or a reused file
  vtkManifoldHarmonicsParallel::Welding Welding;
  vtkManifoldHarmonicsBasisFile::Plan File; // Path empty: the basis stays in memory
};

//------------------------------------------------------------------------------
vtkManifoldHarmonicBasis::vtkManifoldHarmonicBasis()
  : vtkManifoldHarmonicsAlgorithm(POINT_SET_ONLY)
  , NumberOfHarmonics(DEFAULT_NUMBER_OF_HARMONICS)
  , MassMatrix(LUMPED)
  , Laplacian(COTANGENT)
  , BoundaryCondition(NEUMANN)
  , BandSize(spectral::EigenOptions().BandSize)
  , Tolerance(spectral::EigenOptions().Tolerance)
  , MaxIterations(spectral::EigenOptions().MaxIterations)
  , BasisPrecision(DOUBLE)
  , MemoryLimit(0.0)
  , MinimumComponentSize(0)
  , NumberOfNeighbors(DEFAULT_NUMBER_OF_NEIGHBORS)
  , EigenvaluesOnly(false)
  , Solver(BUILT_IN)
  , SlepcPartitions(1)
  , WeldSeams(true)
  , SeamTolerance(vtkManifoldHarmonicsParallel::SeamTolerance)
  , Storage(AUTOMATIC)
{
  this->FrequencyWindow[0] = 0.0;
  this->FrequencyWindow[1] = 0.0;
}

//------------------------------------------------------------------------------
bool vtkManifoldHarmonicBasis::HasSlepc()
{
#ifdef MANIFOLDHARMONICS_HAS_SLEPC
  return true;
#else
  return false;
#endif
}

//------------------------------------------------------------------------------
const char* vtkManifoldHarmonicBasis::HarmonicsArrayName()
{
  return vtkManifoldHarmonicsNames::Harmonics;
}

//------------------------------------------------------------------------------
const char* vtkManifoldHarmonicBasis::MassArrayName()
{
  return vtkManifoldHarmonicsNames::Mass;
}

//------------------------------------------------------------------------------
const char* vtkManifoldHarmonicBasis::EigenvaluesArrayName()
{
  return vtkManifoldHarmonicsNames::Eigenvalues;
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicBasis::Execute(vtkPointSet* input,
  vtkPointSet* output,
  vtkTable* vtkNotUsed(table))
{
  const int status = this->ChooseAndRun(input, output);
  if (status == 0 || this->AbortRequested())
  {
    // No harmonics were computed: nothing was kept anywhere.
    this->StorageUsed = AUTOMATIC;
    this->StorageReason.clear();
  }
  return status;
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicBasis::ChooseAndRun(vtkPointSet* input, vtkPointSet* output)
{
  if (!vtkManifoldHarmonicsParameters::AcceptNumbers(this,
        { { "Tolerance", this->Tolerance },
          { "SeamTolerance", this->SeamTolerance },
          { "MemoryLimit", this->MemoryLimit } }))
  {
    return 0;
  }
  if ((this->Storage == FILE || !this->BasisFileName.empty()) &&
    (this->Solver == SLEPC || vtkManifoldHarmonicsParallel::DistributedController()))
  {
    // Refused alike on every process, before any collective step.
    vtkErrorMacro(<< "A basis in a file (Storage File or a BasisFileName) is available in serial "
                     "runs of the Built-in solver only: choose Storage In Memory or Automatic and "
                     "leave BasisFileName empty, or compute the basis in a serial run.");
    return 0;
  }
  this->StorageUsed = AUTOMATIC;
  this->StorageReason.clear();
  this->BasisReused = false;
  if (this->Solver == SLEPC)
  {
    // Every process takes part, with or without cells.
    return this->ComputeSlepcBasis(input, output);
  }
  vtkPolyData* surface = vtkPolyData::SafeDownCast(input);
  const bool hasSurface = surface && surface->GetNumberOfPolys() + surface->GetNumberOfStrips() > 0;
  if (vtkMultiProcessController* controller = vtkManifoldHarmonicsParallel::DistributedController())
  {
    // The basis is global: never a per-piece basis when several processes hold the mesh. Only
    // vtkPolyData surfaces are gathered so far (both counts are collective); volumes and
    // point clouds (points without a surface) are refused.
    const bool otherCells = !hasSurface && input->GetNumberOfPoints() > 0;
    // Points without cells, or with vertex cells only: a point cloud.
    const bool cloud = otherCells &&
      (input->GetNumberOfCells() == 0 || (surface && surface->GetNumberOfLines() == 0));
    const int others = vtkManifoldHarmonicsParallel::CountRanks(controller, otherCells);
    const int clouds = vtkManifoldHarmonicsParallel::CountRanks(controller, cloud);
    const int holders =
      vtkManifoldHarmonicsParallel::CountRanks(controller, hasSurface || otherCells);
    if (holders > 1)
    {
      if (clouds > 0)
      {
        vtkErrorMacro(<< "A point cloud (points without triangles or tetrahedra) held by several "
                         "processes has no harmonics yet: neither solver takes a distributed "
                         "cloud. Compute its harmonics in a serial run, or gather it on one "
                         "process first (Merge Blocks, Reduction).");
        return 0;
      }
      if (others > 0)
      {
        vtkErrorMacro(<< "The Built-in solver takes distributed surfaces (vtkPolyData with "
                         "polygons) only: this mesh, a volume or other cells ("
                      << input->GetClassName()
                      << " on this process), is held by several processes. Choose Solver SLEPc, "
                         "compute its harmonics in a serial run, or gather it on one process "
                         "first (Merge Blocks, Reduction).");
        return 0;
      }
      return this->ComputeDistributedBasis(controller, surface, vtkPolyData::SafeDownCast(output));
    }
    if (holders == 0 && controller->GetLocalProcessId() == 0)
    {
      vtkWarningMacro(<< NothingToSolve << ", in any process's piece; passing the input through.");
    }
    if (!hasSurface && !otherCells)
    {
      // Another process (or none) holds the whole surface.
      output->ShallowCopy(input);
      return 1;
    }
  }
  return this->ComputeBasis(input, output, this->WeldSeams);
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicBasis::ComputeDistributedBasis(vtkMultiProcessController* controller,
  vtkPolyData* input,
  vtkPolyData* output)
{
  if (this->EigenvaluesOnly)
  {
    // Refused on every process alike, before any collective step.
    vtkErrorMacro(<< "EigenvaluesOnly is not available in distributed runs yet: turn it off, or "
                     "compute the spectrum in a serial run.");
    return 0;
  }
  const bool hasSurface = input->GetNumberOfPolys() + input->GetNumberOfStrips() > 0;
  vtkSmartPointer<vtkPolyData> piece = input;
  if (hasSurface)
  {
    piece = ::Triangulate(this, input);
  }
  if (!this->WeldSeams && controller->GetLocalProcessId() == 0)
  {
    vtkWarningMacro(<< KeptSeamsIgnored);
  }
  const vtkManifoldHarmonicsParallel::MergedMesh merged =
    vtkManifoldHarmonicsParallel::GatherAndMerge(controller, piece, this->SeamTolerance);

  // Process 0 solves on the merged surface (welded already by GatherAndMerge), in Eigen from
  // the solve to the scatter.
  int status = 1;
  spectral::RowMatrix harmonics;
  spectral::Vector mass;
  spectral::Vector eigenvalues;
  std::array<double, 2> figures = { 0.0, 0.0 };
  if (controller->GetLocalProcessId() == 0)
  {
    Solution solution;
    status = this->Solve(merged.Surface, false, solution, false);
    if (status && solution.Basis)
    {
      ::FullRows(*solution.Basis, merged.Surface->GetNumberOfPoints(), harmonics, mass);
      eigenvalues = solution.Basis->Pairs.Eigenvalues;
      figures = { solution.Basis->Pairs.MaxBackwardError, solution.Basis->Pairs.MaxResidual };
    }
  }
  vtkManifoldHarmonicsParallel::PieceBasis rows;
  if (!vtkManifoldHarmonicsParallel::ScatterBasis(
        controller, harmonics.size() > 0, merged, harmonics, mass, eigenvalues, figures, rows))
  {
    // Fail on every process (also after a cancel), so that no downstream stage runs on some
    // processes only and waits for the others.
    if (controller->GetLocalProcessId() == 0 && status == 0)
    {
      return 0;
    }
    vtkErrorMacro(<< "The manifold harmonics of the distributed surface failed on process 0.");
    return 0;
  }
  ::AddPieceArrays(output, input, rows, this->BasisPrecision == FLOAT);
  return 1;
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicBasis::ComputeSlepcBasis(vtkPointSet* input, vtkPointSet* output)
{
  // The settings the SLEPc solver does not have, refused alike on every process before any
  // collective step.
  const std::string unsupported = ::SlepcUnsupported(this);
  if (!unsupported.empty())
  {
    vtkErrorMacro(<< "The SLEPc solver does not support " << unsupported
                  << " yet: choose the Built-in solver, or leave it at its default.");
    return 0;
  }
#ifdef MANIFOLDHARMONICS_HAS_SLEPC
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (this->MemoryLimit > 0.0 && (!controller || controller->GetLocalProcessId() == 0))
  {
    vtkWarningMacro(<< "MemoryLimit " << this->MemoryLimit
                    << " MiB does not apply to the SLEPc solver, which checks no memory estimate "
                       "(each process holds the rows of its own points and its share of the "
                       "matrices and factors).");
  }
  this->StorageUsed = IN_MEMORY;
  this->StorageReason = "in memory: each process keeps the rows of its own points (SLEPc solver)";
  const vtkManifoldHarmonicsArrays::CoreMesh cells = vtkManifoldHarmonicsArrays::ToCoreMesh(input);
  for (const std::string& warning : cells.Warnings())
  {
    vtkWarningMacro(<< warning);
  }
  if (!::SlepcPiecesUsable(this, controller, cells, input))
  {
    return 0;
  }
  // Progress [0, 0.95]: writing the arrays is the rest.
  const spectral::Monitor monitor = this->MakeMonitor(0.95);
  return this->Guard(
           [&]() { ::SolveWithSlepc(this, controller, cells.Mesh, input, output, monitor); })
    ? 1
    : 0;
#else
  (void)input;
  (void)output;
  vtkErrorMacro(<< "This build of the module has no SLEPc solver (SLEPc was not found when it "
                   "was built): choose the Built-in solver, or rebuild with libslepc-real-dev.");
  return 0;
#endif
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicBasis::ComputeBasis(vtkPointSet* input, vtkPointSet* output, bool weld)
{
  Solution solution;
  if (!this->Solve(input, weld, solution, true))
  {
    return 0;
  }
  output->ShallowCopy(input);
  if (solution.Basis || solution.File.Reuse)
  {
    this->SetProgressText("Write");
    if (!this->Guard(
          [&]()
          {
            ::WriteBasis(output,
              input,
              solution.Basis.get(),
              solution.File,
              solution.Welding,
              this->BasisPrecision == FLOAT);
          }))
    {
      output->Initialize();
      return 0;
    }
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicBasis::SolveStreamed(vtkPointSet* input, StreamRequest& request)
{
  Solution solution;
  return this->Solve(input, this->WeldSeams, solution, false, &request);
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicBasis::Solve(vtkPointSet* input,
  bool weld,
  Solution& solution,
  bool allowFile,
  StreamRequest* stream)
{
  vtkDebugMacro(<< "Computing " << this->NumberOfHarmonics << " harmonics, mass matrix "
                << this->MassMatrix << ", Laplacian " << this->Laplacian << ", band size "
                << this->BandSize << ", tolerance " << this->Tolerance << ", max iterations "
                << this->MaxIterations << ", basis precision " << this->BasisPrecision
                << ", memory limit " << this->MemoryLimit << " MiB");
  const vtkIdType numPts = input->GetNumberOfPoints();
  const vtkManifoldHarmonicsArrays::CoreMesh cells = vtkManifoldHarmonicsArrays::ToCoreMesh(input);
  const std::string problem = cells.Problem();
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  if (numPts == 0 || (!cells.HasCells() && !cells.IsPointCloud()))
  {
    vtkWarningMacro(<< NothingToSolve << "; passing the input through.");
    return 1;
  }
  ::WarnAboutCells(this, cells);
  if (numPts > VTK_INT_MAX)
  {
    vtkErrorMacro(<< "Too many points: " << numPts << " (at most " << VTK_INT_MAX << ").");
    return 0;
  }
  this->SolvedPoints = numPts;
  const spectral::Monitor monitor = this->MakeMonitor(0.95);
  spectral::BasisOptions options = ::CoreOptions(this);
  if (stream)
  {
    // Streamed into the smoothing's filter: no basis is kept, in memory or in a file.
  }
  else if (!allowFile)
  {
    this->StorageUsed = IN_MEMORY;
    this->StorageReason = "in memory: process 0 of a distributed run scatters it";
  }
  else if (!vtkManifoldHarmonicsBasisFile::PlanStorage(this,
             options,
             cells.Mesh,
             numPts,
             solution.File,
             this->StorageUsed,
             this->StorageReason))
  {
    return 0;
  }
  this->FileRefusal = solution.File.Refusal;
  const int bytesPerValue = options.BytesPerValue;
  if (!solution.File.Path.empty() && !solution.File.Streamed)
  {
    // The output basis is in the file: the memory check of the solve leaves it out.
    options.BytesPerValue = 0;
  }
  if (solution.File.WriterBytes > 0 && options.MemoryLimit > 0)
  {
    // The writer holds its memory beside the solve: the solve plans in the rest of the limit, as
    // the storage choice did (vtkManifoldHarmonicsBasisFile::PlanStorage).
    options.MemoryLimit = spectral::MemoryShare(options.MemoryLimit, solution.File.WriterBytes);
  }
  return this->Guard(
           [&]()
           {
             // The seam rule of every path: coincident points are one point (their copies get
             // its rows).
             spectral::TriangleMesh welded;
             const bool merged =
               weld && ::WeldMesh(cells.Mesh, input, this->SeamTolerance, solution.Welding, welded);
             ::WarnAboutOpenSeams(this, merged ? welded : cells.Mesh);
             if (stream)
             {
               stream->Filtered = ::StreamInto(stream->Design,
                 cells.Mesh,
                 merged ? welded : cells.Mesh,
                 merged ? &solution.Welding : nullptr,
                 options,
                 monitor,
                 stream->Eigenvalues);
               return;
             }
             if (solution.File.Reuse)
             {
               this->BasisReused = true;
               for (const std::string& warning : solution.File.Header.Warnings)
               {
                 vtkWarningMacro(<< "(reused basis file) " << warning);
               }
               return;
             }
             const spectral::TriangleMesh& solved = merged ? welded : cells.Mesh;
             if (solution.File.Streamed)
             {
               solution.Basis.reset(new spectral::BasisResult(::StreamBasisToFile(solved,
                 options,
                 monitor,
                 solution.File,
                 solution.Welding,
                 numPts,
                 bytesPerValue)));
               return;
             }
             solution.Basis.reset(
               new spectral::BasisResult(spectral::ComputeBasis(solved, options, monitor)));
             if (!solution.File.Path.empty())
             {
               ::WriteBasisFile(
                 *solution.Basis, solution.File, solution.Welding, numPts, bytesPerValue);
             }
           })
    ? 1
    : 0;
}

//------------------------------------------------------------------------------
std::string vtkManifoldHarmonicBasis::DescribeFailure(const std::exception& e)
{
  if (const auto* memory = dynamic_cast<const spectral::InsufficientMemory*>(&e))
  {
    // With Storage AUTOMATIC: why no file would do either.
    return ::MemoryProblem(this, this->SolvedPoints, *memory) +
      (this->FileRefusal.empty() ? std::string() : " " + this->FileRefusal);
  }
  if (dynamic_cast<const spectral::InvalidInput*>(&e))
  {
    return std::string("Invalid input: ") + e.what();
  }
  if (const auto* solver = dynamic_cast<const spectral::SolverFailure*>(&e))
  {
    return "Eigensolver failed (" + std::to_string(solver->Converged) +
      " pairs converged): " + e.what();
  }
  return this->Superclass::DescribeFailure(e);
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicBasis::SetNumberOfHarmonics(int m)
{
  if (vtkManifoldHarmonicsParameters::AcceptNumberOfHarmonics(this, m, this->NumberOfHarmonics) &&
    m != this->NumberOfHarmonics)
  {
    this->NumberOfHarmonics = m;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkManifoldHarmonicBasis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  namespace Enums = vtkManifoldHarmonicsEnums;
  const auto onOff = [](bool value) { return value ? "On" : "Off"; };
  os << indent << "NumberOfHarmonics: " << this->NumberOfHarmonics << "\n";
  os << indent << "MassMatrix: " << Enums::Name(Enums::MassMatrix, this->MassMatrix) << "\n";
  os << indent << "Laplacian: " << Enums::Name(Enums::Laplacian, this->Laplacian) << "\n";
  os << indent
     << "BoundaryCondition: " << Enums::Name(Enums::BoundaryCondition, this->BoundaryCondition)
     << "\n";
  os << indent << "BandSize: " << this->BandSize << (this->BandSize == 0 ? " (automatic)\n" : "\n");
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "MaxIterations: " << this->MaxIterations << "\n";
  os << indent << "BasisPrecision: " << Enums::Name(Enums::BasisPrecision, this->BasisPrecision)
     << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << " MiB"
     << (this->MemoryLimit > 0.0 ? "\n" : " (the memory the system reports available)\n");
  os << indent << "MinimumComponentSize: " << this->MinimumComponentSize << "\n";
  os << indent << "NumberOfNeighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "EigenvaluesOnly: " << onOff(this->EigenvaluesOnly) << "\n";
  os << indent << "FrequencyWindow: [" << this->FrequencyWindow[0] << ", "
     << this->FrequencyWindow[1] << ")"
     << (spectral::IsFrequencyWindow(this->FrequencyWindow[0], this->FrequencyWindow[1])
            ? "\n"
            : " (off)\n");
  os << indent << "Solver: " << Enums::Name(Enums::Solver, this->Solver) << "\n";
  os << indent << "SlepcPartitions: " << this->SlepcPartitions << "\n";
  os << indent << "SlepcOptions: \"" << this->SlepcOptions << "\"\n";
  os << indent << "WeldSeams: " << onOff(this->WeldSeams) << "\n";
  os << indent << "SeamTolerance: " << this->SeamTolerance << " of the bounding box diagonal\n";
  os << indent << "Storage: " << Enums::Name(Enums::Storage, this->Storage) << "\n";
  os << indent << "BasisFileName: \"" << this->BasisFileName << "\""
     << (this->BasisFileName.empty() ? " (a temporary file when the basis is kept in a file)\n"
                                     : "\n");
}
