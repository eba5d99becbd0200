// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicsBasisFile.h"

#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicsEnums.h"
#include "vtkManifoldHarmonicsNames.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include <sys/stat.h>
#include <unistd.h>

namespace vtkManifoldHarmonicsBasisFile
{
namespace
{
//------------------------------------------------------------------------------
// The harmonics array over a mapped payload: the array frees it with UnmapBasisPayload.
template<typename ArrayT>
vtkSmartPointer<vtkDataArray> MappedArray(void* payload, const spectral::BasisFileHeader& header)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetNumberOfComponents(static_cast<int>(header.Columns));
  array->SetArray(static_cast<typename ArrayT::ValueType*>(payload),
    static_cast<vtkIdType>(header.Rows * header.Columns),
    0,
    ArrayT::VTK_DATA_ARRAY_USER_DEFINED);
  array->SetArrayFreeFunction(spectral::UnmapBasisPayload);
  return array;
}

//------------------------------------------------------------------------------
bool Exists(const std::string& path)
{
  struct stat status;
  return stat(path.c_str(), &status) == 0;
}

//------------------------------------------------------------------------------
// Whether the named file holds the basis asked for; otherwise warns what differed (or why it
// cannot be read) and returns false. Throws BasisFileError (Foreign) for a file that is not a
// basis file: it is not overwritten.
bool Reusable(vtkManifoldHarmonicBasis* self,
  const std::string& path,
  std::uint64_t digest,
  long long numPts,
  int bytes,
  spectral::BasisFileHeader& header)
{
  if (!Exists(path))
  {
    return false;
  }
  try
  {
    header = spectral::ReadBasisFileHeader(path);
  }
  catch (const spectral::BasisFileError& e)
  {
    if (e.Which == spectral::BasisFileError::Kind::Foreign)
    {
      throw;
    }
    vtkWarningWithObjectMacro(
      self, << "Cannot reuse the basis file: " << e.what() << "; recomputing and overwriting it.");
    return false;
  }
  std::string changes;
  if (header.Rows != static_cast<std::uint64_t>(numPts) || header.MeshDigest != digest)
  {
    changes = "the mesh (" + std::to_string(header.Rows) + " points then, " +
      std::to_string(numPts) + " now, or other coordinates or cells)";
  }
  if (header.BytesPerValue != static_cast<std::uint32_t>(bytes))
  {
    changes += std::string(changes.empty() ? "" : ", ") + "BasisPrecision " +
      (header.BytesPerValue == 4 ? "Float -> Double" : "Double -> Float");
  }
  const std::string options = spectral::DescribeOptionChanges(header.Options, OptionsText(self));
  if (!options.empty())
  {
    changes += (changes.empty() ? "" : ", ") + options;
  }
  if (changes.empty())
  {
    return true;
  }
  vtkWarningWithObjectMacro(self,
    << "The basis file '" << path << "' holds another basis (" << changes
    << "): recomputing and overwriting it.");
  return false;
}
} // anonymous namespace

//------------------------------------------------------------------------------
std::string OptionsText(vtkManifoldHarmonicBasis* self)
{
  std::ostringstream text;
  text << std::setprecision(17);
  text << "NumberOfHarmonics=" << self->GetNumberOfHarmonics() << "\n"
       << "MassMatrix=" << self->GetMassMatrix() << "\n"
       << "Laplacian=" << self->GetLaplacian() << "\n"
       << "BoundaryCondition=" << self->GetBoundaryCondition() << "\n"
       << "BandSize=" << self->GetBandSize() << "\n"
       << "Tolerance=" << self->GetTolerance() << "\n"
       << "MinimumComponentSize=" << self->GetMinimumComponentSize() << "\n"
       << "NumberOfNeighbors=" << self->GetNumberOfNeighbors() << "\n"
       << "FrequencyWindow=" << self->GetFrequencyWindow()[0] << " "
       << self->GetFrequencyWindow()[1] << "\n"
       << "WeldSeams=" << self->GetWeldSeams() << "\n"
       << "SeamTolerance=" << self->GetSeamTolerance() << "\n";
  return text.str();
}

//------------------------------------------------------------------------------
std::uint64_t Digest(const spectral::TriangleMesh& mesh)
{
  // Row-major copies: the digest of the coordinates and cells as they are listed.
  const spectral::RowMatrix points = mesh.Vertices;
  const Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> faces = mesh.Faces;
  const Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> tets = mesh.Tets;
  return spectral::MeshDigest(points.data(),
    static_cast<std::size_t>(points.rows()),
    faces.data(),
    static_cast<std::size_t>(faces.rows()),
    tets.data(),
    static_cast<std::size_t>(tets.rows()));
}

//------------------------------------------------------------------------------
std::string TemporaryPath()
{
  static std::atomic<int> counter(0);
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/ManifoldHarmonics-" +
    std::to_string(getpid()) + "-" + std::to_string(counter++) + ".mhb";
}

//------------------------------------------------------------------------------
bool PlanStorage(vtkManifoldHarmonicBasis* self,
  const spectral::BasisOptions& options,
  const spectral::TriangleMesh& mesh,
  long long numPts,
  Plan& plan,
  int& used,
  std::string& reason)
{
  plan = Plan();
  const std::string name = self->GetBasisFileName();
  if (options.EigenvaluesOnly)
  {
    used = vtkManifoldHarmonicBasis::AUTOMATIC;
    reason = "no harmonics are kept (EigenvaluesOnly)";
    if (!name.empty())
    {
      vtkWarningWithObjectMacro(self,
        << "BasisFileName '" << name
        << "' is not written or read: EigenvaluesOnly keeps no harmonics.");
    }
    return true;
  }
  if (!name.empty() && self->GetStorage() == vtkManifoldHarmonicBasis::IN_MEMORY)
  {
    vtkWarningWithObjectMacro(self,
      << "BasisFileName '" << name
      << "' is not written or read: Storage is In Memory. Choose Automatic or File to use it.");
  }
  plan.Digest = Digest(mesh);
  plan.Options = OptionsText(self);
  int requested = self->GetStorage();
  if (!name.empty() && requested == vtkManifoldHarmonicBasis::AUTOMATIC)
  {
    requested = vtkManifoldHarmonicBasis::FILE;
  }
  if (requested == vtkManifoldHarmonicBasis::FILE && !name.empty())
  {
    try
    {
      if (Reusable(self, name, plan.Digest, numPts, options.BytesPerValue, plan.Header))
      {
        plan.Path = name;
        plan.Reuse = true;
        used = vtkManifoldHarmonicBasis::FILE;
        reason = "reused the basis file '" + name + "' (same mesh and options): no solve";
        return true;
      }
    }
    catch (const spectral::BasisFileError& e)
    {
      vtkErrorWithObjectMacro(
        self, << e.what() << ": it is not overwritten; choose another BasisFileName.");
      return false;
    }
  }
  const std::uint64_t n = static_cast<std::uint64_t>(numPts);
  const int m = static_cast<int>(std::min<long long>(options.NumberOfHarmonics, numPts));
  const bool volume = mesh.Tets.rows() > 0;
  const std::uint64_t available =
    options.MemoryLimit > 0 ? options.MemoryLimit : spectral::AvailableMemory();
  // The estimates in the bands the solve's memory plan would choose (smaller ones where the
  // automatic band does not fit: Solver/Memory.h).
  const int band = options.Solver.BandSize;
  const std::uint64_t inMemory =
    spectral::PlanBasisMemory(n, n, m, band, options.BytesPerValue, true, volume, available)
      .Estimate.Total();
  // Into a file, the basis is streamed (never whole in memory) when that needs less memory than
  // computing it in memory and writing it: when m is above the three bands of the blocks in
  // delivery (Memory.h). A frequency window is not streamed.
  const std::uint64_t written =
    spectral::PlanBasisMemory(n, n, m, band, 0, true, volume, available).Estimate.Total();
  // Streamed, with the writer's memory beside the solve (BasisFileWriterBytes), which the
  // solve's share of the limit leaves out (MemoryShare).
  const std::uint64_t writer = spectral::BasisFileWriterBytes(n,
    static_cast<std::uint64_t>(m),
    static_cast<std::uint32_t>(options.BytesPerValue),
    spectral::StreamedBlockColumns);
  const std::uint64_t streaming =
    spectral::PlanStreamedMemory(n, n, m, band, volume, spectral::MemoryShare(available, writer))
      .Estimate.Total() +
    writer;
  const bool streamed =
    !spectral::IsFrequencyWindow(options.LowerFrequency, options.UpperFrequency) &&
    streaming <= written;
  const std::uint64_t inFile = streamed ? streaming : written;
  const std::string path = name.empty() ? TemporaryPath() : name;
  const std::uint64_t fileBytes = spectral::BasisFileDiskBytes(n,
    static_cast<std::uint64_t>(m),
    options.BytesPerValue,
    streamed ? spectral::BasisFileWriting::InBands : spectral::BasisFileWriting::Whole);
  const spectral::BasisStorage asked =
    vtkManifoldHarmonicsEnums::To(vtkManifoldHarmonicsEnums::Storage, requested, "Storage");
  // Checked before the solve: a long solve must not end on a file that cannot be created.
  const std::string directory = spectral::DirectoryOf(path);
  const spectral::StorageChoice choice = spectral::ChooseBasisStorage(asked,
    inMemory,
    inFile,
    available,
    fileBytes,
    spectral::FreeDiskSpace(directory),
    spectral::UnwritableDirectory(directory));
  if (choice.Chosen == spectral::BasisStorage::File)
  {
    plan.Path = path;
    plan.Temporary = name.empty();
    plan.Streamed = streamed;
    plan.WriterBytes = streamed ? writer : 0;
    used = vtkManifoldHarmonicBasis::FILE;
    reason = "the basis is kept " + choice.Reason + ", in '" + path + "', " +
      (streamed ? "streamed into it band by band" : "computed in memory, then written");
    if (requested == vtkManifoldHarmonicBasis::AUTOMATIC)
    {
      vtkWarningWithObjectMacro(self, << "Storage Automatic: " << reason << ".");
    }
    return true;
  }
  if (requested == vtkManifoldHarmonicBasis::FILE)
  {
    vtkErrorWithObjectMacro(self, << choice.Refusal);
    return false;
  }
  // In memory, as asked or chosen; when nothing fits, the solve's memory check refuses with
  // the details and this refusal (DescribeFailure).
  used = vtkManifoldHarmonicBasis::IN_MEMORY;
  reason = choice.Refusal.empty() ? "the basis is kept " + choice.Reason
                                  : "the basis is kept in memory: nothing fits, the solve's "
                                    "memory check decides. " +
      choice.Refusal;
  plan.Refusal = choice.Refusal;
  return true;
}

//------------------------------------------------------------------------------
void NameHarmonics(vtkDataArray* harmonics)
{
  harmonics->SetName(vtkManifoldHarmonicsNames::Harmonics);
  for (int k = 0; k < harmonics->GetNumberOfComponents(); ++k)
  {
    harmonics->SetComponentName(k, ("Phi_" + std::to_string(k)).c_str());
  }
}

//------------------------------------------------------------------------------
void AddSpectrumArrays(vtkDataSet* output,
  const double* eigenvalues,
  int m,
  double backwardError,
  double residual)
{
  vtkNew<vtkDoubleArray> values;
  values->SetName(vtkManifoldHarmonicsNames::Eigenvalues);
  values->SetNumberOfTuples(m);
  std::copy(eigenvalues, eigenvalues + m, values->GetPointer(0));
  output->GetFieldData()->AddArray(values);
  for (const auto& figure :
    { std::make_pair(vtkManifoldHarmonicsNames::BackwardError, backwardError),
      std::make_pair(vtkManifoldHarmonicsNames::Residual, residual) })
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(figure.first);
    array->InsertNextValue(figure.second);
    output->GetFieldData()->AddArray(array);
  }
}

//------------------------------------------------------------------------------
void AddFileArrays(vtkDataSet* output,
  const std::string& path,
  const spectral::BasisFileHeader& header)
{
  void* payload = spectral::MapBasisPayload(path, header);
  vtkSmartPointer<vtkDataArray> harmonics = header.BytesPerValue == 4
    ? MappedArray<vtkFloatArray>(payload, header)
    : MappedArray<vtkDoubleArray>(payload, header);
  NameHarmonics(harmonics);
  output->GetPointData()->AddArray(harmonics);
  vtkNew<vtkDoubleArray> mass;
  mass->SetName(vtkManifoldHarmonicsNames::Mass);
  mass->SetNumberOfTuples(static_cast<vtkIdType>(header.Rows));
  std::copy(header.Mass.begin(), header.Mass.end(), mass->GetPointer(0));
  output->GetPointData()->AddArray(mass);
  AddSpectrumArrays(output,
    header.Eigenvalues.data(),
    static_cast<int>(header.Columns),
    header.BackwardError,
    header.Residual);
}
} // namespace vtkManifoldHarmonicsBasisFile
