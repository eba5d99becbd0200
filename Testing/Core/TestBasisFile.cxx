// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The basis file (Filters/Spectral/Common/BasisFile.h): round trips through the writer, the
// checked reader and the read-only mapping; damaged and foreign files refused with their fault;
// a writer that is not committed leaves no file; the choice between memory and a file.
#include "Checks.h"
#include "Common/BasisFile.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace spectral;
using namespace spectral::testing;

namespace
{
//------------------------------------------------------------------------------
// A fresh path in the temporary directory.
std::string TempPath(const std::string& name)
{
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/TestBasisFile-" + std::to_string(getpid()) +
    "-" + name;
}

bool Exists(const std::string& path)
{
  struct stat status;
  return stat(path.c_str(), &status) == 0;
}

//------------------------------------------------------------------------------
// A header and a column-major n x m block of distinct values; rows 0..n-2 of the block go to
// output rows 1..n-1 (row 0 has no source: it must read as zeros).
struct Sample
{
  BasisFileHeader Header;
  std::vector<double> Block;
  std::vector<int> Sources;
  std::vector<std::int64_t> Targets;
};

Sample MakeSample(std::uint64_t n, std::uint64_t m, std::uint32_t bytes)
{
  Sample s;
  s.Header.Rows = n;
  s.Header.Columns = m;
  s.Header.BytesPerValue = bytes;
  s.Header.MeshDigest = 0x1234;
  s.Header.Options = "NumberOfHarmonics=" + std::to_string(m) + "\nLaplacian=Cotangent\n";
  for (std::uint64_t k = 0; k < m; ++k)
  {
    s.Header.Eigenvalues.push_back(0.5 * k);
  }
  s.Header.Mass.assign(n, 0.25);
  s.Block.resize(n * m);
  for (std::size_t i = 0; i < s.Block.size(); ++i)
  {
    s.Block[i] = 1.0 / (1.0 + i) + 1e-3 * i;
  }
  for (std::uint64_t r = 0; r + 1 < n; ++r)
  {
    s.Sources.push_back(static_cast<int>(r));
    s.Targets.push_back(static_cast<std::int64_t>(r + 1));
  }
  return s;
}

// Writes the sample in bands of `band` columns and commits it (tiles of `tileBytes`). The first
// band is written twice, other values first, as a solve that restarts does. Whole: all the
// columns in one call, which `band` then does not split.
void WriteSample(const std::string& path,
  const Sample& s,
  std::uint64_t band,
  std::uint64_t tileBytes = BasisFileTileBytes,
  BasisFileWriting writing = BasisFileWriting::InBands)
{
  BasisFileWriter writer(path, s.Header, writing, tileBytes);
  Check(!Exists(writer.PartialPath() + ".tiles"), "the scratch has no name");
  const std::uint64_t n = s.Header.Rows;
  const std::uint64_t m = s.Header.Columns;
  if (writing == BasisFileWriting::Whole)
  {
    band = m;
  }
  const std::vector<double> other(s.Block.size(), -7.0);
  if (writing == BasisFileWriting::InBands)
  {
    writer.WriteColumns(0, std::min(band, m), other.data(), n, s.Sources, s.Targets);
  }
  for (std::uint64_t c = 0; c < m; c += band)
  {
    const std::uint64_t count = std::min(band, m - c);
    writer.WriteColumns(c, count, s.Block.data() + c * n, n, s.Sources, s.Targets);
  }
  BasisFileHeader final = s.Header;
  final.Warnings = { "a warning of the solve" };
  final.Residual = 3e-12;
  writer.Commit(final);
}

// Whether the file system of `path` has files without a name (O_TMPFILE).
bool UnnamedFiles(const std::string& path)
{
  std::string directory = path.substr(0, path.find_last_of('/'));
  const int descriptor = open(directory.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (descriptor < 0)
  {
    return false;
  }
  close(descriptor);
  return true;
}

// The number of open file descriptors of the process.
int OpenDescriptors()
{
  int count = 0;
  if (DIR* directory = opendir("/proc/self/fd"))
  {
    while (readdir(directory))
    {
      ++count;
    }
    closedir(directory);
  }
  return count;
}

//------------------------------------------------------------------------------
void RoundTrip()
{
  // Tiles: one for the whole file, 3 rows (the last has 1), 1 row; in bands and whole; doubles
  // and floats.
  const int descriptors = OpenDescriptors();
  for (int t = 0; t < 12; ++t)
  {
    const std::uint64_t tileRows = std::vector<std::uint64_t>{ 0, 3, 1 }[t / 4];
    const BasisFileWriting writing =
      t % 4 < 2 ? BasisFileWriting::InBands : BasisFileWriting::Whole;
    const std::uint32_t bytes = t % 2 == 0 ? 8u : 4u;
    const std::string path = TempPath("roundtrip.mhb");
    const Sample s = MakeSample(37, 11, bytes);
    WriteSample(path, s, 4, tileRows == 0 ? BasisFileTileBytes : tileRows * 11 * bytes, writing);
    Check(Exists(path) && !Exists(path + ".partial"), "committed: the file, no partial file");
    struct stat status;
    stat(path.c_str(), &status);
    const std::uint64_t payloadBytes = 37 * 11 * bytes;
    const std::uint64_t disk = BasisFileDiskBytes(37, 11, bytes, writing);
    Check(static_cast<std::uint64_t>(status.st_size) +
          (writing == BasisFileWriting::InBands ? payloadBytes : 0) <=
        disk,
      "BasisFileDiskBytes (" + std::to_string(disk) + ") covers the file (" +
        std::to_string(status.st_size) + " bytes) and, in bands, its scratch");
    const BasisFileHeader h = ReadBasisFileHeader(path);
    Check(h.Rows == 37 && h.Columns == 11 && h.BytesPerValue == bytes && h.MeshDigest == 0x1234,
      "n, m, precision and digest read back");
    Check(h.Options == s.Header.Options && h.Eigenvalues == s.Header.Eigenvalues &&
        h.Mass == s.Header.Mass && h.Residual == 3e-12 && h.Warnings.size() == 1,
      "options, eigenvalues, mass, figures and warnings read back");
    Check(h.PayloadOffset % static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE)) == 0,
      "the payload is page-aligned");
    void* payload = MapBasisPayload(path, h);
    double worst = 0.0;
    bool zeroRow = true;
    for (std::uint64_t i = 0; i < 37; ++i)
    {
      for (std::uint64_t k = 0; k < 11; ++k)
      {
        const double value = bytes == 8 ? static_cast<double*>(payload)[i * 11 + k]
                                        : static_cast<float*>(payload)[i * 11 + k];
        if (i == 0)
        {
          zeroRow = zeroRow && value == 0.0;
          continue;
        }
        const double expected =
          bytes == 8 ? s.Block[k * 37 + (i - 1)] : static_cast<float>(s.Block[k * 37 + (i - 1)]);
        worst = std::max(worst, std::abs(value - expected));
      }
    }
    CheckBelow(worst,
      0.0,
      "row-major payload equals the bands, bit for bit (tiles of " + std::to_string(tileRows) +
        " rows, 0: one tile)");
    Check(zeroRow, "a row no source reaches reads as zeros");
    UnmapBasisPayload(payload);
    std::remove(path.c_str());
  }
  Check(OpenDescriptors() == descriptors, "no file descriptor left open");
}

//------------------------------------------------------------------------------
// Expects `write` to throw `Error`.
template<typename Error, typename Write>
void ExpectThrows(Write write, const std::string& what)
{
  try
  {
    write();
    Check(false, what + ": no exception");
  }
  catch (const Error& error)
  {
    Check(true, what + ": " + error.what());
  }
}

//------------------------------------------------------------------------------
void InvalidWritesRefused()
{
  const std::string path = TempPath("invalid.mhb");
  const Sample s = MakeSample(20, 6, 8);
  const int descriptors = OpenDescriptors();
  {
    BasisFileWriter writer(path, s.Header);
    std::vector<std::int64_t> far = s.Targets;
    far.back() = 20;
    ExpectThrows<std::out_of_range>([&]()
      { writer.WriteColumns(0, 2, s.Block.data(), 20, s.Sources, far); },
      "a target row beyond n");
    std::vector<int> missing = s.Sources;
    missing.front() = 20;
    ExpectThrows<std::out_of_range>([&]()
      { writer.WriteColumns(0, 2, s.Block.data(), 20, missing, s.Targets); },
      "a source row beyond the block's rows");
    std::vector<int> shorter(s.Sources.begin(), s.Sources.end() - 1);
    ExpectThrows<std::invalid_argument>([&]()
      { writer.WriteColumns(0, 2, s.Block.data(), 20, shorter, s.Targets); },
      "fewer sources than targets");
    ExpectThrows<std::out_of_range>([&]()
      { writer.WriteColumns(5, 2, s.Block.data(), 20, s.Sources, s.Targets); },
      "columns beyond m");
  }
  {
    BasisFileWriter whole(path, s.Header, BasisFileWriting::Whole);
    ExpectThrows<std::invalid_argument>([&]()
      { whole.WriteColumns(0, 3, s.Block.data(), 20, s.Sources, s.Targets); },
      "part of the columns to a Whole writer");
  }
  BasisFileHeader odd = s.Header;
  odd.BytesPerValue = 2;
  ExpectThrows<std::invalid_argument>(
    [&]() { BasisFileWriter writer(path, odd); }, "values of 2 bytes");
  Check(!Exists(path) && !Exists(path + ".partial") && OpenDescriptors() == descriptors,
    "refused writes leave no file and no open descriptor");
}

//------------------------------------------------------------------------------
// Expects ReadBasisFileHeader to throw `kind`; prints the message.
void ExpectRefused(const std::string& path, BasisFileError::Kind kind, const std::string& what)
{
  try
  {
    ReadBasisFileHeader(path);
    Check(false, what + ": accepted");
  }
  catch (const BasisFileError& e)
  {
    Check(e.Which == kind, what + ": " + e.what());
  }
}

void Patch(const std::string& path, long offset, const std::string& bytes)
{
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekp(offset);
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void DamagedAndForeignFiles()
{
  const std::string path = TempPath("damaged.mhb");
  const Sample s = MakeSample(300, 40, 8);
  const auto fresh = [&]() { WriteSample(path, s, 16); };

  fresh();
  Check(
    truncate(path.c_str(), static_cast<off_t>(ReadBasisFileHeader(path).PayloadOffset + 100)) == 0,
    "truncated the payload");
  ExpectRefused(path, BasisFileError::Kind::Unusable, "a truncated payload");
  Check(truncate(path.c_str(), 50) == 0, "truncated into the header");
  ExpectRefused(path, BasisFileError::Kind::Unusable, "a file cut in its header");

  fresh();
  Patch(path, 8, std::string("\x02\0\0\0", 4));
  ExpectRefused(path, BasisFileError::Kind::Unusable, "another version");

  fresh();
  const std::uint64_t m = 41; // n m no longer matches the file's size
  Patch(path, 24, std::string(reinterpret_cast<const char*>(&m), 8));
  ExpectRefused(path, BasisFileError::Kind::Unusable, "m inconsistent with the file's size");

  fresh();
  Patch(path, 100, "x"); // inside the options text
  ExpectRefused(path, BasisFileError::Kind::Unusable, "a damaged header");

  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    std::mt19937 random(7);
    for (int i = 0; i < 100000; ++i)
    {
      file.put(static_cast<char>(random()));
    }
  }
  ExpectRefused(path, BasisFileError::Kind::Foreign, "random bytes");
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file << "MHB";
  }
  ExpectRefused(path, BasisFileError::Kind::Foreign, "a three-byte file");
  std::remove(path.c_str());
  ExpectRefused(path, BasisFileError::Kind::Io, "a missing file");
  // A directory: named so, not 'too short' (its size is the directory's).
  Check(mkdir(path.c_str(), 0700) == 0, "made a directory under the name");
  try
  {
    ReadBasisFileHeader(path);
    Check(false, "a directory: accepted");
  }
  catch (const BasisFileError& e)
  {
    Check(e.Which == BasisFileError::Kind::Foreign &&
        std::string(e.what()).find("is a directory") != std::string::npos,
      std::string("a directory: ") + e.what());
  }
  rmdir(path.c_str());
}

//------------------------------------------------------------------------------
void UncommittedLeavesNothing()
{
  const std::string path = TempPath("aborted.mhb");
  const Sample s = MakeSample(50, 10, 8);
  WriteSample(path, s, 10); // an older complete file under the name
  const BasisFileHeader before = ReadBasisFileHeader(path);
  {
    BasisFileWriter writer(path, s.Header);
    writer.WriteColumns(0, 5, s.Block.data(), 50, s.Sources, s.Targets);
    Check(!UnnamedFiles(path) || !Exists(writer.PartialPath()),
      "while written the file has no name (where the file system allows)");
    // Destroyed without Commit: an abort or an error of the solve.
  }
  Check(!Exists(path + ".partial"), "an uncommitted writer removes its partial file");
  Check(ReadBasisFileHeader(path).Options == before.Options,
    "the complete file under the name is untouched until a commit replaces it");
  std::remove(path.c_str());
}

//------------------------------------------------------------------------------
// The commit reports its progress tile by tile and stops where it is cancelled, leaving the file
// uncommitted: the complete file already under the name stays, no partial file is left.
void CommitProgressAndCancel()
{
  const std::string path = TempPath("commit.mhb");
  const Sample s = MakeSample(50, 10, 8);
  const std::uint64_t tileBytes = 7 * 10 * 8; // tiles of 7 rows: 8 tiles
  {
    BasisFileWriter writer(path, s.Header, BasisFileWriting::InBands, tileBytes);
    writer.WriteColumns(0, 10, s.Block.data(), 50, s.Sources, s.Targets);
    std::vector<double> reports;
    Monitor monitor;
    monitor.Progress = [&](double f) { reports.push_back(f); };
    writer.Commit(s.Header, monitor);
    Check(reports.size() >= 8 && reports.front() == 0.0 && reports.back() == 1.0 &&
        std::is_sorted(reports.begin(), reports.end()),
      "the commit reports from 0 to 1, tile by tile (" + std::to_string(reports.size()) +
        " reports)");
  }
  const BasisFileHeader before = ReadBasisFileHeader(path);
  Sample other = MakeSample(50, 10, 8);
  other.Header.Options += "BandSize=7\n";
  int reports = 0;
  bool cancelled = false;
  {
    BasisFileWriter writer(path, other.Header, BasisFileWriting::InBands, tileBytes);
    writer.WriteColumns(0, 10, other.Block.data(), 50, other.Sources, other.Targets);
    Monitor monitor;
    monitor.Progress = [&](double) { ++reports; };
    monitor.Cancelled = [&]() { return reports >= 3; };
    try
    {
      writer.Commit(other.Header, monitor);
    }
    catch (const Cancelled&)
    {
      cancelled = true;
    }
  }
  Check(cancelled && reports == 3, "a cancelled commit stops at the next tile");
  Check(ReadBasisFileHeader(path).Options == before.Options && !Exists(path + ".partial"),
    "and leaves the file under the name as it was, and no partial file");
  std::remove(path.c_str());
}

//------------------------------------------------------------------------------
void KilledLeavesNothing()
{
  // A process killed while it writes (out of memory: no destructor runs) leaves neither the
  // file nor a partial file, where the file system has O_TMPFILE.
  const std::string path = TempPath("killed.mhb");
  const Sample s = MakeSample(300, 40, 8);
  const pid_t child = fork();
  if (child == 0)
  {
    BasisFileWriter writer(path, s.Header);
    writer.WriteColumns(0, 20, s.Block.data(), 300, s.Sources, s.Targets);
    _exit(0); // no destructor, as SIGKILL
  }
  int status = 0;
  waitpid(child, &status, 0);
  Check(WIFEXITED(status) && WEXITSTATUS(status) == 0, "the writing process ended");
  if (!UnnamedFiles(path))
  {
    std::printf(
      "    (this file system has no O_TMPFILE: a killed writer leaves %s.partial)\n", path.c_str());
    std::remove((path + ".partial").c_str());
    return;
  }
  Check(!Exists(path) && !Exists(path + ".partial"), "a killed writer leaves no file behind");
}

//------------------------------------------------------------------------------
void StorageChoiceRules()
{
  const std::uint64_t GB = 1ull << 30;
  StorageChoice c = ChooseBasisStorage(BasisStorage::Automatic, 2 * GB, GB, 3 * GB, GB, 10 * GB);
  Check(c.Chosen == BasisStorage::InMemory, "automatic: in memory when it fits: " + c.Reason);
  c = ChooseBasisStorage(BasisStorage::Automatic, 5 * GB, GB, 3 * GB, 4 * GB, 10 * GB);
  Check(c.Chosen == BasisStorage::File, "automatic: a file when only the file fits: " + c.Reason);
  c = ChooseBasisStorage(BasisStorage::Automatic, 5 * GB, GB, 3 * GB, 4 * GB, 2 * GB);
  Check(c.Chosen == BasisStorage::Automatic &&
      c.Refusal.find("needs 4.0 GiB on its disk while it is written") != std::string::npos,
    "automatic: refused, naming the disk room needed: " + c.Refusal);
  c = ChooseBasisStorage(BasisStorage::Automatic, 5 * GB, 4 * GB, 3 * GB, GB, 10 * GB);
  Check(c.Chosen == BasisStorage::Automatic &&
      c.Refusal.find("the solve alone needs about 4.0 GiB") != std::string::npos,
    "automatic: refused when even the solve does not fit: " + c.Refusal);
  c = ChooseBasisStorage(BasisStorage::File, GB, GB, 3 * GB, 4 * GB, 2 * GB);
  Check(c.Chosen == BasisStorage::Automatic && !c.Refusal.empty(),
    "file: refused without disk room: " + c.Refusal);
  c = ChooseBasisStorage(BasisStorage::InMemory, 5 * GB, GB, 3 * GB, GB, 10 * GB);
  Check(c.Chosen == BasisStorage::InMemory, "in memory: as asked (the solve's check refuses)");
}

//------------------------------------------------------------------------------
void DigestAndOptions()
{
  std::vector<double> points = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
  const std::vector<int> triangle = { 0, 1, 2 };
  const std::uint64_t d = MeshDigest(points.data(), 3, triangle.data(), 1, nullptr, 0);
  points[4] = std::nextafter(points[4], 1.0);
  Check(MeshDigest(points.data(), 3, triangle.data(), 1, nullptr, 0) != d,
    "one coordinate bit changes the digest");
  const std::vector<int> flipped = { 0, 2, 1 };
  points[4] = 0.0;
  Check(MeshDigest(points.data(), 3, flipped.data(), 1, nullptr, 0) != d,
    "the order of a cell's points changes the digest");
  Check(MeshDigest(points.data(), 3, triangle.data(), 1, nullptr, 0) == d, "the digest is stable");
  const std::string changes = DescribeOptionChanges("A=1\nB=2\nC=3\n", "A=1\nB=5\nD=4\n");
  Check(changes == "B 2 -> 5, D (none) -> 4, C 3 -> (none)", "option changes named: " + changes);
  Check(DescribeOptionChanges("A=1\n", "A=1\n").empty(), "equal options: no change");
}

const Case Cases[] = {
  { "RoundTrip", RoundTrip },
  { "InvalidWritesRefused", InvalidWritesRefused },
  { "DamagedAndForeignFiles", DamagedAndForeignFiles },
  { "UncommittedLeavesNothing", UncommittedLeavesNothing },
  { "CommitProgressAndCancel", CommitProgressAndCancel },
  { "KilledLeavesNothing", KilledLeavesNothing },
  { "StorageChoiceRules", StorageChoiceRules },
  { "DigestAndOptions", DigestAndOptions },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
