// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The file-backed basis of vtkManifoldHarmonicBasis (Storage, BasisFileName;
// vtkManifoldHarmonicsBasisFile.h): with a MemoryLimit that refuses the basis in memory,
// AUTOMATIC streams it into a file whose mapping equals the in-memory basis bit for bit, and the
// transform and spectral filter give the same results from it; a named file is reused without
// solving, and recomputed (with a warning saying what differed) when the mesh or an option
// changed; damaged or foreign files are never used; an abort leaves no file; FILE is refused
// where it is not available.

#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkSpectralFilter.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"
#include "vtkTestUtilities.h"

#include "Spectral/Common/BasisFile.h"
#include "Spectral/Solver/Memory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace
{
using ManifoldHarmonicsTest::Check;
using ManifoldHarmonicsTest::RelativeDifference;

constexpr int Harmonics = 240;

std::string Directory;

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> MakeSphere()
{
  return ManifoldHarmonicsTest::SphereWithHeight(40, 30);
}

//------------------------------------------------------------------------------
// Bands of 5 pairs and m = 240: a streamed basis holds the vectors of three bands and a block
// in delivery of at most 64 harmonics twice (Memory.h, EstimateStreamedMemory), and the writer
// gathers the block once more (BasisFileWriterBytes): 207 columns, fewer than the solver's 240
// when it computes the basis in memory to write it: the filter streams into the file.
constexpr int BandSize = 5;

//------------------------------------------------------------------------------
// A MemoryLimit (MiB) between the estimate of a basis streamed into a file and of the basis in
// memory: AUTOMATIC must then choose a file, IN_MEMORY is refused.
double LimitBetween(vtkIdType n, int bytesPerValue)
{
  // Into a file, with the writer's memory beside the solve.
  const double streamed =
    static_cast<double>(spectral::EstimateStreamedMemory(n, n, Harmonics, BandSize, false).Total() +
      spectral::BasisFileWriterBytes(n, Harmonics, bytesPerValue, spectral::StreamedBlockColumns));
  const double memory = static_cast<double>(
    spectral::EstimateBasisMemory(n, n, Harmonics, BandSize, bytesPerValue, true, false).Total());
  if (!(streamed < memory))
  {
    std::cerr << "ERROR: streaming needs no less memory than the basis in memory" << std::endl;
  }
  return 0.5 * (streamed + memory) / 1048576.0;
}

//------------------------------------------------------------------------------
vtkDataArray* HarmonicsOf(vtkManifoldHarmonicBasis* basis)
{
  return basis->GetPolyDataOutput()->GetPointData()->GetArray(
    vtkManifoldHarmonicBasis::HarmonicsArrayName());
}

vtkDataArray* EigenvaluesOf(vtkManifoldHarmonicBasis* basis)
{
  return basis->GetPolyDataOutput()->GetFieldData()->GetArray(
    vtkManifoldHarmonicBasis::EigenvaluesArrayName());
}

//------------------------------------------------------------------------------
// max |a - b| over every value (1 when the shapes differ or an array is missing).
double MaxDifference(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents())
  {
    return 1.0;
  }
  double worst = 0.0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    worst = std::max(
      worst, std::abs(a->GetVariantValue(i).ToDouble() - b->GetVariantValue(i).ToDouble()));
  }
  return worst;
}

//------------------------------------------------------------------------------
// max over the harmonics of max_i |a_k(i) - s_k b_k(i)|, with s_k = +-1 the sign that matches
// best; `flips` counts the harmonics matched with -1 (1 when the shapes differ).
double MaxDifferenceUpToSigns(vtkDataArray* a, vtkDataArray* b, int& flips)
{
  flips = 0;
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents())
  {
    return 1.0;
  }
  double worst = 0.0;
  for (int k = 0; k < a->GetNumberOfComponents(); ++k)
  {
    double same = 0.0;
    double opposite = 0.0;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      same = std::max(same, std::abs(a->GetComponent(i, k) - b->GetComponent(i, k)));
      opposite = std::max(opposite, std::abs(a->GetComponent(i, k) + b->GetComponent(i, k)));
    }
    flips += opposite < same ? 1 : 0;
    worst = std::max(worst, std::min(same, opposite));
  }
  return worst;
}

//------------------------------------------------------------------------------
// The line of /proc/self/maps of the mapping that holds `address` ("" when none).
std::string MappingOf(const void* address)
{
  std::ifstream maps("/proc/self/maps");
  std::string line;
  const unsigned long long at = reinterpret_cast<unsigned long long>(address);
  while (std::getline(maps, line))
  {
    unsigned long long begin = 0, end = 0;
    char dash = 0;
    std::istringstream fields(line);
    fields >> std::hex >> begin >> dash >> end;
    if (at >= begin && at < end)
    {
      return line;
    }
  }
  return std::string();
}

bool Exists(const std::string& path)
{
  struct stat status;
  return stat(path.c_str(), &status) == 0;
}

ino_t Inode(const std::string& path)
{
  struct stat status;
  return stat(path.c_str(), &status) == 0 ? status.st_ino : 0;
}

//------------------------------------------------------------------------------
// Transform (points and Height) and a low-pass of a basis output.
struct Downstream
{
  vtkNew<vtkManifoldHarmonicTransform> Transform;
  vtkNew<vtkSpectralFilter> Filter;
  explicit Downstream(vtkAlgorithmOutput* basis)
  {
    this->Transform->SetInputConnection(basis);
    this->Transform->GetPointDataArraySelection()->EnableArray("Height");
    this->Filter->SetInputConnection(this->Transform->GetOutputPort());
    this->Filter->Update();
  }
  double DifferenceTo(Downstream& other)
  {
    vtkPointSet* fa = vtkPointSet::SafeDownCast(this->Filter->GetOutput());
    vtkPointSet* fb = vtkPointSet::SafeDownCast(other.Filter->GetOutput());
    if (!fa || !fb || !fa->GetPoints() || !fb->GetPoints())
    {
      return 1.0;
    }
    // The filtered signals: the coefficients follow each harmonic's sign, they do not.
    return std::max(RelativeDifference(fa->GetPoints()->GetData(), fb->GetPoints()->GetData()),
      RelativeDifference(fa->GetPointData()->GetArray("Height_Filtered"),
        fb->GetPointData()->GetArray("Height_Filtered")));
  }
};

//------------------------------------------------------------------------------
// AUTOMATIC with a limit that refuses memory: a file, equal to the basis in memory.
bool FileEqualsMemory(int precision)
{
  const bool floats = precision == vtkManifoldHarmonicBasis::FLOAT;
  const std::string label = floats ? "float: " : "double: ";
  // A bumpy ellipsoid with three different axes: no repeated eigenvalue (a sphere's clusters may
  // come in another basis of their eigenspace) and no mirror symmetry (an odd harmonic's
  // largest entries tie, and round-off picks its sign).
  auto mesh = MakeSphere();
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    const double bump = 1.0 + 0.03 * std::sin(7.0 * i);
    mesh->GetPoints()->SetPoint(i, bump * p[0], 1.3 * bump * p[1], 0.7 * bump * p[2]);
  }
  const double limit = LimitBetween(mesh->GetNumberOfPoints(), floats ? 4 : 8);

  vtkNew<vtkManifoldHarmonicBasis> memory;
  memory->SetInputData(mesh);
  memory->SetNumberOfHarmonics(Harmonics);
  memory->SetBasisPrecision(precision);
  memory->SetBandSize(BandSize);
  Downstream fromMemory(memory->GetOutputPort());
  bool ok = Check(memory->GetStorageUsed() == vtkManifoldHarmonicBasis::IN_MEMORY,
    label + "without a limit the basis stays in memory: " + memory->GetStorageReason());

  // IN_MEMORY under the limit is refused (the limit is small enough).
  {
    vtkNew<vtkManifoldHarmonicBasis> refused;
    refused->SetInputData(mesh);
    refused->SetNumberOfHarmonics(Harmonics);
    refused->SetBasisPrecision(precision);
    refused->SetBandSize(BandSize);
    refused->SetMemoryLimit(limit);
    refused->SetStorageToInMemory();
    const ManifoldHarmonicsTest::Messages errors(refused);
    refused->Update();
    ok &= Check(errors->GetError() &&
        errors->GetErrorMessage().find("Not enough memory") != std::string::npos,
      label + "IN_MEMORY under the limit is refused");
  }
  // A file under a limit that not even the stream into it fits: the stream's blocks in delivery
  // are doubles, so a float basis would not help and is not offered; the memory the message
  // counts available is the limit less the writer's share, and it says so.
  {
    vtkNew<vtkManifoldHarmonicBasis> refused;
    refused->SetInputData(mesh);
    refused->SetNumberOfHarmonics(Harmonics);
    refused->SetBasisPrecision(precision);
    refused->SetBandSize(BandSize);
    refused->SetMemoryLimit(1.0);
    refused->SetStorageToFile();
    const ManifoldHarmonicsTest::Messages errors(refused);
    refused->Update();
    const std::string& message = errors->GetErrorMessage();
    ok &= Check(errors->GetError() && message.find("streamed harmonics") != std::string::npos &&
        message.find("harmonics in delivery") != std::string::npos &&
        message.find("(MemoryLimit 1.0 MiB, less ") != std::string::npos &&
        message.find("for the basis file's writer)") != std::string::npos &&
        message.find("BasisPrecision") == std::string::npos,
      label + "a stream into a file that does not fit is refused as a stream: " + message);
  }

  vtkNew<vtkManifoldHarmonicBasis> file;
  file->SetInputData(mesh);
  file->SetNumberOfHarmonics(Harmonics);
  file->SetBasisPrecision(precision);
  file->SetBandSize(BandSize);
  file->SetMemoryLimit(limit);
  const ManifoldHarmonicsTest::Messages messages(file);
  Downstream fromFile(file->GetOutputPort());
  ok &= Check(!messages->GetError(), label + "no error: " + messages->GetErrorMessage());
  ok &= Check(file->GetStorageUsed() == vtkManifoldHarmonicBasis::FILE &&
      messages->GetWarningMessage().find("Storage Automatic: the basis is kept in a file") !=
        std::string::npos &&
      std::string(file->GetStorageReason()).find("streamed into it band by band") !=
        std::string::npos,
    label + "AUTOMATIC chose a file, streamed, and said so: " + file->GetStorageReason());
  vtkDataArray* mapped = HarmonicsOf(file);
  const std::string mapping = mapped ? MappingOf(mapped->GetVoidPointer(0)) : std::string();
  std::cout << label << "mapping " << mapping << std::endl;
  ok &= Check(mapping.find(" r--s ") != std::string::npos &&
      mapping.find("/ManifoldHarmonics-") != std::string::npos &&
      mapping.find("(deleted)") != std::string::npos,
    label + "the harmonics are a read-only shared mapping of the temporary file, unlinked");
  ok &= Check(floats ? vtkFloatArray::SafeDownCast(mapped) != nullptr
                     : vtkDoubleArray::SafeDownCast(mapped) != nullptr,
    label + "the mapped array has the basis precision");
  ok &= Check(mapped &&
      std::string(mapped->GetComponentName(Harmonics - 1)) ==
        "Phi_" + std::to_string(Harmonics - 1),
    label + "components named");
  int flips = 0;
  const double harmonics = MaxDifferenceUpToSigns(mapped, HarmonicsOf(memory), flips);
  const double eigenvalues = RelativeDifference(EigenvaluesOf(file), EigenvaluesOf(memory));
  const double mass = MaxDifference(
    file->GetPolyDataOutput()->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName()),
    memory->GetPolyDataOutput()->GetPointData()->GetArray(
      vtkManifoldHarmonicBasis::MassArrayName()));
  const double downstream = fromFile.DifferenceTo(fromMemory);
  std::cout << label << "file vs memory: harmonics " << harmonics << " (" << flips
            << " of opposite sign), eigenvalues " << eigenvalues << ", mass " << mass
            << ", filtered points and signal " << downstream << std::endl;
  // The streamed solve equals the one in memory to round-off (Testing/Core/TestStreaming.cxx),
  // compared up to signs all the same (NormalizeSigns decides by the largest entries, which
  // round-off decides when they nearly tie); a float basis rounds both to float, which may then
  // differ by one unit in the last place.
  // The two are the same computation (the band solver makes the same pairs final whether it
  // keeps their vectors or streams them), and its rounding no longer follows where the heap puts
  // its buffers (SumOfEntries, Common/Mesh.h): measured equal, bit for bit; before, 4.4e-11 on
  // the harmonics (entries of about 0.5).
  ok &= Check(harmonics <= (floats ? 1e-7 : 1e-12) && eigenvalues <= 1e-12 && mass == 0.0,
    label + "harmonics (up to sign), eigenvalues and mass equal the in-memory basis");
  ok &= Check(downstream <= 1e-12, label + "transform and filter give the same results");
  return ok;
}

//------------------------------------------------------------------------------
// A basis computed into a named file.
vtkSmartPointer<vtkManifoldHarmonicBasis> NamedBasis(vtkPolyData* mesh,
  const std::string& path,
  int harmonics = Harmonics)
{
  auto basis = vtkSmartPointer<vtkManifoldHarmonicBasis>::New();
  basis->SetInputData(mesh);
  basis->SetNumberOfHarmonics(harmonics);
  basis->SetBasisFileName(path.c_str());
  return basis;
}

//------------------------------------------------------------------------------
bool Reuse()
{
  const std::string path = Directory + "/TestBasisFileReuse.mhb";
  std::remove(path.c_str());
  auto mesh = MakeSphere();
  auto first = NamedBasis(mesh, path);
  first->Update();
  bool ok = Check(Exists(path) && !first->GetBasisReused() &&
      first->GetStorageUsed() == vtkManifoldHarmonicBasis::FILE,
    "the named file is written and kept");
  const ino_t inode = Inode(path);

  auto second = NamedBasis(mesh, path);
  const ManifoldHarmonicsTest::Messages messages(second);
  second->Update();
  ok &= Check(second->GetBasisReused() && Inode(path) == inode && !messages->GetWarning(),
    std::string("the same mesh and options reuse the file without solving or rewriting it: ") +
      second->GetStorageReason());
  ok &= Check(MaxDifference(HarmonicsOf(second), HarmonicsOf(first)) == 0.0 &&
      MaxDifference(EigenvaluesOf(second), EigenvaluesOf(first)) == 0.0,
    "the reused basis is the computed one");

  // Another option: recomputed, with a warning naming it.
  auto fewer = NamedBasis(mesh, path, Harmonics - 10);
  const ManifoldHarmonicsTest::Messages fewerMessages(fewer);
  fewer->Update();
  const std::string warning = fewerMessages->GetWarningMessage();
  ok &= Check(!fewer->GetBasisReused() && Inode(path) != inode &&
      warning.find("NumberOfHarmonics " + std::to_string(Harmonics) + " -> " +
        std::to_string(Harmonics - 10)) != std::string::npos &&
      HarmonicsOf(fewer)->GetNumberOfComponents() == Harmonics - 10,
    "another NumberOfHarmonics recomputes and overwrites, naming the change: " + warning);

  // Another mesh (one coordinate moved): recomputed.
  auto moved = vtkSmartPointer<vtkPolyData>::New();
  moved->DeepCopy(mesh);
  double p[3];
  moved->GetPoint(5, p);
  moved->GetPoints()->SetPoint(5, p[0] * 1.01, p[1], p[2]);
  auto other = NamedBasis(moved, path, Harmonics - 10);
  const ManifoldHarmonicsTest::Messages otherMessages(other);
  other->Update();
  ok &= Check(!other->GetBasisReused() &&
      otherMessages->GetWarningMessage().find("the mesh") != std::string::npos,
    "a moved point recomputes: " + otherMessages->GetWarningMessage());
  // And the file now holds the moved mesh's basis: reused for it.
  auto again = NamedBasis(moved, path, Harmonics - 10);
  again->Update();
  ok &=
    Check(again->GetBasisReused() && MaxDifference(HarmonicsOf(again), HarmonicsOf(other)) == 0.0,
      "the overwritten file is reused for the new mesh");

  // Where the name is not used, a warning says so: Storage In Memory, EigenvaluesOnly.
  auto inMemory = NamedBasis(moved, path, Harmonics - 10);
  inMemory->SetStorageToInMemory();
  const ManifoldHarmonicsTest::Messages inMemoryMessages(inMemory);
  inMemory->Update();
  ok &= Check(!inMemory->GetBasisReused() &&
      inMemory->GetStorageUsed() == vtkManifoldHarmonicBasis::IN_MEMORY &&
      inMemoryMessages->GetWarningMessage().find("Storage is In Memory") != std::string::npos,
    "a BasisFileName with Storage In Memory is not used, with a warning: " +
      inMemoryMessages->GetWarningMessage());
  auto spectrum = NamedBasis(moved, path, Harmonics - 10);
  spectrum->EigenvaluesOnlyOn();
  const ManifoldHarmonicsTest::Messages spectrumMessages(spectrum);
  spectrum->Update();
  ok &= Check(spectrumMessages->GetWarningMessage().find("EigenvaluesOnly keeps no harmonics") !=
      std::string::npos,
    "a BasisFileName with EigenvaluesOnly is not used, with a warning: " +
      spectrumMessages->GetWarningMessage());

  // A directory under the name: an error that says so.
  std::remove(path.c_str());
  const std::string directory = Directory + "/TestBasisFileDirectory.mhb";
  mkdir(directory.c_str(), 0700);
  auto toDirectory = NamedBasis(moved, directory, Harmonics - 10);
  const ManifoldHarmonicsTest::Messages directoryMessages(toDirectory);
  toDirectory->Update();
  ok &= Check(directoryMessages->GetErrorMessage().find("is a directory") != std::string::npos &&
      toDirectory->GetStorageUsed() == vtkManifoldHarmonicBasis::AUTOMATIC,
    "a directory as BasisFileName: an error naming it, and no storage reported: " +
      directoryMessages->GetErrorMessage());
  rmdir(directory.c_str());
  return ok;
}

//------------------------------------------------------------------------------
bool DamagedAndForeignFiles()
{
  const std::string path = Directory + "/TestBasisFileDamaged.mhb";
  auto mesh = MakeSphere();
  vtkNew<vtkManifoldHarmonicBasis> reference;
  reference->SetInputData(mesh);
  reference->SetNumberOfHarmonics(Harmonics);
  reference->Update();
  bool ok = true;

  // A foreign file: an error, and the file is left as it was.
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << "not a basis, a user's precious notes\n";
  }
  auto foreign = NamedBasis(mesh, path);
  {
    const ManifoldHarmonicsTest::Messages messages(foreign);
    foreign->Update();
    std::ifstream in(path);
    std::string text;
    std::getline(in, text);
    ok &= Check(messages->GetError() &&
        messages->GetErrorMessage().find("not a manifold harmonics basis file") !=
          std::string::npos &&
        text == "not a basis, a user's precious notes" && !HarmonicsOf(foreign),
      "a foreign file is an error and is not overwritten: " + messages->GetErrorMessage());
  }

  // A truncated basis file, then one of another version: recomputed with a warning, right.
  for (const std::string damage : { "truncated", "version" })
  {
    std::remove(path.c_str());
    NamedBasis(mesh, path)->Update();
    if (damage == "truncated")
    {
      struct stat status;
      stat(path.c_str(), &status);
      ok &= Check(truncate(path.c_str(), status.st_size / 2) == 0, "truncate");
    }
    else
    {
      std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
      file.seekp(8);
      file.write("\x09\0\0\0", 4);
    }
    auto damaged = NamedBasis(mesh, path);
    const ManifoldHarmonicsTest::Messages messages(damaged);
    damaged->Update();
    const std::string warning = messages->GetWarningMessage();
    ok &= Check(!messages->GetError() && !damaged->GetBasisReused() &&
        warning.find(damage == "truncated" ? "is truncated" : "format version 9") !=
          std::string::npos &&
        MaxDifference(HarmonicsOf(damaged), HarmonicsOf(reference)) == 0.0,
      "a " + damage + " basis file is recomputed with a warning: " + warning);
  }
  std::remove(path.c_str());
  return ok;
}

//------------------------------------------------------------------------------
// Sets AbortExecute once progress passes a threshold.
class AbortAt : public vtkCommand
{
public:
  static AbortAt* New() { return new AbortAt; }
  void Execute(vtkObject* caller, unsigned long, void* callData) override
  {
    if (*static_cast<double*>(callData) >= this->Threshold)
    {
      vtkAlgorithm::SafeDownCast(caller)->AbortExecuteOn();
    }
  }
  double Threshold = 0.5;
};

bool AbortLeavesNoFile()
{
  const std::string path = Directory + "/TestBasisFileAbort.mhb";
  std::remove(path.c_str());
  auto mesh = MakeSphere();
  auto basis = NamedBasis(mesh, path);
  vtkNew<AbortAt> abort;
  const unsigned long tag = basis->AddObserver(vtkCommand::ProgressEvent, abort);
  basis->Update();
  bool ok = Check(!Exists(path) && !Exists(path + ".partial") && !HarmonicsOf(basis),
    "an abort in the middle leaves no file and no partial file");
  basis->RemoveObserver(tag);
  basis->Modified();
  basis->Update();
  ok &= Check(Exists(path) && !basis->GetBasisReused() && HarmonicsOf(basis),
    "the next run computes the file (nothing to reuse)");
  std::remove(path.c_str());
  return ok;
}

//------------------------------------------------------------------------------
// A frequency window is not streamed: computed in memory, then written; the same basis.
bool WindowWritten()
{
  auto mesh = MakeSphere();
  vtkNew<vtkManifoldHarmonicBasis> memory;
  memory->SetInputData(mesh);
  memory->SetFrequencyWindow(2.0, 5.0);
  memory->Update();
  vtkNew<vtkManifoldHarmonicBasis> file;
  file->SetInputData(mesh);
  file->SetFrequencyWindow(2.0, 5.0);
  file->SetStorageToFile();
  const ManifoldHarmonicsTest::Messages messages(file);
  file->Update();
  const std::string reason = file->GetStorageReason();
  const int m = HarmonicsOf(memory) ? HarmonicsOf(memory)->GetNumberOfComponents() : 0;
  return Check(!messages->GetError() && m > 0 &&
      reason.find("computed in memory, then written") != std::string::npos &&
      MappingOf(HarmonicsOf(file)->GetVoidPointer(0)).find(" r--s ") != std::string::npos &&
      MaxDifference(EigenvaluesOf(file), EigenvaluesOf(memory)) == 0.0,
    "a window's basis is written into the file after its solve: " + reason + " (" +
      std::to_string(m) + " harmonics)");
}

//------------------------------------------------------------------------------
// A basis file that cannot be created (a missing directory, a file for a directory) is refused
// before the solve, naming why: the error came after the whole solve ("cannot create
// ...partial"), hours on a large mesh. Storage Automatic with a memory limit that needs a file
// says a file would not do either, and why.
bool UnwritableDirectory()
{
  auto mesh = MakeSphere();
  bool ok = true;
  const std::string file = Directory + "/TestBasisFilePlain.txt";
  std::ofstream(file) << "a file, not a directory";
  for (const std::string& path :
    { Directory + "/no-such-directory/basis.mhb", file + "/basis.mhb" })
  {
    auto basis = NamedBasis(mesh, path);
    basis->SetStorageToFile();
    int reports = 0;
    vtkNew<vtkCallbackCommand> progress;
    progress->SetClientData(&reports);
    progress->SetCallback(
      [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
    basis->AddObserver(vtkCommand::ProgressEvent, progress);
    const ManifoldHarmonicsTest::Messages messages(basis);
    basis->Update();
    const std::string error = messages->GetErrorMessage();
    ok &= Check(messages->GetError() && error.find("cannot be created") != std::string::npos &&
        (error.find("does not exist") != std::string::npos ||
          error.find("is not a directory") != std::string::npos) &&
        reports <= 2 && !HarmonicsOf(basis),
      "Storage File in '" + path + "': refused before the solve (" + std::to_string(reports) +
        " progress reports), naming why: " + error);
    // A temporary file (no BasisFileName) in TMPDIR, which is that directory.
    const std::string directory = path.substr(0, path.find_last_of('/'));
    setenv("TMPDIR", directory.c_str(), 1);
    vtkNew<vtkManifoldHarmonicBasis> automatic;
    automatic->SetInputData(mesh);
    automatic->SetNumberOfHarmonics(Harmonics);
    automatic->SetMemoryLimit(LimitBetween(mesh->GetNumberOfPoints(), 8));
    automatic->SetBandSize(BandSize);
    const ManifoldHarmonicsTest::Messages automaticMessages(automatic);
    automatic->Update();
    const std::string refusal = automaticMessages->GetErrorMessage();
    ok &= Check(automaticMessages->GetError() &&
        refusal.find("A file would not do either") != std::string::npos &&
        refusal.find(directory) != std::string::npos,
      "Storage Automatic under the limit, TMPDIR '" + directory +
        "': the memory error says why no file: " + refusal);
  }
  unsetenv("TMPDIR");
  std::remove(file.c_str());
  return ok;
}

//------------------------------------------------------------------------------
bool RefusedWithSlepc()
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(MakeSphere());
  basis->SetNumberOfHarmonics(10);
  basis->SetSolverToSlepc();
  basis->SetStorageToFile();
  const ManifoldHarmonicsTest::Messages messages(basis);
  basis->Update();
  return Check(messages->GetError() &&
      messages->GetErrorMessage().find("serial runs of the Built-in solver only") !=
        std::string::npos,
    "Storage FILE with the SLEPc solver is refused: " + messages->GetErrorMessage());
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestBasisFile(int argc, char* argv[])
{
  char* temporary =
    vtkTestUtilities::GetArgOrEnvOrDefault("-T", argc, argv, "VTK_TEMP_DIR", "Testing/Temporary");
  Directory = temporary;
  delete[] temporary;
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "FileEqualsMemory", [] { return FileEqualsMemory(vtkManifoldHarmonicBasis::DOUBLE); } },
      { "FloatFileEqualsMemory", [] { return FileEqualsMemory(vtkManifoldHarmonicBasis::FLOAT); } },
      { "Reuse", Reuse },
      { "DamagedAndForeignFiles", DamagedAndForeignFiles },
      { "AbortLeavesNoFile", AbortLeavesNoFile },
      { "WindowWritten", WindowWritten },
      { "RefusedWithSlepc", RefusedWithSlepc },
      { "UnwritableDirectory", UnwritableDirectory },
    });
}
