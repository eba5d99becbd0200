// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The distributed engine (Filters/Spectral/Distributed/Solve.h) without VTK, under mpiexec: a mesh
// cut into one piece per process (each piece its own copy of the seam points) against the core's
// serial ComputeBasis of the whole mesh on every process. Built only with SLEPc; run with
// mpiexec -n 2 (label mpi).
// - SphereMatchesSerial, BoxMatchesSerial: the eigenvalues equal the serial ones to 1e-10
//   relative (above the zero ones, to 1e-10 of the largest); the harmonics gathered from the
//   owned rows are D-orthonormal (the serial mass) and satisfy the serial pencil to the
//   residual tolerance; every copy of a seam point has its owner's values.
// - OwnersFollowTheOwnerRule: the copies that own the seam points are those the one seam rule
//   names (Common/Seams.h, WeldPoints on the pieces in rank order with their ownership flags):
//   with the seam points flagged as ghosts on rank 0, rank 1 owns them; without flags, rank 0.
// - WindowMatchesSerial: a frequency window gives the serial window's pairs and first index.
// - OwnersAsTheGatherPath: the SLEPc numbering's owners are the copies the gather path's merge
//   counts (WeldPoints on all pieces' points in rank order), seams differing by round-off.
#include "Checks.h"
#include "Meshes.h"

#include "Basis.h"
#include "Common/Seams.h"
#include "Distributed/Petsc.h"
#include "Distributed/Solve.h"
#include "Solver/Acceptance.h"

#include <mpi.h>

#include <string>
#include <utility>
#include <vector>

using namespace spectral;
using namespace spectral::testing;

namespace
{
constexpr int Harmonics = 16;

/// One process's piece: its cells, its points (copies of mesh points), and which mesh point each
/// copies.
struct Piece
{
  TriangleMesh Mesh;
  std::vector<int> Source;
};

int Rank(MPI_Comm comm = MPI_COMM_WORLD)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

int Size(MPI_Comm comm = MPI_COMM_WORLD)
{
  int size = 1;
  MPI_Comm_size(comm, &size);
  return size;
}

//------------------------------------------------------------------------------
// The cells of `mesh` whose first corner's x coordinate falls in this rank's slab (of `size`
// slabs over the bounding box), with the points they use, renumbered.
Piece CutPiece(const TriangleMesh& mesh, int rank, int size)
{
  const bool volume = mesh.IsVolume();
  const Eigen::Index cells = volume ? mesh.Tets.rows() : mesh.Faces.rows();
  const int corners = volume ? 4 : 3;
  const double low = mesh.Vertices.col(0).minCoeff();
  const double high = mesh.Vertices.col(0).maxCoeff();
  Piece piece;
  std::vector<int> local(static_cast<std::size_t>(mesh.Vertices.rows()), -1);
  std::vector<std::vector<int>> kept;
  for (Eigen::Index c = 0; c < cells; ++c)
  {
    const auto corner = [&](int j) { return volume ? mesh.Tets(c, j) : mesh.Faces(c, j); };
    double x = 0.0;
    for (int j = 0; j < corners; ++j)
    {
      x += mesh.Vertices(corner(j), 0) / corners;
    }
    const int slab = std::min(size - 1, static_cast<int>((x - low) / (high - low) * size));
    if (slab != rank)
    {
      continue;
    }
    std::vector<int> ids;
    for (int j = 0; j < corners; ++j)
    {
      int& id = local[static_cast<std::size_t>(corner(j))];
      if (id < 0)
      {
        id = static_cast<int>(piece.Source.size());
        piece.Source.push_back(corner(j));
      }
      ids.push_back(id);
    }
    kept.push_back(ids);
  }
  piece.Mesh.Vertices.resize(static_cast<Eigen::Index>(piece.Source.size()), 3);
  for (std::size_t i = 0; i < piece.Source.size(); ++i)
  {
    piece.Mesh.Vertices.row(static_cast<Eigen::Index>(i)) = mesh.Vertices.row(piece.Source[i]);
  }
  Triangles& faces = piece.Mesh.Faces;
  Tetrahedra& tets = piece.Mesh.Tets;
  if (volume)
  {
    tets.resize(static_cast<Eigen::Index>(kept.size()), 4);
  }
  else
  {
    faces.resize(static_cast<Eigen::Index>(kept.size()), 3);
  }
  for (std::size_t c = 0; c < kept.size(); ++c)
  {
    for (int j = 0; j < corners; ++j)
    {
      if (volume)
      {
        tets(static_cast<Eigen::Index>(c), j) = kept[c][j];
      }
      else
      {
        faces(static_cast<Eigen::Index>(c), j) = kept[c][j];
      }
    }
  }
  return piece;
}

//------------------------------------------------------------------------------
// The harmonics of the whole mesh from the owned rows of every piece (summed over processes:
// each mesh point has one owned copy), and the largest difference between a copy's values and
// its point's.
DenseMatrix GatherOwned(const Piece& piece,
  const DistributedResult& result,
  Eigen::Index n,
  double& copyDifference)
{
  const Eigen::Index m = result.Harmonics.cols();
  DenseMatrix H = DenseMatrix::Zero(n, m);
  for (std::size_t i = 0; i < piece.Source.size(); ++i)
  {
    if (!result.Duplicate[i])
    {
      H.row(piece.Source[i]) = result.Harmonics.row(static_cast<Eigen::Index>(i));
    }
  }
  MPI_Allreduce(
    MPI_IN_PLACE, H.data(), static_cast<int>(H.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  copyDifference = 0.0;
  for (std::size_t i = 0; i < piece.Source.size(); ++i)
  {
    copyDifference = std::max(copyDifference,
      (H.row(piece.Source[i]) - result.Harmonics.row(static_cast<Eigen::Index>(i)))
        .cwiseAbs()
        .maxCoeff());
  }
  MPI_Allreduce(MPI_IN_PLACE, &copyDifference, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return H;
}

//------------------------------------------------------------------------------
void MatchesSerial(const TriangleMesh& mesh, const std::string& name)
{
  BasisOptions serialOptions;
  serialOptions.NumberOfHarmonics = Harmonics;
  const BasisResult serial = ComputeBasis(mesh, serialOptions);
  const Piece piece = CutPiece(mesh, Rank(), Size());
  DistributedOptions options;
  options.NumberOfHarmonics = Harmonics;
  const DistributedResult result = SolveDistributed(MPI_COMM_WORLD, piece.Mesh, options);
  Check(result.Eigenvalues.size() == Harmonics,
    name + ": " + std::to_string(Harmonics) + " eigenvalues");
  Check(result.GlobalPoints == mesh.Vertices.rows(),
    name + ": the pieces' seams merged to the mesh's " + std::to_string(mesh.Vertices.rows()) +
      " points");
  const double top = serial.Pairs.Eigenvalues.maxCoeff();
  double worst = 0.0;
  for (int k = 0; k < Harmonics && k < result.Eigenvalues.size(); ++k)
  {
    const double expected = serial.Pairs.Eigenvalues[k];
    worst = std::max(worst,
      std::abs(result.Eigenvalues[k] - expected) / std::max(std::abs(expected), 1e-10 * top));
  }
  CheckBelow(worst, 1e-10, name + ": eigenvalues equal the serial ComputeBasis's (relative)");

  double copies = 0.0;
  const DenseMatrix H = GatherOwned(piece, result, mesh.Vertices.rows(), copies);
  CheckBelow(copies, 0.0, name + ": every copy of a seam point has its owner's values");
  const PreparedMesh whole = PrepareMesh(mesh);
  const DiscreteLaplacian ops = AssembleLaplacian(whole, LaplacianOptions());
  const double gram = OrthonormalityError(H, ops.Mass);
  CheckBelow(gram, 1e-10, name + ": D-orthonormal in the serial mass");
  CheckBelow(std::abs(gram - result.OrthonormalityError),
    1e-12,
    name + ": the engine's Gram error is the one measured here");
  CheckBelow(RelativeResiduals(ops.Stiffness, ops.Mass, result.Eigenvalues, H).maxCoeff(),
    EigenOptions().ResidualTolerance,
    name + ": the serial pencil's relative residuals within the tolerance");
}

//------------------------------------------------------------------------------
void SphereMatchesSerial()
{
  MatchesSerial(Icosphere(3), "sphere");
}

//------------------------------------------------------------------------------
void BoxMatchesSerial()
{
  MatchesSerial(TetrahedralBox(1.0, 0.7, 0.5, 8, 6, 5), "box");
}

//------------------------------------------------------------------------------
// A frequency window: the pairs of the serial ComputeBasis's window, the same first index, from 0
// (the constant among them) and from above the first cluster.
void WindowMatchesSerial()
{
  const TriangleMesh mesh = Icosphere(3);
  const Piece piece = CutPiece(mesh, Rank(), Size());
  // The unit sphere's frequencies sqrt(l (l + 1)): 0, 1.41, 2.45, 3.46, 4.47.
  for (const std::pair<double, double>& window :
    { std::make_pair(0.0, 3.0), std::make_pair(2.0, 4.0) })
  {
    const std::string name =
      "window [" + std::to_string(window.first) + ", " + std::to_string(window.second) + ")";
    BasisOptions serialOptions;
    serialOptions.LowerFrequency = window.first;
    serialOptions.UpperFrequency = window.second;
    const BasisResult serial = ComputeBasis(mesh, serialOptions);
    DistributedOptions options;
    options.LowerFrequency = window.first;
    options.UpperFrequency = window.second;
    const DistributedResult result = SolveDistributed(MPI_COMM_WORLD, piece.Mesh, options);
    // The sphere is one component, which the window's harmonics represent whether or not the
    // window holds its zero eigenvalue: every point keeps its mass (the transform's weights).
    Check(result.Mass.size() > 0 && result.Mass.minCoeff() > 0.0,
      name + ": every point of the piece keeps its lumped mass");
    Check(result.Eigenvalues.size() == serial.Pairs.Eigenvalues.size(),
      name + ": as many pairs as the serial window (" + std::to_string(result.Eigenvalues.size()) +
        " vs " + std::to_string(serial.Pairs.Eigenvalues.size()) + ")");
    Check(result.FirstIndex == serial.FirstIndex,
      name + ": the same first index " + std::to_string(serial.FirstIndex));
    if (result.Eigenvalues.size() != serial.Pairs.Eigenvalues.size())
    {
      continue;
    }
    const double top = serial.Pairs.Eigenvalues.maxCoeff();
    CheckBelow((result.Eigenvalues - serial.Pairs.Eigenvalues).cwiseAbs().maxCoeff() / top,
      1e-10,
      name + ": eigenvalues equal the serial ones (relative to the largest)");
    double copies = 0.0;
    const DenseMatrix H = GatherOwned(piece, result, mesh.Vertices.rows(), copies);
    const DiscreteLaplacian ops = AssembleLaplacian(PrepareMesh(mesh), LaplacianOptions());
    CheckBelow(OrthonormalityError(H, ops.Mass), 1e-10, name + ": D-orthonormal");
  }
  DistributedOptions empty;
  empty.LowerFrequency = 1.5;
  empty.UpperFrequency = 1.6;
  CheckThrows<InvalidInput>([&]() { SolveDistributed(MPI_COMM_WORLD, piece.Mesh, empty); },
    "a window without eigenvalues is refused");
}

//------------------------------------------------------------------------------
// The copies that own the seam points, by rank, with and without ownership flags.
void OwnersFollowTheOwnerRule()
{
  const TriangleMesh mesh = Icosphere(2);
  const Piece piece = CutPiece(mesh, Rank(), Size());
  // Per mesh point: how many ranks hold it, the lowest that does, and the lowest that holds it
  // as its own when rank 0 flags its seam copies as ghosts.
  const Eigen::Index n = mesh.Vertices.rows();
  std::vector<int> holders(static_cast<std::size_t>(n), 0);
  std::vector<int> first(static_cast<std::size_t>(n), Size());
  std::vector<int> firstOwned(static_cast<std::size_t>(n), Size());
  for (const int source : piece.Source)
  {
    holders[static_cast<std::size_t>(source)] = 1;
    first[static_cast<std::size_t>(source)] = Rank();
  }
  MPI_Allreduce(
    MPI_IN_PLACE, holders.data(), static_cast<int>(n), MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, first.data(), static_cast<int>(n), MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  std::vector<unsigned char> flags(piece.Source.size(), 1);
  for (std::size_t i = 0; i < piece.Source.size(); ++i)
  {
    const std::size_t j = static_cast<std::size_t>(piece.Source[i]);
    flags[i] = Rank() == 0 && holders[j] > 1 ? 0 : 1;
    firstOwned[j] = flags[i] ? Rank() : Size();
  }
  MPI_Allreduce(
    MPI_IN_PLACE, firstOwned.data(), static_cast<int>(n), MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  for (const bool flagged : { false, true })
  {
    DistributedOptions options;
    options.NumberOfHarmonics = 4;
    if (flagged)
    {
      options.OwnedPoints = flags;
    }
    const DistributedResult result = SolveDistributed(MPI_COMM_WORLD, piece.Mesh, options);
    // The rule of Seams.h: the first copy in rank order that its piece holds as its own owns a
    // point (the first copy when none does).
    long long wrong = 0;
    long long seam = 0;
    for (std::size_t i = 0; i < piece.Source.size(); ++i)
    {
      const std::size_t j = static_cast<std::size_t>(piece.Source[i]);
      if (holders[j] < 2)
      {
        continue;
      }
      ++seam;
      const int owner = flagged && firstOwned[j] < Size() ? firstOwned[j] : first[j];
      wrong += (!result.Duplicate[i]) == (owner == Rank()) ? 0 : 1;
    }
    MPI_Allreduce(MPI_IN_PLACE, &wrong, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &seam, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
    const std::string how = flagged ? "seam flagged as ghosts on rank 0" : "no flags";
    Check(seam > 0, how + ": the pieces share seam points (" + std::to_string(seam) + " copies)");
    Check(wrong == 0,
      how + ": owners as the owner rule names them (" + std::to_string(wrong) + " wrong)");
    Check(result.GlobalPoints == n, how + ": every point numbered once");
  }
}

//------------------------------------------------------------------------------
// The SLEPc numbering's owners against the gather path's merge (vtkManifoldHarmonicsParallel::
// GatherAndMerge: WeldPoints on every piece's points in rank order, with their ownership flags,
// the copy Counted owns), on pieces whose seam copies differ by round-off (as the Sphere
// source's pieces do) and whose seam is flagged as ghosts on rank 0.
void OwnersAsTheGatherPath()
{
  const TriangleMesh mesh = Icosphere(3);
  Piece piece = CutPiece(mesh, Rank(), Size());
  // Round-off on this rank's copies, and the seam (points another rank holds) flagged on rank 0.
  std::vector<int> holders(static_cast<std::size_t>(mesh.Vertices.rows()), 0);
  for (const int source : piece.Source)
  {
    holders[static_cast<std::size_t>(source)] = 1;
  }
  MPI_Allreduce(MPI_IN_PLACE,
    holders.data(),
    static_cast<int>(holders.size()),
    MPI_INT,
    MPI_SUM,
    MPI_COMM_WORLD);
  std::vector<unsigned char> flags(piece.Source.size(), 1);
  for (std::size_t i = 0; i < piece.Source.size(); ++i)
  {
    piece.Mesh.Vertices.row(static_cast<Eigen::Index>(i)) *= 1.0 + (Rank() + 1) * 1e-15;
    flags[i] = Rank() == 0 && holders[static_cast<std::size_t>(piece.Source[i])] > 1 ? 0 : 1;
  }
  DistributedOptions options;
  options.NumberOfHarmonics = 4;
  options.OwnedPoints = flags;
  const DistributedResult result = SolveDistributed(MPI_COMM_WORLD, piece.Mesh, options);

  // The gather path's merge of all pieces' points (row-major coordinates) and flags.
  const int count = static_cast<int>(piece.Source.size());
  std::vector<int> counts(static_cast<std::size_t>(Size()));
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::vector<int> offsets(counts.size() + 1, 0);
  for (std::size_t r = 0; r < counts.size(); ++r)
  {
    offsets[r + 1] = offsets[r] + counts[r];
  }
  std::vector<double> xyz(3 * static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      xyz[3 * i + c] = piece.Mesh.Vertices(i, c);
    }
  }
  std::vector<int> counts3(counts.size());
  std::vector<int> offsets3(counts.size());
  for (std::size_t r = 0; r < counts.size(); ++r)
  {
    counts3[r] = 3 * counts[r];
    offsets3[r] = 3 * offsets[r];
  }
  std::vector<double> allXyz(3 * static_cast<std::size_t>(offsets.back()));
  std::vector<unsigned char> allFlags(static_cast<std::size_t>(offsets.back()));
  MPI_Allgatherv(xyz.data(),
    3 * count,
    MPI_DOUBLE,
    allXyz.data(),
    counts3.data(),
    offsets3.data(),
    MPI_DOUBLE,
    MPI_COMM_WORLD);
  MPI_Allgatherv(flags.data(),
    count,
    MPI_UNSIGNED_CHAR,
    allFlags.data(),
    counts.data(),
    offsets.data(),
    MPI_UNSIGNED_CHAR,
    MPI_COMM_WORLD);
  const Welding gathered =
    WeldPoints(allXyz.data(), offsets.back(), nullptr, DefaultSeamTolerance, allFlags);
  long long differ = 0;
  for (int i = 0; i < count; ++i)
  {
    differ +=
      gathered.Owns(offsets[Rank()] + i) == !result.Duplicate[static_cast<std::size_t>(i)] ? 0 : 1;
  }
  MPI_Allreduce(MPI_IN_PLACE, &differ, 1, MPI_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  Check(gathered.Merged() && static_cast<long long>(gathered.First.size()) == result.GlobalPoints,
    "the gather path's merge and the SLEPc numbering find the same " +
      std::to_string(result.GlobalPoints) + " points");
  Check(differ == 0,
    "every copy owns its point in the SLEPc numbering exactly when the gather path counts it (" +
      std::to_string(differ) + " differ)");
}

const Case Cases[] = {
  { "SphereMatchesSerial", SphereMatchesSerial },
  { "BoxMatchesSerial", BoxMatchesSerial },
  { "OwnersFollowTheOwnerRule", OwnersFollowTheOwnerRule },
  { "WindowMatchesSerial", WindowMatchesSerial },
  { "OwnersAsTheGatherPath", OwnersAsTheGatherPath },
};
} // namespace

int main(int argc, char* argv[])
{
  MPI_Init(&argc, &argv);
  int status = RunCases(argc, argv, Cases);
  // Every process's verdict: a failure on any fails the test on all.
  MPI_Allreduce(MPI_IN_PLACE, &status, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  // SLEPc registered its finalization at exit when it initialized MPI itself; here MPI is ours.
  PetscBool slepc = PETSC_FALSE;
  SlepcInitialized(&slepc);
  if (slepc)
  {
    SlepcFinalize();
  }
  MPI_Finalize();
  return status;
}
