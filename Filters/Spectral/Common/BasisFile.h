// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BasisFile.h
 * @brief A basis in a file: its format, its atomic writer, its checked reader, its read-only
 *        mapping, the digest of a mesh, and the choice between memory and a file.
 *
 * The format (version 1, native byte order, recorded and checked):
 *
 *     offset 0   magic "MHBASIS\0" (8 bytes), uint32 version, uint32 byte-order mark 0x01020304
 *            16  uint64 n (rows: the output's points), uint64 m (harmonics), uint32 bytes a
 *                value (8 double, 4 float), uint32 reserved, uint64 mesh digest, uint64 payload
 *                offset, uint64 header bytes, uint64 header checksum (FNV-1a of the header
 *                after this fixed part)
 *            80  the header: the options text (uint64 length, bytes), m eigenvalues, n lumped
 *                masses (one per output point), the backward error and the residual (doubles),
 *                the warnings (uint64 count, then each as uint64 length and bytes)
 *     payload    n m values, row-major (tuple i = the m values of point i: the layout of a
 *                vtkAOSDataArrayTemplate with m components), at a page-aligned offset
 *
 * The file's size is exactly payload offset + n m b: a shorter file is truncated, a longer one
 * inconsistent. The payload has no checksum (reading 32 GB to check it would cost a minute);
 * a file appears under its name only complete: BasisFileWriter writes it without a name
 * (O_TMPFILE; else as `<name>.partial`), fsyncs it, names it `<name>.partial` and renames that,
 * and leaves nothing when it is not committed (an error, an abort, a killed process).
 *
 * Writing band by band into a row-major file is strided (every band touches every row), and
 * through the page cache it rewrites each page once a band when the file is larger than what
 * the cache keeps dirty (171 GiB written for a 7.5 GiB file: Documentation/large-meshes.md).
 * BasisFileWriter therefore writes the bands into a scratch file of row tiles, each tile's rows
 * column after column (a band is one contiguous write a tile), and Commit transposes tile after
 * tile into the payload: the disk writes each value twice and reads it once, in large
 * sequential blocks. The scratch has no name (O_TMPFILE, or unlinked as soon as created):
 * nothing is left behind, even by a crash; the disk holds both until the commit
 * (BasisFileDiskBytes). A basis computed in memory is written Whole, straight into the payload.
 *
 * Mapping: MapBasisPayload maps the payload read-only and shared (PROT_READ, MAP_SHARED): its
 * pages are page cache (RssFile), not the process's anonymous memory, are never charged against
 * the commit limit, and the system evicts them under pressure. The mapping must not be written
 * (a write is a segmentation fault). UnmapBasisPayload takes the pointer alone (the free
 * function of a VTK array): a registry keeps each mapping's length.
 *
 * Used by vtkManifoldHarmonicBasis (Storage FILE); tested by Testing/Core/TestBasisFile.cxx.
 */
#ifndef spectral_BasisFile_h
#define spectral_BasisFile_h

#include "Common/Monitor.h"

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace spectral
{
/// The version BasisFileWriter writes and ReadBasisFileHeader accepts.
constexpr std::uint32_t BasisFileVersion = 1;

/// Thrown for a file that is not a usable basis file, or an I/O failure; the message says which
/// file and what is wrong.
class BasisFileError : public std::runtime_error
{
public:
  enum class Kind
  {
    /// The file cannot be opened, read, written or mapped (permissions, disk full, ...).
    Io,
    /// Not a basis file at all (another magic): never overwritten without being asked.
    Foreign,
    /// A basis file that cannot be used: another version or byte order, truncated, sizes that
    /// disagree, a damaged header. It may be recomputed and overwritten.
    Unusable
  };
  BasisFileError(Kind kind, const std::string& message)
    : std::runtime_error(message)
    , Which(kind)
  {
  }
  Kind Which;
};

/// What a basis file holds besides its payload.
struct BasisFileHeader
{
  std::uint64_t Rows = 0;
  std::uint64_t Columns = 0;
  /// 8 (double) or 4 (float).
  std::uint32_t BytesPerValue = 8;
  /// MeshDigest of the mesh the basis was computed on.
  std::uint64_t MeshDigest = 0;
  /// The options that change the basis, as "Name=value" lines (compared to decide a reuse;
  /// DescribeOptionChanges names what differs).
  std::string Options;
  std::vector<double> Eigenvalues;
  /// The lumped mass of each of the Rows points.
  std::vector<double> Mass;
  double BackwardError = 0.0;
  double Residual = 0.0;
  std::vector<std::string> Warnings;
  /// Set by ReadBasisFileHeader (and BasisFileWriter): where the payload starts.
  std::uint64_t PayloadOffset = 0;

  /// n m b.
  std::uint64_t PayloadBytes() const { return this->Rows * this->Columns * this->BytesPerValue; }
};

/**
 * A 64-bit FNV-1a digest of a mesh: its point count and coordinates, its triangles and its
 * tetrahedra, as bytes (so any change of a coordinate bit or a cell changes it, up to the
 * 2^-64 chance of a collision).
 * \param points n x 3 coordinates, row after row; \param triangles 3 indices a triangle; \param
 * tets 4 indices a tetrahedron (either may be empty).
 */
std::uint64_t MeshDigest(const double* points,
  std::size_t numPoints,
  const int* triangles,
  std::size_t numTriangles,
  const int* tets,
  std::size_t numTets);

/// FNV-1a 64 of `bytes`, continuing from `hash` (the offset basis to start).
std::uint64_t Fnv1a(const void* bytes,
  std::size_t size,
  std::uint64_t hash = 14695981039346656037ull);

/**
 * The lines of two options texts ("Name=value" a line) that differ, as "Name a -> b" joined by
 * ", " ("" when they agree).
 */
std::string DescribeOptionChanges(const std::string& before, const std::string& now);

/**
 * The header of a basis file, checked: magic, version, byte order, header checksum, and the
 * file's size against n, m and b.
 * \throws BasisFileError (Io when it cannot be read; Foreign for another magic; Unusable
 *         otherwise), naming the file and the fault.
 */
BasisFileHeader ReadBasisFileHeader(const std::string& path);

/// Bytes of the scratch tiles of BasisFileWriter (a tile is as many whole rows as fit; at least
/// one row) and of each of the two buffers that transpose them.
constexpr std::uint64_t BasisFileTileBytes = 16ull << 20;

/// How a BasisFileWriter receives the basis.
enum class BasisFileWriting
{
  /// Blocks of columns as a solve verifies them, in any order, again when the solve restarts:
  /// they go to a scratch file, transposed into the payload at the commit.
  InBands,
  /// All the columns in one WriteColumns call (a basis computed in memory): transposed straight
  /// into the payload, no scratch.
  Whole
};

/// The disk space a basis file of n x m values of b bytes takes while it is written: its header
/// (an upper bound) and payload, and the scratch of the bands (the payload again) when written
/// InBands, until the commit.
std::uint64_t BasisFileDiskBytes(std::uint64_t n,
  std::uint64_t m,
  std::uint32_t b,
  BasisFileWriting writing);

/// Rows of a tile of `tileBytes` (BasisFileTileBytes) in a file of m values of b bytes a row:
/// as many whole rows as fit, at least one.
std::uint64_t RowsPerTile(std::uint64_t m, std::uint32_t b, std::uint64_t tileBytes);

/**
 * The memory of a basis file's writing beside a solve that streams into it (InBands) in blocks of
 * at most `columns` columns, while the solve runs: the writer's source row of each output row
 * (4 n bytes), the caller's map from the solve's rows to the file's (a 4-byte row and an 8-byte
 * point a row: 12 n bytes) and the tile being gathered (RowsPerTile rows of the block). The
 * memory plans of a solve streamed into a file add it to the solve's estimate and give the solve
 * the rest of the limit. A basis written Whole is written after its solve, in the memory the
 * solve's workspace has freed; the commit's two tiles come after the solve too.
 */
std::uint64_t BasisFileWriterBytes(std::uint64_t n,
  std::uint64_t m,
  std::uint32_t b,
  std::uint64_t columns);

/**
 * Writes a basis file atomically: the constructor creates the file without a name (O_TMPFILE;
 * `<path>.partial`, replacing a stale one, where the file system lacks it) and, InBands, the
 * scratch of the bands (without a name too), both allocated on the disk; WriteColumns writes into
 * the scratch (InBands) or the payload (Whole); Commit() transposes the scratch into the payload,
 * writes the header, fsyncs, names the file
 * `<path>.partial` and renames it to `path`. A writer destroyed without Commit() leaves
 * nothing; a process killed while it writes leaves nothing where the file system has
 * O_TMPFILE. Memory: the source row of each output row (4 n bytes) and one tile while writing,
 * two tiles (2 BasisFileTileBytes) while transposing.
 */
class BasisFileWriter
{
public:
  /**
   * \param tileBytes The size of a scratch tile (BasisFileTileBytes; tests pass a few rows' worth
   *        to have many tiles).
   * \throws BasisFileError (Io) when the file or its scratch cannot be created or allocated;
   *         std::invalid_argument for values of other than 4 or 8 bytes.
   */
  BasisFileWriter(const std::string& path,
    const BasisFileHeader& header,
    BasisFileWriting writing = BasisFileWriting::InBands,
    std::uint64_t tileBytes = BasisFileTileBytes);
  ~BasisFileWriter();
  BasisFileWriter(const BasisFileWriter&) = delete;
  BasisFileWriter& operator=(const BasisFileWriter&) = delete;

  /**
   * Writes columns [firstColumn, firstColumn + count) of the rows listed: value (r, c) of the
   * column-major block `values` (rows x count, leading dimension `rows`) goes to each output row
   * targets[e] with sources[e] == r. Output rows no target reaches are 0. Columns written again
   * (a solve that restarts) replace the earlier ones. A Whole writer takes all m columns in one
   * call.
   * \throws BasisFileError (Io) when the file cannot be written; std::out_of_range for columns
   *         beyond m or rows outside [0, rows) -> [0, n); std::invalid_argument otherwise.
   */
  void WriteColumns(std::uint64_t firstColumn,
    std::uint64_t count,
    const double* values,
    std::uint64_t rows,
    const std::vector<int>& sources,
    const std::vector<std::int64_t>& targets);

  /**
   * Completes the file: the payload from the scratch, its header (eigenvalues, figures and
   * warnings known only at the end may be set in `header`; n, m, b must not change), fsync,
   * rename to the final name, fsync of the directory. The payload is moved tile after tile
   * (twice the basis through the disk: minutes for tens of GiB): `monitor` receives the fraction
   * of it done, and a cancellation between two tiles leaves the file uncommitted, as a writer
   * destroyed without Commit.
   * \throws BasisFileError (Io); spectral::Cancelled when monitor.Cancelled returned true.
   */
  void Commit(const BasisFileHeader& header, const Monitor& monitor = Monitor());

  /// The name the file has just before the commit renames it (`<path>.partial`): while it is
  /// written it has no name where the file system allows (O_TMPFILE), else this one.
  const std::string& PartialPath() const { return this->Partial; }

private:
  void Discard();
  /// The rows of tile t: [t TileRows, min(n, (t + 1) TileRows)).
  std::uint64_t RowsOfTile(std::uint64_t t) const;
  std::string Path;
  std::string Partial;
  BasisFileHeader Header;
  int Descriptor = -1;
  /// The scratch file (no name; InBands only): tile t at byte t TileRows m b, its rows column
  /// after column.
  int Scratch = -1;
  std::uint64_t TileRows = 1;
  BasisFileWriting Writing;
  /// Whether the file has no name yet (O_TMPFILE).
  bool Unnamed = false;
  /// The source row of each output row (-1: none) of the last WriteColumns.
  std::vector<int> SourceOf;
  bool Committed = false;
};

/**
 * Maps the payload of a checked basis file read-only and shared.
 * \return The first value (n m values of `header.BytesPerValue` bytes, row-major); release it
 *         with UnmapBasisPayload. nullptr for an empty payload.
 * \throws BasisFileError (Io) when it cannot be mapped.
 */
void* MapBasisPayload(const std::string& path, const BasisFileHeader& header);

/// Unmaps a mapping of MapBasisPayload (the length is in a registry); ignores other pointers.
void UnmapBasisPayload(void* payload);

/// Where a basis is kept.
enum class BasisStorage
{
  Automatic,
  InMemory,
  File
};

/// What ChooseBasisStorage decided and why (one sentence each).
struct StorageChoice
{
  /// InMemory or File; Automatic when nothing fits (Refusal says why a file would not do: the
  /// caller's memory error says the rest).
  BasisStorage Chosen = BasisStorage::InMemory;
  std::string Reason;
  std::string Refusal;
};

/**
 * The storage of a basis. AUTOMATIC: in memory when `inMemory` fits in `available`; else a file
 * when `inFile` (the same computation without the output basis in memory) fits and the disk
 * has `fileBytes` (BasisFileDiskBytes) free; else refused. IN_MEMORY and FILE are taken as
 * asked (FILE is still refused when the disk lacks room; the memory check of the solve itself
 * stays with ComputeBasis).
 * \param available Bytes of memory available (MemoryLimit or the system's).
 * \param diskFree Bytes free on the file's disk.
 * \param unwritable Why no file can be created in the file's directory (UnwritableDirectory),
 *        empty when one can: a file is then never chosen, and the refusal says why.
 */
StorageChoice ChooseBasisStorage(BasisStorage requested,
  std::uint64_t inMemory,
  std::uint64_t inFile,
  std::uint64_t available,
  std::uint64_t fileBytes,
  std::uint64_t diskFree,
  const std::string& unwritable = std::string());

/// Bytes free for an unprivileged user on the disk that holds `directory` (statvfs); the
/// largest value when unknown (creating the file then reports the fault).
std::uint64_t FreeDiskSpace(const std::string& directory);

/**
 * Why no file can be created in `directory` (it does not exist, is not a directory, is not
 * writable, or is on a read-only file system), or an empty string when one can: checked before
 * a solve that would write its basis there, so that a long solve does not end on an error.
 */
std::string UnwritableDirectory(const std::string& directory);

/// The directory of a path ("." for a bare name).
std::string DirectoryOf(const std::string& path);

/// A byte count for people: "1.5 GiB", "380.0 MiB", "12 bytes".
std::string ByteCount(std::uint64_t bytes);
} // namespace spectral

#endif
