// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Common/BasisFile.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iomanip>
#include <map>
#include <mutex>
#include <sstream>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

namespace spectral
{
namespace
{
constexpr char Magic[8] = { 'M', 'H', 'B', 'A', 'S', 'I', 'S', '\0' };
constexpr std::uint32_t ByteOrderMark = 0x01020304u;
/// The fixed part: magic, version, byte order, n, m, b, reserved, digest, payload offset,
/// header bytes, header checksum.
constexpr std::uint64_t FixedBytes = 80;
/// Bytes kept in the header for the warnings of the solve (Commit drops those beyond).
constexpr std::uint64_t WarningRoom = 65536;

//------------------------------------------------------------------------------
std::string SystemError(const std::string& what, const std::string& path)
{
  return what + " '" + path + "': " + std::strerror(errno);
}

//------------------------------------------------------------------------------
std::uint64_t PageSize()
{
  const long size = sysconf(_SC_PAGESIZE);
  return size > 0 ? static_cast<std::uint64_t>(size) : 4096;
}

//------------------------------------------------------------------------------
// The variable part of the header as bytes.
struct Buffer
{
  std::string Bytes;
  template<typename T>
  void Put(const T& value)
  {
    this->Bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void PutString(const std::string& text)
  {
    this->Put<std::uint64_t>(text.size());
    this->Bytes.append(text);
  }
  void PutDoubles(const std::vector<double>& values)
  {
    this->Bytes.append(
      reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  }
};

//------------------------------------------------------------------------------
// Reads the variable part back; every read is bounds-checked (a damaged header is Unusable).
struct Reader
{
  const std::string& Bytes;
  const std::string& Path;
  std::size_t At = 0;
  void Need(std::uint64_t size)
  {
    if (size > this->Bytes.size() - this->At)
    {
      throw BasisFileError(BasisFileError::Kind::Unusable,
        "the basis file '" + this->Path + "' has a damaged header (a field runs past its end)");
    }
  }
  template<typename T>
  T Get()
  {
    this->Need(sizeof(T));
    T value;
    std::memcpy(&value, this->Bytes.data() + this->At, sizeof(T));
    this->At += sizeof(T);
    return value;
  }
  std::string GetString()
  {
    const std::uint64_t size = this->Get<std::uint64_t>();
    this->Need(size);
    std::string text = this->Bytes.substr(this->At, size);
    this->At += size;
    return text;
  }
  std::vector<double> GetDoubles(std::uint64_t count)
  {
    if (count > (this->Bytes.size() - this->At) / sizeof(double))
    {
      this->Need(this->Bytes.size() + 1);
    }
    std::vector<double> values(count);
    std::memcpy(values.data(), this->Bytes.data() + this->At, count * sizeof(double));
    this->At += count * sizeof(double);
    return values;
  }
};

//------------------------------------------------------------------------------
std::string VariableHeader(const BasisFileHeader& header)
{
  Buffer buffer;
  buffer.PutString(header.Options);
  buffer.PutDoubles(header.Eigenvalues);
  buffer.PutDoubles(header.Mass);
  buffer.Put(header.BackwardError);
  buffer.Put(header.Residual);
  buffer.Put<std::uint64_t>(header.Warnings.size());
  for (const std::string& warning : header.Warnings)
  {
    buffer.PutString(warning);
  }
  return buffer.Bytes;
}

//------------------------------------------------------------------------------
std::string FixedHeader(const BasisFileHeader& header, const std::string& variable)
{
  Buffer buffer;
  buffer.Bytes.append(Magic, sizeof(Magic));
  buffer.Put(BasisFileVersion);
  buffer.Put(ByteOrderMark);
  buffer.Put(header.Rows);
  buffer.Put(header.Columns);
  buffer.Put(header.BytesPerValue);
  buffer.Put<std::uint32_t>(0);
  buffer.Put(header.MeshDigest);
  buffer.Put(header.PayloadOffset);
  buffer.Put<std::uint64_t>(variable.size());
  buffer.Put(Fnv1a(variable.data(), variable.size()));
  return buffer.Bytes;
}

//------------------------------------------------------------------------------
// Writes `size` bytes at `offset`; \throws BasisFileError (Io) "<what> '<path>': <reason>".
void WriteAll(int descriptor,
  const void* data,
  std::uint64_t size,
  std::uint64_t offset,
  const std::string& path,
  const std::string& what = "cannot write")
{
  const char* bytes = static_cast<const char*>(data);
  std::uint64_t done = 0;
  while (done < size)
  {
    const ssize_t wrote =
      pwrite(descriptor, bytes + done, size - done, static_cast<off_t>(offset + done));
    if (wrote < 0 && errno == EINTR)
    {
      continue;
    }
    if (wrote == 0)
    {
      errno = ENOSPC; // no progress and no error: report it as what it would be
    }
    if (wrote <= 0)
    {
      throw BasisFileError(BasisFileError::Kind::Io, SystemError(what, path));
    }
    done += static_cast<std::size_t>(wrote);
  }
}

//------------------------------------------------------------------------------
void WriteAll(int descriptor,
  const std::string& bytes,
  std::uint64_t offset,
  const std::string& path)
{
  WriteAll(descriptor, bytes.data(), bytes.size(), offset, path);
}

//------------------------------------------------------------------------------
// Reads exactly `size` bytes at `offset`; false at the end of the file.
bool ReadAll(int descriptor, char* bytes, std::uint64_t size, std::uint64_t offset)
{
  std::uint64_t done = 0;
  while (done < size)
  {
    const ssize_t got =
      pread(descriptor, bytes + done, size - done, static_cast<off_t>(offset + done));
    if (got < 0 && errno == EINTR)
    {
      continue;
    }
    if (got <= 0)
    {
      return false;
    }
    done += static_cast<std::uint64_t>(got);
  }
  return true;
}

//------------------------------------------------------------------------------
// The registry of the mappings of MapBasisPayload: the free function of a VTK array gets only
// the pointer.
std::mutex& RegistryMutex()
{
  static std::mutex mutex;
  return mutex;
}
std::map<void*, std::uint64_t>& Registry()
{
  static std::map<void*, std::uint64_t> mappings;
  return mappings;
}

//------------------------------------------------------------------------------
// The lines of an options text by name.
std::map<std::string, std::string> OptionLines(const std::string& text)
{
  std::map<std::string, std::string> lines;
  std::istringstream stream(text);
  std::string line;
  while (std::getline(stream, line))
  {
    const std::size_t equal = line.find('=');
    lines[line.substr(0, equal)] = equal == std::string::npos ? "" : line.substr(equal + 1);
  }
  return lines;
}
//------------------------------------------------------------------------------
// Gathers columns of a tile: out (tileRows x count, column-major) takes value (sourceOf[r], k)
// of `values` (leading dimension `rows`), 0 where sourceOf[r] is negative (`sourceOf` starts
// at the tile's first row).
template<typename T>
void GatherTileAs(T* out,
  const double* values,
  std::uint64_t rows,
  std::uint64_t count,
  const int* sourceOf,
  std::uint64_t tileRows)
{
  for (std::uint64_t k = 0; k < count; ++k)
  {
    const double* column = values + k * rows;
    T* to = out + k * tileRows;
    for (std::uint64_t r = 0; r < tileRows; ++r)
    {
      to[r] = sourceOf[r] >= 0 ? static_cast<T>(column[sourceOf[r]]) : T(0);
    }
  }
}

/// GatherTileAs into values of `bytesPerValue` bytes (4: float, else double).
void GatherTile(unsigned char* out,
  std::uint32_t bytesPerValue,
  const double* values,
  std::uint64_t rows,
  std::uint64_t count,
  const int* sourceOf,
  std::uint64_t tileRows)
{
  if (bytesPerValue == 4)
  {
    GatherTileAs(reinterpret_cast<float*>(out), values, rows, count, sourceOf, tileRows);
  }
  else
  {
    GatherTileAs(reinterpret_cast<double*>(out), values, rows, count, sourceOf, tileRows);
  }
}

//------------------------------------------------------------------------------
// Transposes a tile: `rowMajor` (rows x m) from `columnMajor` (leading dimension rows), in
// blocks of rows so that both stay in the cache.
template<typename T>
void TransposeTileAs(T* rowMajor, const T* columnMajor, std::uint64_t rows, std::uint64_t m)
{
  const std::uint64_t block = 64;
  for (std::uint64_t r0 = 0; r0 < rows; r0 += block)
  {
    const std::uint64_t r1 = std::min(rows, r0 + block);
    for (std::uint64_t c = 0; c < m; ++c)
    {
      const T* from = columnMajor + c * rows;
      for (std::uint64_t r = r0; r < r1; ++r)
      {
        rowMajor[r * m + c] = from[r];
      }
    }
  }
}

/// TransposeTileAs on values of `bytesPerValue` bytes (4: float, else double).
void TransposeTile(unsigned char* rowMajor,
  const unsigned char* columnMajor,
  std::uint32_t bytesPerValue,
  std::uint64_t rows,
  std::uint64_t m)
{
  if (bytesPerValue == 4)
  {
    TransposeTileAs(
      reinterpret_cast<float*>(rowMajor), reinterpret_cast<const float*>(columnMajor), rows, m);
  }
  else
  {
    TransposeTileAs(
      reinterpret_cast<double*>(rowMajor), reinterpret_cast<const double*>(columnMajor), rows, m);
  }
}
} // namespace

//------------------------------------------------------------------------------
std::uint64_t Fnv1a(const void* bytes, std::size_t size, std::uint64_t hash)
{
  const unsigned char* data = static_cast<const unsigned char*>(bytes);
  for (std::size_t i = 0; i < size; ++i)
  {
    hash ^= data[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

//------------------------------------------------------------------------------
std::uint64_t MeshDigest(const double* points,
  std::size_t numPoints,
  const int* triangles,
  std::size_t numTriangles,
  const int* tets,
  std::size_t numTets)
{
  const std::uint64_t counts[3] = { numPoints, numTriangles, numTets };
  std::uint64_t hash = Fnv1a(counts, sizeof(counts));
  hash = Fnv1a(points, numPoints * 3 * sizeof(double), hash);
  hash = Fnv1a(triangles, numTriangles * 3 * sizeof(int), hash);
  return Fnv1a(tets, numTets * 4 * sizeof(int), hash);
}

//------------------------------------------------------------------------------
std::string DescribeOptionChanges(const std::string& before, const std::string& now)
{
  const std::map<std::string, std::string> a = OptionLines(before);
  const std::map<std::string, std::string> b = OptionLines(now);
  std::string changes;
  const auto add = [&changes](
                     const std::string& name, const std::string& from, const std::string& to)
  { changes += (changes.empty() ? "" : ", ") + name + " " + from + " -> " + to; };
  for (const auto& line : b)
  {
    const auto old = a.find(line.first);
    if (old == a.end() || old->second != line.second)
    {
      add(line.first, old == a.end() ? "(none)" : old->second, line.second);
    }
  }
  for (const auto& line : a)
  {
    if (b.find(line.first) == b.end())
    {
      add(line.first, line.second, "(none)");
    }
  }
  return changes;
}

//------------------------------------------------------------------------------
BasisFileHeader ReadBasisFileHeader(const std::string& path)
{
  const int descriptor = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor < 0)
  {
    throw BasisFileError(BasisFileError::Kind::Io, SystemError("cannot open the basis file", path));
  }
  struct Closer
  {
    int Descriptor;
    ~Closer() { close(this->Descriptor); }
  } closer{ descriptor };
  struct stat status;
  if (fstat(descriptor, &status) != 0)
  {
    throw BasisFileError(BasisFileError::Kind::Io, SystemError("cannot stat", path));
  }
  if (S_ISDIR(status.st_mode))
  {
    throw BasisFileError(BasisFileError::Kind::Foreign,
      "'" + path + "' is a directory, not a manifold harmonics basis file: name a file in it");
  }
  const std::uint64_t fileSize = static_cast<std::uint64_t>(status.st_size);
  const auto unusable = [&path](const std::string& why) {
    return BasisFileError(BasisFileError::Kind::Unusable, "the basis file '" + path + "' " + why);
  };
  std::string fixed(FixedBytes, '\0');
  if (!ReadAll(descriptor, &fixed[0], FixedBytes, 0))
  {
    if (fileSize >= sizeof(Magic) && std::memcmp(fixed.data(), Magic, sizeof(Magic)) == 0)
    {
      throw unusable(
        "is truncated (" + std::to_string(fileSize) + " bytes, shorter than its header)");
    }
    throw BasisFileError(BasisFileError::Kind::Foreign,
      "'" + path + "' is not a manifold harmonics basis file (" + std::to_string(fileSize) +
        " bytes, too short)");
  }
  if (std::memcmp(fixed.data(), Magic, sizeof(Magic)) != 0)
  {
    throw BasisFileError(BasisFileError::Kind::Foreign,
      "'" + path + "' is not a manifold harmonics basis file (no MHBASIS signature)");
  }
  Reader fields{ fixed, path, sizeof(Magic) };
  const std::uint32_t version = fields.Get<std::uint32_t>();
  const std::uint32_t order = fields.Get<std::uint32_t>();
  if (version != BasisFileVersion)
  {
    throw unusable("has format version " + std::to_string(version) + "; this build reads version " +
      std::to_string(BasisFileVersion));
  }
  if (order != ByteOrderMark)
  {
    throw unusable("was written on a machine of the other byte order");
  }
  BasisFileHeader header;
  header.Rows = fields.Get<std::uint64_t>();
  header.Columns = fields.Get<std::uint64_t>();
  header.BytesPerValue = fields.Get<std::uint32_t>();
  fields.Get<std::uint32_t>();
  header.MeshDigest = fields.Get<std::uint64_t>();
  header.PayloadOffset = fields.Get<std::uint64_t>();
  const std::uint64_t variableBytes = fields.Get<std::uint64_t>();
  const std::uint64_t checksum = fields.Get<std::uint64_t>();
  if (header.BytesPerValue != 4 && header.BytesPerValue != 8)
  {
    throw unusable("has " + std::to_string(header.BytesPerValue) + " bytes a value (4 or 8)");
  }
  // n m b must not overflow, and the header must lie before the payload.
  const std::uint64_t limit = ~std::uint64_t(0) / 16;
  if (header.Rows > limit || header.Columns > limit ||
    (header.Columns > 0 && header.Rows > limit / header.Columns) || variableBytes > fileSize ||
    header.PayloadOffset < FixedBytes + variableBytes || header.PayloadOffset % PageSize() != 0)
  {
    throw unusable("has sizes that disagree (n " + std::to_string(header.Rows) + ", m " +
      std::to_string(header.Columns) + ", header " + std::to_string(variableBytes) +
      " bytes, payload at " + std::to_string(header.PayloadOffset) + ")");
  }
  const std::uint64_t expected = header.PayloadOffset + header.PayloadBytes();
  if (fileSize != expected)
  {
    throw unusable(
      std::string(fileSize < expected ? "is truncated" : "is longer than its header says") + ": " +
      std::to_string(fileSize) + " bytes, " + std::to_string(expected) + " expected for n " +
      std::to_string(header.Rows) + ", m " + std::to_string(header.Columns) + " and " +
      std::to_string(header.BytesPerValue) + "-byte values");
  }
  std::string variable(variableBytes, '\0');
  if (!ReadAll(descriptor, &variable[0], variableBytes, FixedBytes))
  {
    throw unusable("is truncated in its header");
  }
  if (Fnv1a(variable.data(), variable.size()) != checksum)
  {
    throw unusable("has a damaged header (its checksum does not match)");
  }
  Reader reader{ variable, path };
  header.Options = reader.GetString();
  header.Eigenvalues = reader.GetDoubles(header.Columns);
  header.Mass = reader.GetDoubles(header.Rows);
  header.BackwardError = reader.Get<double>();
  header.Residual = reader.Get<double>();
  const std::uint64_t warnings = reader.Get<std::uint64_t>();
  for (std::uint64_t w = 0; w < warnings; ++w)
  {
    header.Warnings.push_back(reader.GetString());
  }
  return header;
}

//------------------------------------------------------------------------------
std::uint64_t RowsPerTile(std::uint64_t m, std::uint32_t b, std::uint64_t tileBytes)
{
  return std::max<std::uint64_t>(1, tileBytes / std::max<std::uint64_t>(1, m * b));
}

//------------------------------------------------------------------------------
std::uint64_t BasisFileDiskBytes(std::uint64_t n,
  std::uint64_t m,
  std::uint32_t b,
  BasisFileWriting writing)
{
  // The header: the fixed part, n masses, m eigenvalues, the figures, the warnings' room, and
  // the options (a few hundred bytes; a page is kept for them), up to the page-aligned payload.
  const std::uint64_t page = PageSize();
  const std::uint64_t header = FixedBytes + 8 * (n + m) + 64 + WarningRoom + page;
  const std::uint64_t payload = n * m * b;
  return (header + page - 1) / page * page +
    (writing == BasisFileWriting::InBands ? 2 * payload : payload);
}

//------------------------------------------------------------------------------
std::uint64_t BasisFileWriterBytes(std::uint64_t n,
  std::uint64_t m,
  std::uint32_t b,
  std::uint64_t columns)
{
  return 16 * n + std::min(n, RowsPerTile(m, b, BasisFileTileBytes)) * std::min(columns, m) * b;
}

namespace
{
//------------------------------------------------------------------------------
// A new file without a name (O_TMPFILE, read and write) in the directory of `beside`, or -1
// (errno set) where the file system has none.
int OpenUnnamed(const std::string& beside, mode_t mode)
{
  return open(DirectoryOf(beside).c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, mode);
}

//------------------------------------------------------------------------------
// Gives the file without a name open as `descriptor` the name `name`: linkat through /proc, or
// AT_EMPTY_PATH where the process may. False (errno set) when neither works.
bool NameFile(int descriptor, const std::string& name)
{
  const std::string self = "/proc/self/fd/" + std::to_string(descriptor);
  return linkat(AT_FDCWD, self.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0 ||
    linkat(descriptor, "", AT_FDCWD, name.c_str(), AT_EMPTY_PATH) == 0;
}

//------------------------------------------------------------------------------
// Copies the `bytes` of the file open as `descriptor` to a new file `name`, synced: where a file
// without a name cannot be named (no /proc, no CAP_DAC_READ_SEARCH; linking is tried only at
// the commit, since a file linked once cannot be linked again after its unlink). False (errno
// set) on failure, the new file removed.
bool CopyToName(int descriptor, std::uint64_t bytes, const std::string& name)
{
  const int copy = open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (copy < 0)
  {
    return false;
  }
  std::vector<char> buffer(std::min<std::uint64_t>(bytes, BasisFileTileBytes));
  std::uint64_t done = 0;
  bool ok = true;
  while (ok && done < bytes)
  {
    const std::uint64_t size = std::min<std::uint64_t>(buffer.size(), bytes - done);
    ok = ReadAll(descriptor, buffer.data(), size, done);
    if (ok)
    {
      try
      {
        WriteAll(copy, buffer.data(), size, done, name);
      }
      catch (const BasisFileError&)
      {
        ok = false;
      }
    }
    done += size;
  }
  ok = ok && fsync(copy) == 0;
  const int error = errno;
  close(copy);
  if (!ok)
  {
    unlink(name.c_str());
    errno = error;
  }
  return ok;
}

//------------------------------------------------------------------------------
// An unlinked file in `directory` for the scratch of `partial`: O_TMPFILE where the file system
// has it (never has a name), else a new file named after `partial`, unlinked at once. -1 with
// errno set when neither can be created.
int CreateScratch(const std::string& partial)
{
  const int unnamed = OpenUnnamed(partial, 0600);
  if (unnamed >= 0)
  {
    return unnamed;
  }
  const std::string named = partial + ".tiles";
  unlink(named.c_str());
  const int descriptor =
    open(named.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (descriptor >= 0)
  {
    unlink(named.c_str());
  }
  return descriptor;
}
} // namespace

//------------------------------------------------------------------------------
BasisFileWriter::BasisFileWriter(const std::string& path,
  const BasisFileHeader& header,
  BasisFileWriting writing,
  std::uint64_t tileBytes)
  : Path(path)
  , Partial(path + ".partial")
  , Header(header)
  , Writing(writing)
{
  if (header.BytesPerValue != 4 && header.BytesPerValue != 8)
  {
    throw std::invalid_argument(
      "BasisFileWriter: values of 4 or 8 bytes, not " + std::to_string(header.BytesPerValue));
  }
  const std::uint64_t page = PageSize();
  // Room for the header of Commit: m eigenvalues, n masses, and warnings known only at the end.
  BasisFileHeader sized = header;
  sized.Eigenvalues.resize(header.Columns);
  sized.Mass.resize(header.Rows);
  const std::uint64_t used = FixedBytes + VariableHeader(sized).size() + WarningRoom;
  this->Header.PayloadOffset = (used + page - 1) / page * page;
  this->TileRows = RowsPerTile(header.Columns, header.BytesPerValue, tileBytes);
  const std::uint64_t payload = this->Header.PayloadBytes();
  // Without a name until the commit (O_TMPFILE) where the file system allows: a solve killed on
  // the way (out of memory, a crash) leaves nothing behind. Else `<path>.partial`.
  this->Descriptor = OpenUnnamed(path, 0644);
  this->Unnamed = this->Descriptor >= 0;
  if (!this->Unnamed)
  {
    unlink(this->Partial.c_str());
    this->Descriptor = open(this->Partial.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  }
  if (this->Descriptor < 0)
  {
    throw BasisFileError(
      BasisFileError::Kind::Io, SystemError("cannot create the basis file", this->Partial));
  }
  if (writing == BasisFileWriting::InBands)
  {
    // Beside it (the same disk), without a name: closing it frees its blocks, whatever ends the
    // writer.
    this->Scratch = CreateScratch(this->Partial);
    if (this->Scratch < 0)
    {
      const std::string message =
        SystemError("cannot create the scratch of the basis file", this->Partial);
      this->Discard();
      throw BasisFileError(BasisFileError::Kind::Io, message);
    }
  }
  // Blocks allocated now: a disk that fills up is an error here, not at the end of a long solve.
  int allocated =
    posix_fallocate(this->Descriptor, 0, static_cast<off_t>(this->Header.PayloadOffset + payload));
  if (allocated == 0 && this->Scratch >= 0 && payload > 0)
  {
    allocated = posix_fallocate(this->Scratch, 0, static_cast<off_t>(payload));
  }
  if (allocated != 0)
  {
    errno = allocated;
    const std::string message = SystemError("cannot allocate the " +
        ByteCount(BasisFileDiskBytes(header.Rows, header.Columns, header.BytesPerValue, writing)) +
        " the basis file takes while it is written",
      this->Partial);
    this->Discard();
    throw BasisFileError(BasisFileError::Kind::Io, message);
  }
}

//------------------------------------------------------------------------------
BasisFileWriter::~BasisFileWriter()
{
  if (!this->Committed)
  {
    this->Discard();
  }
}

//------------------------------------------------------------------------------
void BasisFileWriter::Discard()
{
  if (this->Scratch >= 0)
  {
    close(this->Scratch);
    this->Scratch = -1;
  }
  if (this->Descriptor >= 0)
  {
    close(this->Descriptor);
    this->Descriptor = -1;
  }
  if (!this->Unnamed)
  {
    unlink(this->Partial.c_str());
  }
}

//------------------------------------------------------------------------------
std::uint64_t BasisFileWriter::RowsOfTile(std::uint64_t t) const
{
  return std::min(this->TileRows, this->Header.Rows - t * this->TileRows);
}

//------------------------------------------------------------------------------
void BasisFileWriter::WriteColumns(std::uint64_t firstColumn,
  std::uint64_t count,
  const double* values,
  std::uint64_t rows,
  const std::vector<int>& sources,
  const std::vector<std::int64_t>& targets)
{
  const std::uint64_t n = this->Header.Rows;
  const std::uint64_t m = this->Header.Columns;
  const std::uint32_t b = this->Header.BytesPerValue;
  if (firstColumn + count > m)
  {
    throw std::out_of_range("BasisFileWriter::WriteColumns: columns beyond m");
  }
  if (this->Writing == BasisFileWriting::Whole && (firstColumn != 0 || count != m))
  {
    throw std::invalid_argument("BasisFileWriter::WriteColumns: a writer of the Whole basis "
                                "takes all its columns at once");
  }
  if (sources.size() != targets.size())
  {
    throw std::invalid_argument("BasisFileWriter::WriteColumns: sources and targets differ in "
                                "length");
  }
  if (count == 0 || n == 0)
  {
    return;
  }
  // The source row of each output row (-1: none), so that a tile is gathered in its own order.
  this->SourceOf.assign(n, -1);
  for (std::size_t e = 0; e < targets.size(); ++e)
  {
    if (targets[e] < 0 || static_cast<std::uint64_t>(targets[e]) >= n || sources[e] < 0 ||
      static_cast<std::uint64_t>(sources[e]) >= rows)
    {
      throw std::out_of_range("BasisFileWriter::WriteColumns: row " + std::to_string(sources[e]) +
        " -> " + std::to_string(targets[e]) + " outside " + std::to_string(rows) + " -> " +
        std::to_string(n));
    }
    this->SourceOf[static_cast<std::size_t>(targets[e])] = sources[e];
  }
  const std::uint64_t tileValues = std::min(n, this->TileRows) * count;
  std::vector<unsigned char> tile(tileValues * b);
  // A whole basis is transposed here, into the payload; bands go to the scratch.
  std::vector<unsigned char> transposed(
    this->Writing == BasisFileWriting::Whole ? tileValues * b : 0);
  for (std::uint64_t t = 0; t * this->TileRows < n; ++t)
  {
    const std::uint64_t first = t * this->TileRows;
    const std::uint64_t tileRows = this->RowsOfTile(t);
    GatherTile(tile.data(), b, values, rows, count, this->SourceOf.data() + first, tileRows);
    if (this->Writing == BasisFileWriting::Whole)
    {
      TransposeTile(transposed.data(), tile.data(), b, tileRows, m);
      WriteAll(this->Descriptor,
        transposed.data(),
        tileRows * m * b,
        this->Header.PayloadOffset + first * m * b,
        this->Partial);
      continue;
    }
    WriteAll(this->Scratch,
      tile.data(),
      tileRows * count * b,
      (first * m + firstColumn * tileRows) * b,
      this->Partial,
      "cannot write the scratch of");
  }
}

//------------------------------------------------------------------------------
void BasisFileWriter::Commit(const BasisFileHeader& header, const Monitor& monitor)
{
  BasisFileHeader final = header;
  std::uint64_t warningBytes = 0;
  std::size_t kept = 0;
  while (
    kept < final.Warnings.size() && warningBytes + final.Warnings[kept].size() + 8 < WarningRoom)
  {
    warningBytes += final.Warnings[kept++].size() + 8;
  }
  final.Warnings.resize(kept);
  final.Eigenvalues.resize(this->Header.Columns);
  final.Mass.resize(this->Header.Rows);
  final.Rows = this->Header.Rows;
  final.Columns = this->Header.Columns;
  final.BytesPerValue = this->Header.BytesPerValue;
  final.PayloadOffset = this->Header.PayloadOffset;
  const std::string variable = VariableHeader(final);
  if (FixedBytes + variable.size() > final.PayloadOffset)
  {
    throw BasisFileError(BasisFileError::Kind::Io,
      "the header of '" + this->Partial + "' grew beyond the room kept for it");
  }
  // The payload from the scratch, tile after tile: one sequential read, one sequential write.
  // The scratch's pages are dropped as they are read (they would push the payload out of the
  // page cache, where the mapping that follows reads it).
  const std::uint64_t n = final.Rows;
  const std::uint64_t m = final.Columns;
  const std::uint32_t b = final.BytesPerValue;
  if (this->Scratch >= 0 && n > 0 && m > 0)
  {
    const std::uint64_t tileBytes = std::min(n, this->TileRows) * m * b;
    std::vector<unsigned char> columns(tileBytes);
    std::vector<unsigned char> rows(tileBytes);
    for (std::uint64_t t = 0; t * this->TileRows < n; ++t)
    {
      const std::uint64_t first = t * this->TileRows;
      monitor.ThrowIfCancelled();
      monitor.Report(static_cast<double>(first) / static_cast<double>(n));
      const std::uint64_t tileRows = this->RowsOfTile(t);
      const std::uint64_t bytes = tileRows * m * b;
      errno = 0;
      if (!ReadAll(this->Scratch, reinterpret_cast<char*>(columns.data()), bytes, first * m * b))
      {
        throw BasisFileError(BasisFileError::Kind::Io,
          "the scratch of '" + this->Partial + "' could not be read back (" +
            (errno != 0 ? std::string(std::strerror(errno)) : "it ended early") + ")");
      }
      posix_fadvise(this->Scratch,
        static_cast<off_t>(first * m * b),
        static_cast<off_t>(bytes),
        POSIX_FADV_DONTNEED);
      TransposeTile(rows.data(), columns.data(), b, tileRows, m);
      WriteAll(
        this->Descriptor, rows.data(), bytes, final.PayloadOffset + first * m * b, this->Partial);
    }
  }
  if (this->Scratch >= 0)
  {
    close(this->Scratch);
    this->Scratch = -1;
  }
  monitor.ThrowIfCancelled();
  WriteAll(this->Descriptor, FixedHeader(final, variable), 0, this->Partial);
  WriteAll(this->Descriptor, variable, FixedBytes, this->Partial);
  if (fsync(this->Descriptor) != 0)
  {
    throw BasisFileError(BasisFileError::Kind::Io, SystemError("cannot sync", this->Partial));
  }
  if (this->Unnamed)
  {
    // The complete file gets the partial name (linkat through /proc, or AT_EMPTY_PATH where
    // the process may), then the final one by an atomic rename.
    unlink(this->Partial.c_str());
    if (!NameFile(this->Descriptor, this->Partial) &&
      !CopyToName(
        this->Descriptor, this->Header.PayloadOffset + this->Header.PayloadBytes(), this->Partial))
    {
      throw BasisFileError(BasisFileError::Kind::Io, SystemError("cannot name", this->Partial));
    }
    this->Unnamed = false;
  }
  if (rename(this->Partial.c_str(), this->Path.c_str()) != 0)
  {
    throw BasisFileError(BasisFileError::Kind::Io, SystemError("cannot rename to", this->Path));
  }
  this->Committed = true;
  close(this->Descriptor);
  this->Descriptor = -1;
  const int directory = open(DirectoryOf(this->Path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (directory >= 0)
  {
    fsync(directory);
    close(directory);
  }
  monitor.Report(1.0);
}

//------------------------------------------------------------------------------
void* MapBasisPayload(const std::string& path, const BasisFileHeader& header)
{
  const std::uint64_t bytes = header.PayloadBytes();
  if (bytes == 0)
  {
    return nullptr;
  }
  const int descriptor = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (descriptor < 0)
  {
    throw BasisFileError(BasisFileError::Kind::Io, SystemError("cannot open the basis file", path));
  }
  void* mapped = mmap(
    nullptr, bytes, PROT_READ, MAP_SHARED, descriptor, static_cast<off_t>(header.PayloadOffset));
  const int mapError = errno;
  close(descriptor);
  if (mapped == MAP_FAILED)
  {
    errno = mapError;
    throw BasisFileError(BasisFileError::Kind::Io, SystemError("cannot map the basis file", path));
  }
  std::lock_guard<std::mutex> lock(RegistryMutex());
  Registry()[mapped] = bytes;
  return mapped;
}

//------------------------------------------------------------------------------
void UnmapBasisPayload(void* payload)
{
  std::uint64_t bytes = 0;
  {
    std::lock_guard<std::mutex> lock(RegistryMutex());
    const auto found = Registry().find(payload);
    if (found == Registry().end())
    {
      return;
    }
    bytes = found->second;
    Registry().erase(found);
  }
  munmap(payload, bytes);
}

//------------------------------------------------------------------------------
StorageChoice ChooseBasisStorage(BasisStorage requested,
  std::uint64_t inMemory,
  std::uint64_t inFile,
  std::uint64_t available,
  std::uint64_t fileBytes,
  std::uint64_t diskFree,
  const std::string& unwritable)
{
  StorageChoice choice;
  const std::string memory =
    "about " + ByteCount(inMemory) + " needed in memory, " + ByteCount(available) + " available";
  const std::string disk = unwritable.empty()
    ? ByteCount(fileBytes) + " on its disk while it is written, " + ByteCount(diskFree) + " free"
    : unwritable;
  if (requested == BasisStorage::InMemory)
  {
    choice.Chosen = BasisStorage::InMemory;
    choice.Reason = "in memory, as asked (" + memory + ")";
    return choice;
  }
  const bool diskFits = unwritable.empty() && fileBytes <= diskFree;
  if (requested == BasisStorage::File)
  {
    choice.Chosen = diskFits ? BasisStorage::File : BasisStorage::Automatic;
    choice.Reason = "in a file, as asked (" + disk + ")";
    if (!unwritable.empty())
    {
      choice.Refusal = "The basis file cannot be created: " + unwritable +
        ". Choose a BasisFileName in a writable directory (or set TMPDIR for a temporary one).";
    }
    else if (!diskFits)
    {
      choice.Refusal = "The basis file does not fit on its disk: " + disk +
        ". Free disk space, choose another BasisFileName (a disk with " + ByteCount(fileBytes) +
        " free), compute fewer harmonics or set BasisPrecision to Float.";
    }
    return choice;
  }
  if (inMemory <= available)
  {
    choice.Chosen = BasisStorage::InMemory;
    choice.Reason = "in memory: it fits (" + memory + ")";
    return choice;
  }
  if (inFile <= available && diskFits)
  {
    choice.Chosen = BasisStorage::File;
    choice.Reason = "in a file: it does not fit in memory (" + memory + "), it does in a file (" +
      disk + ", " + ByteCount(inFile) + " of memory for the solve)";
    return choice;
  }
  choice.Chosen = BasisStorage::Automatic;
  choice.Refusal = "A file would not do either: " +
    (!unwritable.empty() ? unwritable + " (choose a BasisFileName in a writable directory)"
        : inFile > available
        ? "the solve alone needs about " + ByteCount(inFile) + " of memory"
        : "the file needs " + ByteCount(fileBytes) + " on its disk while it is written (" +
          ByteCount(diskFree) + " free on its disk; name a BasisFileName on another)") +
    ".";
  return choice;
}

//------------------------------------------------------------------------------
std::uint64_t FreeDiskSpace(const std::string& directory)
{
  struct statvfs status;
  if (statvfs(directory.c_str(), &status) != 0)
  {
    // Unknown (a missing directory): creating the file will say what is wrong.
    return ~std::uint64_t(0);
  }
  return static_cast<std::uint64_t>(status.f_bavail) * static_cast<std::uint64_t>(status.f_frsize);
}

//------------------------------------------------------------------------------
std::string UnwritableDirectory(const std::string& directory)
{
  struct stat status;
  if (stat(directory.c_str(), &status) != 0)
  {
    return "the directory '" + directory + "' does not exist";
  }
  if (!S_ISDIR(status.st_mode))
  {
    return "'" + directory + "' is not a directory";
  }
  struct statvfs system;
  if (statvfs(directory.c_str(), &system) == 0 && (system.f_flag & ST_RDONLY))
  {
    return "the directory '" + directory + "' is on a read-only file system";
  }
  if (access(directory.c_str(), W_OK | X_OK) != 0)
  {
    return "the directory '" + directory + "' is not writable";
  }
  return std::string();
}

//------------------------------------------------------------------------------
std::string DirectoryOf(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return ".";
  }
  return slash == 0 ? "/" : path.substr(0, slash);
}

//------------------------------------------------------------------------------
std::string ByteCount(std::uint64_t bytes)
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
} // namespace spectral
