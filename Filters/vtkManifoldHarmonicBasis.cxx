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
#include "vtkManifoldHarmonicsGhosts.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkManifoldHarmonicsParallel.h"
#include "vtkManifoldHarmonicsParameters.h"
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

#ifdef MANIFOLDHARMONICS_HAS_SLEPC
#include "vtkManifoldHarmonicsSlepc.h"
#endif

#include <algorithm>
#include <cstdint>
#include <iomanip>
#include <limits>
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
static_assert(
  vtkManifoldHarmonicBasis::NEUMANN == static_cast<int>(spectral::BoundaryCondition::Neumann) &&
    vtkManifoldHarmonicBasis::DIRICHLET == static_cast<int>(spectral::BoundaryCondition::Dirichlet),
  "the boundary conditions have their home in Spectral/Operators/Laplacian.h");

namespace
{
//------------------------------------------------------------------------------
// Where the rows of the core's result go: row Rows[e] of the result is written onto output
// point Ids[e]. A row goes to several points when the point was welded (each copy gets it).
struct RowsToPoints
{
  std::vector<int> Rows;
  std::vector<vtkIdType> Ids;
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
  for (Eigen::Index k = 0; k < H.cols(); ++k)
  {
    harmonics->SetComponentName(k, ("Phi_" + std::to_string(k)).c_str());
  }
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

  vtkNew<vtkDoubleArray> eigenvalues;
  eigenvalues->SetName(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  eigenvalues->SetNumberOfTuples(m);
  std::copy(result.Eigenvalues.data(), result.Eigenvalues.data() + m, eigenvalues->GetPointer(0));
  output->GetFieldData()->AddArray(eigenvalues);
  for (const auto& figure :
    { std::make_pair(vtkManifoldHarmonicsNames::BackwardError, result.MaxBackwardError),
      std::make_pair(vtkManifoldHarmonicsNames::Residual, result.MaxResidual) })
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(figure.first);
    array->InsertNextValue(figure.second);
    output->GetFieldData()->AddArray(array);
  }
}

//------------------------------------------------------------------------------
// The polygons and strips of the input as triangles, through an internal vtkTriangleFilter
// when the input holds anything but triangles. Vertices and lines are passed on, for ToCoreMesh
// to leave out with a warning; ghost cells are dropped (vtkManifoldHarmonicsGhosts: another
// process owns them). The points are the input's.
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
// mass (also on its ghost points: the owner's rows), the eigenvalues, and the point ghost array:
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
  harmonics->SetName(vtkManifoldHarmonicBasis::HarmonicsArrayName());
  for (int k = 0; k < m; ++k)
  {
    harmonics->SetComponentName(k, ("Phi_" + std::to_string(k)).c_str());
  }
  rows.Mass->SetName(vtkManifoldHarmonicBasis::MassArrayName());
  output->GetPointData()->AddArray(harmonics);
  output->GetPointData()->AddArray(rows.Mass);
  AddPointGhosts(output, input, rows.Duplicates);

  vtkNew<vtkDoubleArray> eigenvalues;
  eigenvalues->SetName(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  eigenvalues->SetNumberOfTuples(m);
  std::copy(rows.Eigenvalues.data(), rows.Eigenvalues.data() + m, eigenvalues->GetPointer(0));
  output->GetFieldData()->AddArray(eigenvalues);
}

//------------------------------------------------------------------------------
// A byte count for people: "1.5 GiB", "380.0 MiB", "12.0 KiB".
std::string Bytes(std::uint64_t bytes)
{
  const char* units[] = { "bytes", "KiB", "MiB", "GiB", "TiB" };
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 4)
  {
    value /= 1024.0;
    ++unit;
  }
  std::ostringstream text;
  text << std::fixed << std::setprecision(unit == 0 ? 0 : 1) << value << " " << units[unit];
  return text.str();
}

//------------------------------------------------------------------------------
// The error message of a computation that does not fit in memory: what is needed, what is
// available, what to change.
std::string MemoryProblem(vtkManifoldHarmonicBasis* self,
  vtkIdType numPts,
  const spectral::InsufficientMemory& e)
{
  const int m = e.Harmonics;
  const bool floats = self->GetBasisPrecision() == vtkManifoldHarmonicBasis::FLOAT;
  const bool limited = self->GetMemoryLimit() > 0.0;
  const spectral::MemoryEstimate& need = e.Needed;
  std::ostringstream message;
  message << "Not enough memory for " << m << " harmonics on " << numPts << " points: about "
          << Bytes(need.Total()) << " needed (basis " << Bytes(need.Basis)
          << ", solver eigenvectors " << Bytes(need.Eigenvectors) << ", Lanczos workspace "
          << Bytes(need.Krylov) << ", sparse factor " << Bytes(need.Factor) << "), "
          << Bytes(e.Available) << " available ("
          << (limited ? "MemoryLimit" : "reported by the system") << "). Compute fewer harmonics";
  if (!floats)
  {
    message << ", set BasisPrecision to Float (saves " << Bytes(need.Basis / 2) << ")";
  }
  message << ", choose a smaller BandSize (now "
          << spectral::EffectiveBandSize(m, self->GetBandSize()) << ")"
          << (limited ? " or raise MemoryLimit." : " or free memory.");
  return message.str();
}

//------------------------------------------------------------------------------
// The warning of a distributed run with WeldSeams off.
constexpr const char* KeptSeamsIgnored =
  "WeldSeams is off, but a distributed run merges the points that coincide within SeamTolerance "
  "(it cannot tell a seam inside a piece from one between pieces): keep seams open in a serial "
  "run.";

//------------------------------------------------------------------------------
// The settings of the filter as options of the core's entry point.
spectral::BasisOptions CoreOptions(vtkManifoldHarmonicBasis* self)
{
  spectral::BasisOptions options;
  options.NumberOfHarmonics = self->GetNumberOfHarmonics();
  options.Operators.Laplacian = self->GetLaplacian() == vtkManifoldHarmonicBasis::INTRINSIC_DELAUNAY
    ? spectral::LaplacianKind::IntrinsicDelaunay
    : spectral::LaplacianKind::Cotangent;
  options.Operators.Boundary =
    static_cast<spectral::BoundaryCondition>(self->GetBoundaryCondition());
  options.Operators.Mass = self->GetMassMatrix() == vtkManifoldHarmonicBasis::CONSISTENT
    ? spectral::MassKind::Consistent
    : spectral::MassKind::Lumped;
  options.Solver.BandSize = self->GetBandSize();
  options.Solver.Tolerance = self->GetTolerance();
  options.Solver.MaxIterations = self->GetMaxIterations();
  options.MinimumComponentSize = self->GetMinimumComponentSize();
  options.NumberOfNeighbors = self->GetNumberOfNeighbors();
  options.Solver.Threads = self->GetNumberOfThreads();
  options.EigenvaluesOnly = self->GetEigenvaluesOnly();
  options.LowerFrequency = self->GetFrequencyWindow()[0];
  options.UpperFrequency = self->GetFrequencyWindow()[1];
  options.BytesPerValue = self->GetBasisPrecision() == vtkManifoldHarmonicBasis::FLOAT ? 4 : 8;
  // A limit below one byte still limits (0 would mean "ask the system").
  options.MemoryLimit = self->GetMemoryLimit() > 0.0
    ? std::max<std::uint64_t>(1, static_cast<std::uint64_t>(self->GetMemoryLimit() * 1048576.0))
    : 0;
  return options;
}

//------------------------------------------------------------------------------
// A monitor that reports the core's progress, steps and warnings through the filter and polls
// its abort flag. The core's progress [0, 1] becomes [0, 0.95]; writing the arrays is the rest.
spectral::Monitor FilterMonitor(vtkManifoldHarmonicBasis* self)
{
  spectral::Monitor monitor;
  monitor.Progress = [self](double fraction) { self->UpdateProgress(0.95 * fraction); };
  monitor.Cancelled = [self]() { return self->GetAbortExecute() != 0; };
  monitor.Stage = [self](const char* stage) { self->SetProgressText(stage); };
  monitor.Warning = [self](const std::string& text) { vtkWarningWithObjectMacro(self, << text); };
  return monitor;
}
} // anonymous namespace

//------------------------------------------------------------------------------
vtkManifoldHarmonicBasis::vtkManifoldHarmonicBasis()
  : NumberOfHarmonics(DEFAULT_NUMBER_OF_HARMONICS)
  , MassMatrix(LUMPED)
  , Laplacian(COTANGENT)
  , BoundaryCondition(NEUMANN)
  , BandSize(0)
  , Tolerance(1e-11)
  , MaxIterations(1000)
  , BasisPrecision(DOUBLE)
  , MemoryLimit(0.0)
  , MinimumComponentSize(0)
  , NumberOfNeighbors(DEFAULT_NUMBER_OF_NEIGHBORS)
  , NumberOfThreads(0)
  , EigenvaluesOnly(false)
  , Solver(BUILT_IN)
  , SlepcPartitions(1)
  , WeldSeams(true)
  , SeamTolerance(vtkManifoldHarmonicsParallel::SeamTolerance)
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
int vtkManifoldHarmonicBasis::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPointSet* output = vtkPointSet::GetData(outputVector);
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
    const int others = vtkManifoldHarmonicsParallel::CountRanks(controller, otherCells);
    if (vtkManifoldHarmonicsParallel::CountRanks(controller, hasSurface || otherCells) > 1)
    {
      if (others > 0)
      {
        vtkErrorMacro(<< "The Built-in solver takes distributed vtkPolyData surfaces only: this "
                         "mesh ("
                      << input->GetClassName()
                      << ") is held by several processes. Choose Solver SLEPc (volumes), "
                         "compute its harmonics in a serial run, or gather it on one process "
                         "first (Merge Blocks, Reduction).");
        output->Initialize();
        return 0;
      }
      return this->ComputeDistributedBasis(controller, surface, vtkPolyData::SafeDownCast(output));
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
    output->Initialize();
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

  // Process 0 solves on the merged surface.
  int status = 1;
  spectral::RowMatrix harmonics;
  spectral::Vector mass;
  spectral::Vector eigenvalues;
  if (controller->GetLocalProcessId() == 0)
  {
    vtkNew<vtkPolyData> whole;
    // The pieces are welded already (GatherAndMerge).
    status = this->ComputeBasis(merged.Surface, whole, false);
    vtkDataArray* h = whole->GetPointData()->GetArray(HarmonicsArrayName());
    vtkDataArray* d = whole->GetPointData()->GetArray(MassArrayName());
    vtkDataArray* lambda = whole->GetFieldData()->GetArray(EigenvaluesArrayName());
    if (status && h && d && lambda)
    {
      harmonics = vtkManifoldHarmonicsArrays::Signal(h).View();
      mass = vtkManifoldHarmonicsArrays::Signal(d).View().col(0);
      eigenvalues = vtkManifoldHarmonicsArrays::Signal(lambda).View().col(0);
    }
  }
  vtkManifoldHarmonicsParallel::PieceBasis rows;
  if (!vtkManifoldHarmonicsParallel::ScatterBasis(
        controller, harmonics.size() > 0, merged, harmonics, mass, eigenvalues, rows))
  {
    // Fail on every process (also after a cancel), so that no downstream stage runs on some
    // processes only and waits for the others.
    output->Initialize();
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
  output->Initialize();
  // The settings the SLEPc solver does not have, refused alike on every process before any
  // collective step.
  std::string unsupported;
  if (this->Laplacian != COTANGENT)
  {
    unsupported = "Laplacian Intrinsic Delaunay";
  }
  else if (this->EigenvaluesOnly)
  {
    unsupported = "EigenvaluesOnly";
  }
  else if (this->MinimumComponentSize > 0)
  {
    unsupported = "MinimumComponentSize";
  }
  else if (this->BoundaryCondition != NEUMANN)
  {
    unsupported = "BoundaryCondition Dirichlet";
  }
  if (!unsupported.empty())
  {
    vtkErrorMacro(<< "The SLEPc solver does not support " << unsupported
                  << " yet: choose the Built-in solver, or leave it at its default.");
    return 0;
  }
#ifdef MANIFOLDHARMONICS_HAS_SLEPC
  vtkManifoldHarmonicsSlepc::Settings settings;
  settings.NumberOfHarmonics = this->NumberOfHarmonics;
  settings.ConsistentMass = this->MassMatrix == CONSISTENT;
  settings.Partitions = this->SlepcPartitions;
  settings.Options = this->SlepcOptions;
  settings.Tolerance = this->Tolerance;
  settings.MaxIterations = this->MaxIterations;
  settings.WeldSeams = this->WeldSeams;
  settings.SeamTolerance = this->SeamTolerance;
  settings.LowerFrequency = this->FrequencyWindow[0];
  settings.UpperFrequency = this->FrequencyWindow[1];
  // The owner rule of every path (Spectral/Common/Seams.h) reads the input's point ghost flags.
  const spectral::Vector ownedPoints = vtkManifoldHarmonicsGhosts::OwnedPoints(input);
  for (Eigen::Index i = 0; i < ownedPoints.size(); ++i)
  {
    settings.OwnedPoints.push_back(ownedPoints[i] > 0.0 ? 1 : 0);
  }
  settings.Progress = [this](double fraction) { this->UpdateProgress(0.95 * fraction); };
  settings.Stage = [this](const char* stage) { this->SetProgressText(stage); };
  settings.Cancelled = [this]() { return this->GetAbortExecute() != 0; };
  settings.Warning = [this](const std::string& text) { vtkWarningMacro(<< text); };
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  // The cells of this piece in the core's form: polygons of a vtkPolyData through
  // vtkTriangleFilter, other cells through ToCoreMesh (ghost cells left out by both).
  vtkSmartPointer<vtkPointSet> triangulated = input;
  vtkPolyData* polygons = vtkPolyData::SafeDownCast(input);
  if (polygons && polygons->GetNumberOfPolys() + polygons->GetNumberOfStrips() > 0)
  {
    triangulated = ::Triangulate(this, polygons);
  }
  const vtkManifoldHarmonicsArrays::CoreMesh cells =
    vtkManifoldHarmonicsArrays::ToCoreMesh(triangulated);
  for (const std::string& warning : cells.Warnings())
  {
    vtkWarningMacro(<< warning);
  }
  // Pieces that cannot be used, and point clouds (points on some process, cells on none), are
  // refused on every process alike (the counts are collective).
  const bool distributed = controller && controller->GetNumberOfProcesses() > 1;
  if (distributed && !this->WeldSeams && controller->GetLocalProcessId() == 0)
  {
    vtkWarningMacro(<< KeptSeamsIgnored);
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
      vtkErrorMacro(<< "The SLEPc solver cannot use this piece: " << problem);
    }
    else
    {
      vtkErrorMacro(<< "The SLEPc solver stopped: another process's piece cannot be used.");
    }
    return 0;
  }
  if (withCells == 0 && withPoints > 0)
  {
    vtkErrorMacro(<< "The SLEPc solver does not take point clouds (points without triangles or "
                     "tetrahedra) yet: choose the Built-in solver in a serial run.");
    return 0;
  }
  try
  {
    const vtkManifoldHarmonicsSlepc::Result result =
      vtkManifoldHarmonicsSlepc::Solve(controller, cells.Mesh, settings);
    ::AddPieceArrays(output, input, result.Rows, this->BasisPrecision == FLOAT);
    for (const auto& figure :
      { std::make_pair(vtkManifoldHarmonicsNames::BackwardError, result.MaxBackwardError),
        std::make_pair(vtkManifoldHarmonicsNames::Residual, result.MaxResidual),
        std::make_pair(vtkManifoldHarmonicsNames::OrthonormalityError, result.OrthonormalityError),
        std::make_pair(
          vtkManifoldHarmonicsNames::InertiaCount, static_cast<double>(result.InertiaCount)) })
    {
      vtkNew<vtkDoubleArray> array;
      array->SetName(figure.first);
      array->InsertNextValue(figure.second);
      output->GetFieldData()->AddArray(array);
    }
    vtkDebugMacro(<< "SLEPc: " << result.GlobalPoints << " points, " << result.OwnedPoints
                  << " owned here, " << result.Computed << " pairs in [0, " << result.UpperEnd
                  << "), " << result.Shifts << " shifts");
    this->UpdateProgress(1.0);
    return 1;
  }
  catch (const vtkManifoldHarmonicsSlepc::Cancelled&)
  {
    output->Initialize();
    return 1;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "The SLEPc solver failed: " << e.what());
  }
  output->Initialize();
  return 0;
#else
  (void)input;
  vtkErrorMacro(<< "This build of the module has no SLEPc solver (SLEPc was not found when it "
                   "was built): choose the Built-in solver, or rebuild with libslepc-real-dev.");
  return 0;
#endif
}

//------------------------------------------------------------------------------
int vtkManifoldHarmonicBasis::ComputeBasis(vtkPointSet* input, vtkPointSet* output, bool weld)
{
  vtkDebugMacro(<< "Computing " << this->NumberOfHarmonics << " harmonics, mass matrix "
                << this->MassMatrix << ", Laplacian " << this->Laplacian << ", band size "
                << this->BandSize << ", tolerance " << this->Tolerance << ", max iterations "
                << this->MaxIterations << ", basis precision " << this->BasisPrecision
                << ", memory limit " << this->MemoryLimit << " MiB");

  const vtkIdType numPts = input->GetNumberOfPoints();
  // Polygons of a vtkPolyData through vtkTriangleFilter (concave ones too); other point sets'
  // cells through ToCoreMesh.
  vtkPolyData* polygons = vtkPolyData::SafeDownCast(input);
  vtkSmartPointer<vtkPointSet> triangulated = input;
  if (polygons && numPts > 0 && polygons->GetNumberOfPolys() + polygons->GetNumberOfStrips() > 0)
  {
    triangulated = ::Triangulate(this, polygons);
  }
  const vtkManifoldHarmonicsArrays::CoreMesh cells =
    vtkManifoldHarmonicsArrays::ToCoreMesh(triangulated);
  const std::string problem = cells.Problem();
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    output->Initialize();
    return 0;
  }
  if (numPts == 0 || (!cells.HasCells() && !cells.IsPointCloud()))
  {
    vtkWarningMacro(<< "No polygons or volume cells to compute manifold harmonics on; passing "
                       "the input through.");
    output->ShallowCopy(input);
    return 1;
  }
  for (const std::string& warning : cells.Warnings())
  {
    vtkWarningMacro(<< warning);
  }
  const std::string cloud = cells.PointCloudWarning(this->NumberOfNeighbors);
  if (!cloud.empty())
  {
    vtkWarningMacro(<< cloud);
  }
  if (numPts > VTK_INT_MAX)
  {
    vtkErrorMacro(<< "Too many points: " << numPts << " (at most " << VTK_INT_MAX << ").");
    return 0;
  }

  try
  {
    // The seam rule of every path: coincident points are one point (their copies get its rows).
    vtkManifoldHarmonicsParallel::Welding welding;
    spectral::TriangleMesh welded;
    const spectral::TriangleMesh& mesh =
      weld && ::WeldMesh(cells.Mesh, input, this->SeamTolerance, welding, welded) ? welded
                                                                                  : cells.Mesh;
    const spectral::BasisResult basis =
      spectral::ComputeBasis(mesh, ::CoreOptions(this), ::FilterMonitor(this));
    this->SetProgressText("Write");
    output->ShallowCopy(input);
    ::AddBasisArrays(output,
      basis.Pairs,
      ::Targets(
        basis.InputPointIds, welding.Merged() ? welding.Map : std::vector<vtkIdType>(), numPts),
      basis.LumpedMass,
      this->BasisPrecision == FLOAT);
    if (welding.Merged())
    {
      ::AddPointGhosts(output, input, ::WeldedDuplicates(welding));
    }
    this->UpdateProgress(1.0);
    return 1;
  }
  catch (const spectral::InsufficientMemory& e)
  {
    vtkErrorMacro(<< ::MemoryProblem(this, numPts, e));
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
  os << indent << "Number Of Harmonics: " << this->NumberOfHarmonics << " (default "
     << DEFAULT_NUMBER_OF_HARMONICS << ")\n";
  os << indent << "Mass Matrix: " << (this->MassMatrix == CONSISTENT ? "Consistent" : "Lumped")
     << " (default Lumped)\n";
  os << indent << "Laplacian: "
     << (this->Laplacian == INTRINSIC_DELAUNAY ? "Intrinsic Delaunay" : "Cotangent")
     << " (default Cotangent)\n";
  os << indent
     << "Boundary Condition: " << (this->BoundaryCondition == DIRICHLET ? "Dirichlet" : "Neumann")
     << " (default Neumann)\n";
  os << indent << "Band Size: " << this->BandSize << " (default 0, automatic)\n";
  os << indent << "Tolerance: " << this->Tolerance << " (default 1e-11)\n";
  os << indent << "Max Iterations: " << this->MaxIterations << " (default 1000)\n";
  os << indent << "Basis Precision: " << (this->BasisPrecision == FLOAT ? "Float" : "Double")
     << " (default Double)\n";
  os << indent << "Memory Limit: " << this->MemoryLimit
     << " MiB (default 0, the memory the system reports available)\n";
  os << indent << "Minimum Component Size: " << this->MinimumComponentSize
     << " (default 0, every component)\n";
  os << indent << "Number Of Neighbors: " << this->NumberOfNeighbors << "\n";
  os << indent << "Number Of Threads: " << this->NumberOfThreads << " (default 0, every core)\n";
  os << indent << "Eigenvalues Only: " << (this->EigenvaluesOnly ? "on" : "off")
     << " (default off)\n";
  os << indent << "Solver: " << (this->Solver == SLEPC ? "SLEPc" : "Built-in")
     << " (default Built-in)\n";
  os << indent << "Slepc Partitions: " << this->SlepcPartitions << " (default 1)\n";
  os << indent << "Slepc Options: \"" << this->SlepcOptions << "\" (default none)\n";
  os << indent << "Frequency Window: [" << this->FrequencyWindow[0] << ", "
     << this->FrequencyWindow[1] << ") (default [0, 0): off)\n";
  os << indent << "Weld Seams: " << (this->WeldSeams ? "on" : "off")
     << " (default on: points within Seam Tolerance are one point)\n";
  os << indent << "Seam Tolerance: " << this->SeamTolerance << " (default "
     << vtkManifoldHarmonicsParallel::SeamTolerance << " of the bounding box diagonal)\n";
}
