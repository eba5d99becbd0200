// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsBasisFile.h
 * @brief Private: the file-backed basis of vtkManifoldHarmonicBasis (Storage FILE): which options
 *        a file records, the choice between memory and a file, reuse of a named file, and the
 *        output arrays of a file (the harmonics as a read-only mapping of its payload).
 *
 * The format, the writer and the mapping are the core's (Spectral/Common/BasisFile.h); this
 * file is what ties them to the filter's properties and arrays. Tested by
 * Filters/Testing/Cxx/TestBasisFile.cxx.
 */
#ifndef vtkManifoldHarmonicsBasisFile_h
#define vtkManifoldHarmonicsBasisFile_h

#include "Spectral/Basis.h"
#include "Spectral/Common/BasisFile.h"

#include <string>

class vtkDataArray;
class vtkDataSet;
class vtkManifoldHarmonicBasis;

namespace vtkManifoldHarmonicsBasisFile
{
/// The options of `self` that change its basis, one "Name=value" a line (the file's Options).
std::string OptionsText(vtkManifoldHarmonicBasis* self);

/// The digest of the mesh a basis is computed on (spectral::MeshDigest).
std::uint64_t Digest(const spectral::TriangleMesh& mesh);

/// A fresh name for a temporary basis file: $TMPDIR (or /tmp)/ManifoldHarmonics-<pid>-<n>.mhb.
std::string TemporaryPath();

/// What the filter plans to do with a file.
struct Plan
{
  /// Empty: the basis stays in memory.
  std::string Path;
  /// Whether Path is a temporary file (unlinked once mapped).
  bool Temporary = false;
  /// Whether the named file holds this basis already (no solve).
  bool Reuse = false;
  /// Whether the basis is streamed into the file (spectral::BasisSink: never whole in memory);
  /// false for a frequency window, which is computed in memory and then written.
  bool Streamed = false;
  /// The memory of the file's writer beside a solve streamed into it
  /// (spectral::BasisFileWriterBytes; 0 when not streamed): the solve plans in the rest of a
  /// MemoryLimit.
  std::uint64_t WriterBytes = 0;
  /// The checked header of the reused file.
  spectral::BasisFileHeader Header;
  /// The digest of the mesh and the options text that a new file records.
  std::uint64_t Digest = 0;
  std::string Options;
  /// Storage AUTOMATIC when nothing fits: why a file would not do either (the solve's memory
  /// error appends it).
  std::string Refusal;
};

/**
 * Where the basis of `mesh` (`numPts` output points) goes, from the filter's Storage and
 * BasisFileName and the core's `options` (harmonics, band size, precision, MemoryLimit); sets the
 * filter's StorageUsed and StorageReason through `used` and `reason`. \return false after an error
 * it reported (a foreign file under the name, no room on the disk); warnings for a file that cannot
 * be reused (what differed) and for a file chosen by AUTOMATIC.
 */
bool PlanStorage(vtkManifoldHarmonicBasis* self,
  const spectral::BasisOptions& options,
  const spectral::TriangleMesh& mesh,
  long long numPts,
  Plan& plan,
  int& used,
  std::string& reason);

/// Names the components of a harmonics array Phi_0, Phi_1, ... (every harmonics array).
void NameHarmonics(vtkDataArray* harmonics);

/// The eigenvalues and the two quality figures as field data (every basis output).
void AddSpectrumArrays(vtkDataSet* output,
  const double* eigenvalues,
  int m,
  double backwardError,
  double residual);

/**
 * The arrays of a basis file on `output`: the harmonics mapping its payload read-only (a
 * vtkDoubleArray or vtkFloatArray whose free function unmaps it), the mass, the eigenvalues and
 * the figures of its header. \throws spectral::BasisFileError when it cannot be mapped.
 */
void AddFileArrays(vtkDataSet* output,
  const std::string& path,
  const spectral::BasisFileHeader& header);
} // namespace vtkManifoldHarmonicsBasisFile

#endif
