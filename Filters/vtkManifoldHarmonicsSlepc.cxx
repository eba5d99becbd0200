// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "vtkManifoldHarmonicsSlepc.h"

#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointLocator.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"

#include "Spectral/Basis.h"
#include "Spectral/Common/Eigenvalues.h"
#include "Spectral/Operators/Operators.h"
#include "Spectral/Solver/EigenSolver.h"
#include "Spectral/Solver/Verification.h"

#include <slepceps.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

namespace
{
// Eigenvalues per spectrum slicing run: the solve checks the abort flag and reports progress
// between runs. Each run adds the factorizations at its ends.
constexpr int SliceHarmonics = 200;
// Eigenvectors whose D-products a process keeps at once (owned rows by GramColumns) to take
// their Gram matrix against the written rows: memory against passes over those rows.
constexpr int GramColumns = 32;
// The share of an eigenvector's squared D-norm below which its part on a connected component is
// round-off of the Krylov vectors and set to zero (Constants::Deflate): a part of D-norm below
// 1e-8, the pair tolerance (Verification.h), changes none of the pair checks.
constexpr double NegligibleShare = 1e-16;

//------------------------------------------------------------------------------
// PETSc errors: the first message of an error (where it arose), recorded by our handler, and
// turned into an exception with what to change.
std::string& FirstError()
{
  static thread_local std::string message;
  return message;
}

PetscErrorCode RecordError(MPI_Comm,
  int,
  const char* function,
  const char*,
  PetscErrorCode code,
  PetscErrorType type,
  const char* message,
  void*)
{
  if (type == PETSC_ERROR_INITIAL && FirstError().empty())
  {
    FirstError() =
      std::string(message ? message : "") + " (in " + (function ? function : "?") + ")";
  }
  return code;
}

// What to change for the MUMPS errors a user can do something about (MUMPS users' guide,
// section "Error diagnostics").
std::string Advice(const std::string& message)
{
  for (const char* code : { "INFOG(1)=-8",
         "INFOG(1)=-9",
         "INFOG(1)=-11",
         "INFOG(1)=-14",
         "INFOG(1)=-15",
         "INFOG(1)=-17",
         "INFOG(1)=-20" })
  {
    if (message.find(code) != std::string::npos)
    {
      return " MUMPS's estimated workspace was too small: increase it with SlepcOptions "
             "\"-st_mat_mumps_icntl_14 100\" (percent of extra workspace; MUMPS's default is "
             "20, raise further if it fails again).";
    }
  }
  if (message.find("INFOG(1)=-13") != std::string::npos)
  {
    return " MUMPS could not allocate its factor: run on more nodes (more memory), or compute "
           "fewer harmonics.";
  }
  if (message.find("INFOG(1)=-38") != std::string::npos)
  {
    return " The parallel ordering of this MUMPS build failed: use the sequential one, "
           "SlepcOptions \"-st_mat_mumps_icntl_28 1\".";
  }
  if (message.find("INFOG(1)=-10") != std::string::npos)
  {
    return " A shift fell on an eigenvalue (singular factorization): change NumberOfHarmonics "
           "by one, or pass \"-eps_krylovschur_partitions\" differently.";
  }
  return "";
}

[[noreturn]] void Fail(PetscErrorCode code, const char* call)
{
  std::string message = FirstError();
  FirstError().clear();
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  std::ostringstream out;
  out << "SLEPc/PETSc error " << code << " (" << (text ? text : "unknown") << ") in " << call;
  if (!message.empty())
  {
    out << ": " << message << ".";
  }
  out << Advice(message);
  throw std::runtime_error(out.str());
}

#define MH_PETSC(call)                                                                             \
  do                                                                                               \
  {                                                                                                \
    const PetscErrorCode mhCode = (call);                                                          \
    if (mhCode != 0)                                                                               \
    {                                                                                              \
      Fail(mhCode, #call);                                                                         \
    }                                                                                              \
  } while (false)

// A PETSc object destroyed at the end of its scope.
template<typename T, PetscErrorCode (*Destroy)(T*)>
struct Owned
{
  T Object = nullptr;
  Owned() = default;
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned()
  {
    if (this->Object)
    {
      Destroy(&this->Object);
    }
  }
};
using OwnedMat = Owned<Mat, MatDestroy>;
using OwnedVec = Owned<Vec, VecDestroy>;
using OwnedKSP = Owned<KSP, KSPDestroy>;
using OwnedEPS = Owned<EPS, EPSDestroy>;
using OwnedIS = Owned<IS, ISDestroy>;
using OwnedScatter = Owned<VecScatter, VecScatterDestroy>;

// For the duration of a solve: our error handler (no tracebacks printed, the message kept) and
// an options database of our own (the solver's settings and the user's), so that nothing leaks
// into later solves or other PETSc users of the process.
class Session
{
public:
  explicit Session(const std::string& options)
  {
    PetscPushErrorHandler(RecordError, nullptr);
    FirstError().clear();
    MH_PETSC(PetscOptionsCreate(&this->Options));
    // The inertia of MUMPS needs null pivot detection, ICNTL(24) = 1, and in parallel
    // ICNTL(13) = 1 (no ScaLAPACK root node). The prefix st_ is the one of the ST's
    // factorization and of our own inertia probes.
    MH_PETSC(
      PetscOptionsInsertString(this->Options, "-st_mat_mumps_icntl_13 1 -st_mat_mumps_icntl_24 1"));
    MH_PETSC(PetscOptionsInsertString(this->Options, options.c_str()));
    MH_PETSC(PetscOptionsPush(this->Options));
  }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session()
  {
    PetscOptionsPop();
    PetscOptionsDestroy(&this->Options);
    PetscPopErrorHandler();
  }

private:
  PetscOptions Options = nullptr;
};

//------------------------------------------------------------------------------
// SLEPc (and PETSc, and MPI when nobody initialized it) once per process.
void Initialize()
{
  PetscBool initialized = PETSC_FALSE;
  SlepcInitialized(&initialized);
  if (initialized)
  {
    return;
  }
  int mpi = 0;
  MPI_Initialized(&mpi);
  if (SlepcInitializeNoArguments() != 0)
  {
    throw std::runtime_error("SLEPc could not be initialized.");
  }
  // The host application (ParaView) handles signals itself.
  PetscPopSignalHandler();
  if (!mpi)
  {
    // SLEPc initialized MPI: finalize both at exit. When the application initialized MPI it
    // also finalizes it, and SLEPc stays initialized to the end (finalizing it after MPI fails).
    std::atexit([]() { SlepcFinalize(); });
  }
}

//------------------------------------------------------------------------------
// Points that another piece may hold: those on a facet (an edge of a triangle, a face of a
// tetrahedron) that not exactly two cells of this piece share (a seam between pieces, a
// boundary of the mesh, a non-manifold facet).
std::vector<int> BorderPoints(const spectral::TriangleMesh& mesh)
{
  const bool volume = mesh.IsVolume();
  const Eigen::Index cells = volume ? mesh.Tets.rows() : mesh.Faces.rows();
  const int corners = volume ? 4 : 3;
  // Each facet as its sorted point ids (the third -1 for an edge), one entry per cell using it.
  std::vector<std::array<int, 3>> facets;
  facets.reserve(static_cast<std::size_t>(cells * corners));
  for (Eigen::Index c = 0; c < cells; ++c)
  {
    for (int left = 0; left < corners; ++left)
    {
      // A facet of a tetrahedron leaves one corner out; an edge of a triangle, the opposite one.
      std::array<int, 3> facet = { -1, -1, -1 };
      int k = 0;
      for (int j = 0; j < corners; ++j)
      {
        if (j != left)
        {
          facet[k++] = volume ? mesh.Tets(c, j) : mesh.Faces(c, j);
        }
      }
      std::sort(facet.begin(), facet.begin() + k);
      facets.push_back(facet);
    }
  }
  std::sort(facets.begin(), facets.end());
  std::vector<char> border(static_cast<std::size_t>(mesh.Vertices.rows()), 0);
  for (std::size_t i = 0; i < facets.size();)
  {
    std::size_t j = i;
    while (j < facets.size() && facets[j] == facets[i])
    {
      ++j;
    }
    if (j - i != 2)
    {
      for (const int point : facets[i])
      {
        if (point >= 0)
        {
          border[point] = 1;
        }
      }
    }
    i = j;
  }
  std::vector<int> points;
  for (std::size_t i = 0; i < border.size(); ++i)
  {
    if (border[i])
    {
      points.push_back(static_cast<int>(i));
    }
  }
  return points;
}

//------------------------------------------------------------------------------
// Global numbers of the used points of this piece (see the header, step 1).
struct Numbering
{
  /// For each used point of the piece: its global number and whether this process owns it.
  std::vector<PetscInt> Global;
  std::vector<char> Owned;
  PetscInt OwnedCount = 0;
  PetscInt Total = 0;
};

Numbering NumberPoints(MPI_Comm comm,
  const spectral::TriangleMesh& mesh,
  const double bounds[6],
  bool weld,
  double tolerance)
{
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int n = static_cast<int>(mesh.Vertices.rows());

  // Every process receives the border points of all, in rank order.
  const std::vector<int> border = BorderPoints(mesh);
  const int count = static_cast<int>(border.size());
  std::vector<int> counts(size);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<int> offsets(size + 1, 0);
  std::partial_sum(counts.begin(), counts.end(), offsets.begin() + 1);
  std::vector<double> coordinates(3 * static_cast<std::size_t>(count));
  for (int b = 0; b < count; ++b)
  {
    for (int c = 0; c < 3; ++c)
    {
      coordinates[3 * b + c] = mesh.Vertices(border[b], c);
    }
  }
  std::vector<double> all(3 * static_cast<std::size_t>(offsets[size]));
  std::vector<int> counts3(size);
  std::vector<int> offsets3(size);
  for (int r = 0; r < size; ++r)
  {
    counts3[r] = 3 * counts[r];
    offsets3[r] = 3 * offsets[r];
  }
  MPI_Allgatherv(coordinates.data(),
    3 * count,
    MPI_DOUBLE,
    all.data(),
    counts3.data(),
    offsets3.data(),
    MPI_DOUBLE,
    comm);

  // The same merge on every process (WeldPoints): the first (lowest rank) holder of a point owns
  // it. Without welding (a serial run with WeldSeams off) every point is its own.
  std::vector<int> first(static_cast<std::size_t>(offsets[size]));
  {
    const vtkManifoldHarmonicsParallel::Welding welding = weld
      ? vtkManifoldHarmonicsParallel::WeldPoints(all.data(), offsets[size], bounds, tolerance)
      : vtkManifoldHarmonicsParallel::Welding();
    for (int g = 0; g < offsets[size]; ++g)
    {
      first[g] = weld ? static_cast<int>(welding.First[welding.Map[g]]) : g;
    }
  }

  Numbering numbering;
  numbering.Owned.assign(static_cast<std::size_t>(n), 1);
  for (int b = 0; b < count; ++b)
  {
    // Owned by the first holder; a copy in the same piece (coincident points) is not.
    numbering.Owned[border[b]] = first[offsets[rank] + b] == offsets[rank] + b ? 1 : 0;
  }
  numbering.OwnedCount =
    static_cast<PetscInt>(std::count(numbering.Owned.begin(), numbering.Owned.end(), 1));
  long long owned = numbering.OwnedCount;
  long long start = 0;
  long long total = 0;
  MPI_Exscan(&owned, &start, 1, MPI_LONG_LONG, MPI_SUM, comm);
  MPI_Allreduce(&owned, &total, 1, MPI_LONG_LONG, MPI_SUM, comm);
  if (rank == 0)
  {
    start = 0;
  }
  if (total > std::numeric_limits<PetscInt>::max())
  {
    throw std::runtime_error("the surface has " + std::to_string(total) +
      " points, more than this PETSc build's 32-bit indices address");
  }
  numbering.Total = static_cast<PetscInt>(total);
  numbering.Global.assign(static_cast<std::size_t>(n), -1);
  PetscInt next = static_cast<PetscInt>(start);
  for (int i = 0; i < n; ++i)
  {
    if (numbering.Owned[i])
    {
      numbering.Global[i] = next++;
    }
  }

  // The owners' numbers of the border points, for the copies held by other processes.
  std::vector<PetscInt> mine(static_cast<std::size_t>(count));
  for (int b = 0; b < count; ++b)
  {
    mine[b] = numbering.Global[border[b]];
  }
  std::vector<PetscInt> numbers(static_cast<std::size_t>(offsets[size]));
  MPI_Allgatherv(
    mine.data(), count, MPIU_INT, numbers.data(), counts.data(), offsets.data(), MPIU_INT, comm);
  for (int b = 0; b < count; ++b)
  {
    if (!numbering.Owned[border[b]])
    {
      numbering.Global[border[b]] = numbers[first[offsets[rank] + b]];
    }
  }
  return numbering;
}

//------------------------------------------------------------------------------
// The connected components of the whole mesh and what the solve needs of them: the constant
// harmonic of each, 1_j / sqrt(mass_j), is an exact null vector of Q (Q 1 = 0: the rows of the
// cotan and P1 stiffness sum to zero), so the solve writes those with eigenvalue 0 itself and
// keeps SLEPc's pairs only in their D-orthogonal complement (step 3 of the header).
struct Components
{
  /// The component (0..Count-1) of each used point of the piece.
  std::vector<int> Label;
  int Count = 0;
  /// Per component, summed over all processes' owned points: the lumped mass (the solve's
  /// units; 1_j^T D 1_j for the consistent mass too, whose rows sum to the lumped one) and the
  /// number of points.
  std::vector<double> Mass;
  std::vector<long long> Points;
  /// The components by decreasing number of points (ties by label): the order of their zero
  /// eigenvalues, as the built-in solver's (Components.cxx, Smallest).
  std::vector<int> Order;
};

/**
 * The connected components of the distributed mesh, without gathering it (collective). Each
 * process labels the components of its own cells (spectral::LabelComponents). Only border
 * points (BorderPoints) can be held by another piece, or merged with a coincident copy in the
 * same piece, so they are the only links between local components: every process receives the
 * pairs (global point number, local component) of every process's border points (O(seam), as
 * NumberPoints receives their coordinates), unites the local components that share a point,
 * the same way on every process, and numbers the components by their first local component in
 * rank order. Then the components' masses (from `lumped`, the distributed lumped mass) and
 * point counts are summed over the owned points of all processes.
 */
Components DistributedComponents(MPI_Comm comm,
  const spectral::TriangleMesh& mesh,
  const Numbering& numbering,
  Vec lumped)
{
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int n = static_cast<int>(mesh.Vertices.rows());

  // Local components, numbered by their first point.
  const spectral::ComponentLabels local = spectral::LabelComponents(mesh);
  const int localCount = local.Count;
  int offset = 0;
  int nodes = 0;
  MPI_Exscan(&localCount, &offset, 1, MPI_INT, MPI_SUM, comm);
  MPI_Allreduce(&localCount, &nodes, 1, MPI_INT, MPI_SUM, comm);
  if (rank == 0)
  {
    offset = 0;
  }

  // Every process's links (global point number, local component + offset), in rank order.
  const std::vector<int> border = BorderPoints(mesh);
  std::vector<long long> links;
  links.reserve(2 * border.size());
  for (const int point : border)
  {
    links.push_back(numbering.Global[point]);
    links.push_back(offset + local.Label[point]);
  }
  const int count = static_cast<int>(links.size());
  std::vector<int> counts(size);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<int> displacements(size + 1, 0);
  std::partial_sum(counts.begin(), counts.end(), displacements.begin() + 1);
  std::vector<long long> all(static_cast<std::size_t>(displacements[size]));
  MPI_Allgatherv(links.data(),
    count,
    MPI_LONG_LONG,
    all.data(),
    counts.data(),
    displacements.data(),
    MPI_LONG_LONG,
    comm);
  // The local components (nodes) joined by a point they share: the graph of those links,
  // labelled in the order of the nodes, the same on every process.
  std::vector<std::pair<long long, int>> byPoint(all.size() / 2);
  for (std::size_t l = 0; l < byPoint.size(); ++l)
  {
    byPoint[l] = { all[2 * l], static_cast<int>(all[2 * l + 1]) };
  }
  std::sort(byPoint.begin(), byPoint.end());
  std::vector<Eigen::Triplet<double>> joined;
  for (std::size_t l = 1; l < byPoint.size(); ++l)
  {
    if (byPoint[l].first == byPoint[l - 1].first)
    {
      joined.emplace_back(byPoint[l].second, byPoint[l - 1].second, 1.0);
      joined.emplace_back(byPoint[l - 1].second, byPoint[l].second, 1.0);
    }
  }
  spectral::SparseMatrix graph(nodes, nodes);
  graph.setFromTriplets(joined.begin(), joined.end());
  const spectral::ComponentLabels global = spectral::LabelComponents(graph);
  Components components;
  components.Count = global.Count;
  components.Label.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
  {
    components.Label[i] = global.Label[offset + local.Label[i]];
  }

  // Masses and point counts over the owned points of all processes.
  components.Mass.assign(static_cast<std::size_t>(components.Count), 0.0);
  components.Points.assign(static_cast<std::size_t>(components.Count), 0);
  PetscInt first = 0;
  MH_PETSC(VecGetOwnershipRange(lumped, &first, nullptr));
  const PetscScalar* mass = nullptr;
  MH_PETSC(VecGetArrayRead(lumped, &mass));
  for (int i = 0; i < n; ++i)
  {
    if (numbering.Owned[i])
    {
      components.Mass[components.Label[i]] += mass[numbering.Global[i] - first];
      ++components.Points[components.Label[i]];
    }
  }
  MH_PETSC(VecRestoreArrayRead(lumped, &mass));
  MPI_Allreduce(
    MPI_IN_PLACE, components.Mass.data(), components.Count, MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(
    MPI_IN_PLACE, components.Points.data(), components.Count, MPI_LONG_LONG, MPI_SUM, comm);
  components.Order.resize(static_cast<std::size_t>(components.Count));
  std::iota(components.Order.begin(), components.Order.end(), 0);
  std::stable_sort(components.Order.begin(),
    components.Order.end(),
    [&components](int a, int b) { return components.Points[a] > components.Points[b]; });
  return components;
}

//------------------------------------------------------------------------------
// Deflation of the constants from distributed vectors, on the owned rows: `label` is the
// component of each owned row, `lumped` the lumped mass of each. D 1_j is the lumped mass on
// component j (for the consistent mass too), so c_j^T D x = sum_{i in j} lumped_i x_i /
// sqrt(mass_j), and x - sum_j (c_j^T D x) c_j subtracts from x its mass-weighted mean on
// every component.
class Constants
{
public:
  Constants(const Components& components, std::vector<int> label, Vec lumped)
    : Parts(components)
    , Label(std::move(label))
  {
    const PetscScalar* mass = nullptr;
    MH_PETSC(VecGetArrayRead(lumped, &mass));
    this->Lumped.assign(mass, mass + this->Label.size());
    MH_PETSC(VecRestoreArrayRead(lumped, &mass));
    this->Comm = PetscObjectComm(reinterpret_cast<PetscObject>(lumped));
  }

  /// x = c_j, the constant harmonic of component j.
  void Set(Vec x, int j) const
  {
    PetscScalar* values = nullptr;
    MH_PETSC(VecGetArray(x, &values));
    const double value = 1.0 / std::sqrt(this->Parts.Mass[j]);
    for (std::size_t r = 0; r < this->Label.size(); ++r)
    {
      values[r] = this->Label[r] == j ? value : 0.0;
    }
    MH_PETSC(VecRestoreArray(x, &values));
  }

  /**
   * Deflates x (collective): returns the share of its squared norm (in the lumped mass) that
   * lies in the span of the constants, and unless that is above `keepBelow`, removes its
   * components along every c_j and sets it to zero on the components that hold less than
   * NegligibleShare of its squared norm. The operators do not couple components, so an
   * eigenvector is zero off the components whose eigenvalue it has: what a Krylov vector holds
   * there is round-off, which on debris rows (entries 1e12 times the others') would dominate
   * its residual.
   */
  double Deflate(Vec x, double keepBelow) const
  {
    const std::size_t count = static_cast<std::size_t>(this->Parts.Count);
    // Per component: sum lumped_i x_i, then sum lumped_i x_i^2.
    std::vector<double> sums(2 * count, 0.0);
    PetscScalar* values = nullptr;
    MH_PETSC(VecGetArray(x, &values));
    for (std::size_t r = 0; r < this->Label.size(); ++r)
    {
      const double weighted = this->Lumped[r] * values[r];
      sums[this->Label[r]] += weighted;
      sums[count + this->Label[r]] += weighted * values[r];
    }
    MPI_Allreduce(
      MPI_IN_PLACE, sums.data(), static_cast<int>(2 * count), MPI_DOUBLE, MPI_SUM, this->Comm);
    double removed = 0.0;
    double total = 0.0;
    for (std::size_t j = 0; j < count; ++j)
    {
      removed += sums[j] * sums[j] / this->Parts.Mass[j];
      total += sums[count + j];
    }
    const double share = total > 0.0 ? removed / total : 1.0;
    if (!(share > keepBelow))
    {
      for (std::size_t r = 0; r < this->Label.size(); ++r)
      {
        const int j = this->Label[r];
        values[r] = sums[count + j] > NegligibleShare * total
          ? values[r] - sums[j] / this->Parts.Mass[j]
          : 0.0;
      }
    }
    MH_PETSC(VecRestoreArray(x, &values));
    return share;
  }

private:
  const Components& Parts;
  std::vector<int> Label;
  std::vector<double> Lumped;
  MPI_Comm Comm = MPI_COMM_NULL;
};

//------------------------------------------------------------------------------
// Makes the entry of largest magnitude of x positive, over all processes, as the built-in
// solver does (EigenSolver.cxx, NormalizeSigns; a tie keeps the sign). Collective.
void NormalizeSign(Vec x)
{
  PetscReal largest = 0.0;
  PetscReal smallest = 0.0;
  MH_PETSC(VecMax(x, nullptr, &largest));
  MH_PETSC(VecMin(x, nullptr, &smallest));
  if (-smallest > largest)
  {
    MH_PETSC(VecScale(x, -1.0));
  }
}

//------------------------------------------------------------------------------
// Tells PETSc (and so MUMPS) that a matrix is symmetric, for good.
void MarkSymmetric(Mat matrix)
{
  MH_PETSC(MatSetOption(matrix, MAT_SYMMETRIC, PETSC_TRUE));
  MH_PETSC(MatSetOption(matrix, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
}

//------------------------------------------------------------------------------
// A distributed AIJ matrix of `local` (a matrix on the piece's used points) added up by global
// numbers, exactly preallocated (a MATPREALLOCATOR pass over the same entries).
void AddEntries(Mat matrix, const spectral::SparseMatrix& local, const std::vector<PetscInt>& ids)
{
  std::vector<PetscInt> rows;
  std::vector<PetscScalar> values;
  for (int j = 0; j < local.outerSize(); ++j)
  {
    rows.clear();
    values.clear();
    for (spectral::SparseMatrix::InnerIterator it(local, j); it; ++it)
    {
      rows.push_back(ids[it.row()]);
      values.push_back(it.value());
    }
    const PetscInt column = ids[j];
    MH_PETSC(MatSetValues(matrix,
      static_cast<PetscInt>(rows.size()),
      rows.data(),
      1,
      &column,
      values.data(),
      ADD_VALUES));
  }
}

void CreateMatrix(MPI_Comm comm,
  const spectral::SparseMatrix& local,
  const Numbering& numbering,
  OwnedMat& out)
{
  OwnedMat preallocator;
  MH_PETSC(MatCreate(comm, &preallocator.Object));
  MH_PETSC(MatSetSizes(preallocator.Object,
    numbering.OwnedCount,
    numbering.OwnedCount,
    numbering.Total,
    numbering.Total));
  MH_PETSC(MatSetType(preallocator.Object, MATPREALLOCATOR));
  MH_PETSC(MatSetUp(preallocator.Object));
  AddEntries(preallocator.Object, local, numbering.Global);
  MH_PETSC(MatAssemblyBegin(preallocator.Object, MAT_FINAL_ASSEMBLY));
  MH_PETSC(MatAssemblyEnd(preallocator.Object, MAT_FINAL_ASSEMBLY));

  MH_PETSC(MatCreate(comm, &out.Object));
  MH_PETSC(MatSetSizes(
    out.Object, numbering.OwnedCount, numbering.OwnedCount, numbering.Total, numbering.Total));
  MH_PETSC(MatSetType(out.Object, MATAIJ));
  MH_PETSC(MatPreallocatorPreallocate(preallocator.Object, PETSC_TRUE, out.Object));
  AddEntries(out.Object, local, numbering.Global);
  MH_PETSC(MatAssemblyBegin(out.Object, MAT_FINAL_ASSEMBLY));
  MH_PETSC(MatAssemblyEnd(out.Object, MAT_FINAL_ASSEMBLY));
  MarkSymmetric(out.Object);
}

//------------------------------------------------------------------------------
// The number of eigenvalues below `shift`: the negative inertia of an LDL^T factorization of
// Q - shift D by MUMPS, with the options of the ST's factorization (prefix st_).
PetscInt CountBelow(Mat Q, Mat D, double shift)
{
  OwnedMat shifted;
  MH_PETSC(MatDuplicate(Q, MAT_COPY_VALUES, &shifted.Object));
  MH_PETSC(MatAXPY(shifted.Object, -shift, D, SUBSET_NONZERO_PATTERN));
  MarkSymmetric(shifted.Object);
  OwnedKSP ksp;
  MH_PETSC(KSPCreate(PetscObjectComm(reinterpret_cast<PetscObject>(Q)), &ksp.Object));
  MH_PETSC(KSPSetOptionsPrefix(ksp.Object, "st_"));
  MH_PETSC(KSPSetOperators(ksp.Object, shifted.Object, shifted.Object));
  MH_PETSC(KSPSetType(ksp.Object, KSPPREONLY));
  PC pc;
  MH_PETSC(KSPGetPC(ksp.Object, &pc));
  MH_PETSC(PCSetType(pc, PCCHOLESKY));
  MH_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  MH_PETSC(PCSetErrorIfFailure(pc, PETSC_TRUE));
  MH_PETSC(KSPSetFromOptions(ksp.Object));
  MH_PETSC(KSPSetUp(ksp.Object));
  Mat factor;
  MH_PETSC(PCFactorGetMatrix(pc, &factor));
  PetscInt negative = 0;
  PetscInt zero = 0;
  PetscInt positive = 0;
  MH_PETSC(MatGetInertia(factor, &negative, &zero, &positive));
  return negative;
}

//------------------------------------------------------------------------------
// Whether any process's user cancelled (collective).
bool AnyCancelled(MPI_Comm comm, const vtkManifoldHarmonicsSlepc::Settings& settings)
{
  int local = settings.Cancelled && settings.Cancelled() ? 1 : 0;
  int any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
  return any != 0;
}

//------------------------------------------------------------------------------
// The eigenpairs of one interval by Krylov-Schur spectrum slicing (shift-and-invert on MUMPS
// Cholesky factorizations, ICNTL(13) and (24) from the session's options), ascending.
struct Slice
{
  std::vector<std::pair<double, PetscInt>> Order;
  /// Eigenvalues in the interval by the inertia at its ends, and the shifts used.
  PetscInt Count = 0;
  PetscInt Shifts = 0;
};

Slice SolveSlice(OwnedEPS& eps,
  Mat Q,
  Mat D,
  double lower,
  double upper,
  int partitions,
  const vtkManifoldHarmonicsSlepc::Settings& settings)
{
  MH_PETSC(EPSCreate(PetscObjectComm(reinterpret_cast<PetscObject>(Q)), &eps.Object));
  MH_PETSC(EPSSetOperators(eps.Object, Q, D));
  MH_PETSC(EPSSetProblemType(eps.Object, EPS_GHEP));
  MH_PETSC(EPSSetType(eps.Object, EPSKRYLOVSCHUR));
  MH_PETSC(EPSSetWhichEigenpairs(eps.Object, EPS_ALL));
  MH_PETSC(EPSSetInterval(eps.Object, lower, upper));
  MH_PETSC(EPSSetTolerances(eps.Object, settings.Tolerance, settings.MaxIterations));
  ST st;
  MH_PETSC(EPSGetST(eps.Object, &st));
  MH_PETSC(STSetType(st, STSINVERT));
  MH_PETSC(STSetMatStructure(st, SUBSET_NONZERO_PATTERN));
  KSP ksp;
  MH_PETSC(STGetKSP(st, &ksp));
  MH_PETSC(KSPSetType(ksp, KSPPREONLY));
  PC pc;
  MH_PETSC(KSPGetPC(ksp, &pc));
  MH_PETSC(PCSetType(pc, PCCHOLESKY));
  MH_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  MH_PETSC(PCSetErrorIfFailure(pc, PETSC_TRUE));
  MH_PETSC(EPSKrylovSchurSetPartitions(eps.Object, partitions));
  MH_PETSC(EPSSetFromOptions(eps.Object));
  MH_PETSC(EPSSolve(eps.Object));

  Slice slice;
  PetscInt converged = 0;
  MH_PETSC(EPSGetConverged(eps.Object, &converged));
  PetscReal* at = nullptr;
  PetscInt* inertias = nullptr;
  MH_PETSC(EPSKrylovSchurGetInertias(eps.Object, &slice.Shifts, &at, &inertias));
  PetscInt atLower = 0;
  PetscInt atUpper = 0;
  for (PetscInt k = 0; k < slice.Shifts; ++k)
  {
    if (at[k] <= lower)
    {
      atLower = inertias[k];
    }
    if (at[k] >= upper)
    {
      atUpper = inertias[k];
    }
  }
  PetscFree(at);
  PetscFree(inertias);
  slice.Count = atUpper - atLower;
  if (slice.Count != converged)
  {
    std::ostringstream text;
    text << "SLEPc computed " << converged << " eigenpairs in a slice where the inertia counts "
         << slice.Count << ": raise MaxIterations, or lower Tolerance";
    throw std::runtime_error(text.str());
  }
  slice.Order.resize(static_cast<std::size_t>(converged));
  for (PetscInt k = 0; k < converged; ++k)
  {
    PetscScalar real = 0.0;
    PetscScalar imaginary = 0.0;
    MH_PETSC(EPSGetEigenvalue(eps.Object, k, &real, &imaginary));
    slice.Order[k] = { PetscRealPart(real), k };
  }
  std::sort(slice.Order.begin(), slice.Order.end());
  return slice;
}
//------------------------------------------------------------------------------
// Copies the values of a distributed vector (owned rows) to the piece's points that use them,
// seam copies included (from their owners, by a PETSc scatter).
class RowWriter
{
public:
  /// `layout`: any vector of the operators' row layout; `global`: the global number of each
  /// used point; `tuples`: its point id in the piece.
  RowWriter(Vec layout, const std::vector<PetscInt>& global, const std::vector<int>& tuples)
    : Tuples(tuples)
  {
    OwnedIS from;
    MH_PETSC(ISCreateGeneral(PETSC_COMM_SELF,
      static_cast<PetscInt>(global.size()),
      global.data(),
      PETSC_COPY_VALUES,
      &from.Object));
    MH_PETSC(
      VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(global.size()), &this->Local.Object));
    MH_PETSC(
      VecScatterCreate(layout, from.Object, this->Local.Object, nullptr, &this->Scatter.Object));
  }

  /// Calls store(point id, value) for every used point (collective).
  void Write(Vec values, const std::function<void(vtkIdType, double)>& store)
  {
    MH_PETSC(VecScatterBegin(
      this->Scatter.Object, values, this->Local.Object, INSERT_VALUES, SCATTER_FORWARD));
    MH_PETSC(VecScatterEnd(
      this->Scatter.Object, values, this->Local.Object, INSERT_VALUES, SCATTER_FORWARD));
    const PetscScalar* local = nullptr;
    MH_PETSC(VecGetArrayRead(this->Local.Object, &local));
    for (std::size_t i = 0; i < this->Tuples.size(); ++i)
    {
      store(this->Tuples[i], local[i]);
    }
    MH_PETSC(VecRestoreArrayRead(this->Local.Object, &local));
  }

private:
  const std::vector<int>& Tuples;
  OwnedVec Local;
  OwnedScatter Scatter;
};

//------------------------------------------------------------------------------
// The checks of one eigenpair with the core's definitions (Verification.h): the D^-1-weighted
// norm of the residual Q x - lambda D x (relative to the spectrum's scale later, once every
// eigenvalue is known) and the componentwise backward error
// max_i |r_i| / max((|Q| |x| + |lambda| D |x|)_i, floor).
struct PairError
{
  double ResidualNorm = 0.0;
  double Backward = 0.0;
};

class PairChecks
{
public:
  PairChecks(Mat Q, Mat D)
    : Q(Q)
    , D(D)
  {
    MH_PETSC(MatDuplicate(Q, MAT_COPY_VALUES, &this->AbsQ.Object));
    PetscInt first = 0;
    PetscInt end = 0;
    MH_PETSC(MatGetOwnershipRange(Q, &first, &end));
    std::vector<PetscScalar> values;
    for (PetscInt row = first; row < end; ++row)
    {
      PetscInt count = 0;
      const PetscInt* cols = nullptr;
      const PetscScalar* entries = nullptr;
      MH_PETSC(MatGetRow(Q, row, &count, &cols, &entries));
      values.assign(entries, entries + count);
      for (PetscScalar& value : values)
      {
        value = std::abs(value);
      }
      const PetscErrorCode set =
        MatSetValues(this->AbsQ.Object, 1, &row, count, cols, values.data(), INSERT_VALUES);
      MH_PETSC(MatRestoreRow(Q, row, &count, &cols, &entries));
      MH_PETSC(set);
    }
    MH_PETSC(MatAssemblyBegin(this->AbsQ.Object, MAT_FINAL_ASSEMBLY));
    MH_PETSC(MatAssemblyEnd(this->AbsQ.Object, MAT_FINAL_ASSEMBLY));
    MH_PETSC(MatCreateVecs(Q, &this->Qx.Object, &this->Dx.Object));
    MH_PETSC(MatCreateVecs(Q, &this->AbsX.Object, &this->Scale.Object));
    MH_PETSC(MatCreateVecs(Q, &this->AbsDx.Object, nullptr));
    // Row sums of D (the lumped weights of the residual norm) and trace(Q) / mass.
    MH_PETSC(VecSet(this->AbsX.Object, 1.0));
    MH_PETSC(MatMult(D, this->AbsX.Object, this->Scale.Object));
    this->RowSum.resize(static_cast<std::size_t>(end - first));
    const PetscScalar* sums = nullptr;
    MH_PETSC(VecGetArrayRead(this->Scale.Object, &sums));
    std::copy(sums, sums + (end - first), this->RowSum.begin());
    MH_PETSC(VecRestoreArrayRead(this->Scale.Object, &sums));
    PetscScalar mass = 0.0;
    PetscScalar trace = 0.0;
    MH_PETSC(VecSum(this->Scale.Object, &mass));
    MH_PETSC(MatGetDiagonal(Q, this->Qx.Object));
    MH_PETSC(VecSum(this->Qx.Object, &trace));
    this->TraceOverMass = trace / std::max(mass, 1e-300);
    // Gershgorin's bound on D^-1 Q: max_i sum_j |Q_ij| / D_i (for AchievableResidual).
    MH_PETSC(MatMult(this->AbsQ.Object, this->AbsX.Object, this->Qx.Object));
    const PetscScalar* absSums = nullptr;
    MH_PETSC(VecGetArrayRead(this->Qx.Object, &absSums));
    double top = 0.0;
    for (std::size_t i = 0; i < this->RowSum.size(); ++i)
    {
      top = std::max(top, this->RowSum[i] > 0.0 ? absSums[i] / this->RowSum[i] : 0.0);
    }
    MH_PETSC(VecRestoreArrayRead(this->Qx.Object, &absSums));
    MPI_Allreduce(&top,
      &this->GershgorinTop,
      1,
      MPI_DOUBLE,
      MPI_MAX,
      PetscObjectComm(reinterpret_cast<PetscObject>(Q)));
  }

  /// Scales x to unit D-norm, stores D x (owned rows) in dx and checks the pair (collective).
  PairError NormalizeAndCheck(Vec x, double lambda, double* dx)
  {
    MH_PETSC(MatMult(this->D, x, this->Dx.Object));
    PetscScalar norm2 = 0.0;
    MH_PETSC(VecDot(x, this->Dx.Object, &norm2));
    const double inverse = 1.0 / std::sqrt(PetscRealPart(norm2));
    MH_PETSC(VecScale(x, inverse));
    MH_PETSC(VecScale(this->Dx.Object, inverse));
    const PetscScalar* values = nullptr;
    MH_PETSC(VecGetArrayRead(this->Dx.Object, &values));
    std::copy(values, values + this->RowSum.size(), dx);
    MH_PETSC(VecRestoreArrayRead(this->Dx.Object, &values));
    MH_PETSC(MatMult(this->Q, x, this->Qx.Object));
    MH_PETSC(VecAXPY(this->Qx.Object, -lambda, this->Dx.Object));
    MH_PETSC(VecCopy(x, this->AbsX.Object));
    MH_PETSC(VecAbs(this->AbsX.Object));
    MH_PETSC(MatMult(this->AbsQ.Object, this->AbsX.Object, this->Scale.Object));
    MH_PETSC(MatMult(this->D, this->AbsX.Object, this->AbsDx.Object));
    MH_PETSC(VecAXPY(this->Scale.Object, std::abs(lambda), this->AbsDx.Object));
    PetscReal largest = 0.0;
    MH_PETSC(VecMax(this->Scale.Object, nullptr, &largest));
    const double floor = spectral::detail::BackwardErrorFloor * largest;
    const PetscScalar* r = nullptr;
    const PetscScalar* denominators = nullptr;
    MH_PETSC(VecGetArrayRead(this->Qx.Object, &r));
    MH_PETSC(VecGetArrayRead(this->Scale.Object, &denominators));
    double sums[2] = { 0.0, 0.0 }; // sum r^2 / d, and the largest backward ratio
    for (std::size_t i = 0; i < this->RowSum.size(); ++i)
    {
      sums[0] += r[i] * r[i] / this->RowSum[i];
      const double error = std::abs(r[i]);
      if (error > 0.0)
      {
        const double denominator = std::max(denominators[i], floor);
        sums[1] = std::max(sums[1],
          denominator > 0.0 ? error / denominator : std::numeric_limits<double>::infinity());
      }
    }
    MH_PETSC(VecRestoreArrayRead(this->Qx.Object, &r));
    MH_PETSC(VecRestoreArrayRead(this->Scale.Object, &denominators));
    const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(this->Q));
    double global[2];
    MPI_Allreduce(&sums[0], &global[0], 1, MPI_DOUBLE, MPI_SUM, comm);
    MPI_Allreduce(&sums[1], &global[1], 1, MPI_DOUBLE, MPI_MAX, comm);
    return { std::sqrt(global[0]), global[1] };
  }

  /// trace(Q) / total mass: the floor of the spectrum's scale for the relative residual.
  double TraceOverMass = 0.0;
  /// Gershgorin's bound on the largest eigenvalue, max_i sum_j |Q_ij| / D_i, over all processes.
  double GershgorinTop = 0.0;

private:
  Mat Q;
  Mat D;
  OwnedMat AbsQ;
  std::vector<double> RowSum;
  OwnedVec Qx;
  OwnedVec Dx;
  OwnedVec AbsX;
  OwnedVec Scale;
  OwnedVec AbsDx;
};

//------------------------------------------------------------------------------
// H^T Y for the first `columns` harmonics H already written in `rows` (row-major, m values a
// point), read at the points of the owned rows (`ownedTuples`, one per row of Y).
spectral::DenseMatrix WrittenTimes(const double* rows,
  int m,
  int columns,
  const std::vector<vtkIdType>& ownedTuples,
  const Eigen::Ref<const spectral::DenseMatrix>& Y)
{
  spectral::DenseMatrix product = spectral::DenseMatrix::Zero(columns, Y.cols());
  if (columns == 0)
  {
    return product;
  }
  const Eigen::Index block = 256;
  spectral::DenseMatrix gathered(block, columns);
  for (Eigen::Index r0 = 0; r0 < Y.rows(); r0 += block)
  {
    const Eigen::Index count = std::min(block, Y.rows() - r0);
    for (Eigen::Index t = 0; t < count; ++t)
    {
      gathered.row(t) =
        Eigen::Map<const Eigen::RowVectorXd>(rows + ownedTuples[r0 + t] * m, columns);
    }
    product.noalias() += gathered.topRows(count).transpose() * Y.middleRows(r0, count);
  }
  return product;
}
} // anonymous namespace

namespace vtkManifoldHarmonicsSlepc
{
//------------------------------------------------------------------------------
Result Solve(vtkMultiProcessController* controller,
  const spectral::TriangleMesh& piece,
  const Settings& settings)
{
  Initialize();
  const MPI_Comm comm = PETSC_COMM_WORLD;
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int processes = controller ? controller->GetNumberOfProcesses() : 1;
  if (processes != size)
  {
    // Decided alike on every process: the sizes are the same everywhere.
    throw std::runtime_error("the SLEPc solver needs every MPI process of the run (" +
      std::to_string(size) + ") in the pipeline, which has " + std::to_string(processes));
  }
  Session session(settings.Options);
  auto stage = [&settings](const char* name)
  {
    if (settings.Stage)
    {
      settings.Stage(name);
    }
  };
  auto progress = [&settings](double fraction)
  {
    if (settings.Progress)
    {
      settings.Progress(fraction);
    }
  };
  auto warn = [&settings, rank](const std::string& text)
  {
    if (settings.Warning && rank == 0)
    {
      settings.Warning(text);
    }
  };

  // 1. This piece's cells of non-zero size and the points they use; global numbers.
  stage("Assemble");
  const spectral::PreparedMesh prepared = spectral::PrepareMesh(piece);
  spectral::TriangleMesh mesh = prepared.Mesh;
  const Eigen::Index used = mesh.Vertices.rows();
  // Triangles on some processes and tetrahedra on others: refused on all alike.
  int kinds[2] = { mesh.Faces.rows() > 0 ? 1 : 0, mesh.IsVolume() ? 1 : 0 };
  MPI_Allreduce(MPI_IN_PLACE, kinds, 2, MPI_INT, MPI_MAX, comm);
  if (kinds[0] && kinds[1])
  {
    throw std::runtime_error("some processes hold triangles and others tetrahedra: the mesh "
                             "must be a surface or a volume on every process");
  }
  const int dimension = kinds[1] ? 3 : 2;
  double low[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double high[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (int c = 0; c < 3 && used > 0; ++c)
  {
    low[c] = mesh.Vertices.col(c).minCoeff();
    high[c] = mesh.Vertices.col(c).maxCoeff();
  }
  double globalLow[3];
  double globalHigh[3];
  MPI_Allreduce(low, globalLow, 3, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(high, globalHigh, 3, MPI_DOUBLE, MPI_MAX, comm);
  long long usedLocal = used;
  long long usedTotal = 0;
  MPI_Allreduce(&usedLocal, &usedTotal, 1, MPI_LONG_LONG, MPI_SUM, comm);
  if (usedTotal == 0)
  {
    throw std::runtime_error(
      "no triangle of non-zero area and no tetrahedron of non-zero volume on any process");
  }
  double diagonal = 0.0;
  double bounds[6];
  for (int c = 0; c < 3; ++c)
  {
    diagonal += (globalHigh[c] - globalLow[c]) * (globalHigh[c] - globalLow[c]);
    bounds[2 * c] = globalLow[c];
    bounds[2 * c + 1] = globalHigh[c];
  }
  diagonal = std::sqrt(diagonal);
  const Numbering numbering =
    NumberPoints(comm, mesh, bounds, settings.WeldSeams || size > 1, settings.SeamTolerance);

  Result result;
  result.GlobalPoints = numbering.Total;
  result.OwnedPoints = numbering.OwnedCount;
  int m = settings.NumberOfHarmonics;
  if (m > numbering.Total)
  {
    warn("NumberOfHarmonics " + std::to_string(m) + " clamped to the " +
      std::to_string(numbering.Total) + " points that triangles use.");
    m = static_cast<int>(numbering.Total);
  }

  // 2. Operators of the local cells in the unit of the global diameter, added up by global
  // numbers.
  const double s = spectral::UnitScale(diagonal);
  mesh.Vertices /= s;
  double measureLocal = spectral::Measure(mesh);
  double measure = 0.0;
  MPI_Allreduce(&measureLocal, &measure, 1, MPI_DOUBLE, MPI_SUM, comm);
  OwnedMat Q;
  CreateMatrix(comm, spectral::CotanStiffness(mesh), numbering, Q);
  const spectral::Vector lumpedLocal = spectral::LumpedMass(mesh);
  OwnedVec lumped;
  MH_PETSC(MatCreateVecs(Q.Object, &lumped.Object, nullptr));
  MH_PETSC(VecSet(lumped.Object, 0.0));
  MH_PETSC(VecSetValues(lumped.Object,
    static_cast<PetscInt>(used),
    numbering.Global.data(),
    lumpedLocal.data(),
    ADD_VALUES));
  MH_PETSC(VecAssemblyBegin(lumped.Object));
  MH_PETSC(VecAssemblyEnd(lumped.Object));
  OwnedMat D;
  if (settings.ConsistentMass)
  {
    CreateMatrix(comm, spectral::ConsistentMass(mesh), numbering, D);
  }
  else
  {
    MH_PETSC(MatCreateAIJ(comm,
      numbering.OwnedCount,
      numbering.OwnedCount,
      numbering.Total,
      numbering.Total,
      1,
      nullptr,
      0,
      nullptr,
      &D.Object));
    MH_PETSC(MatDiagonalSet(D.Object, lumped.Object, INSERT_VALUES));
    MH_PETSC(MatAssemblyBegin(D.Object, MAT_FINAL_ASSEMBLY));
    MH_PETSC(MatAssemblyEnd(D.Object, MAT_FINAL_ASSEMBLY));
    MarkSymmetric(D.Object);
  }
  progress(0.05);

  // The connected components: each one's constant harmonic is written with eigenvalue 0, the
  // largest components' first; SLEPc's pairs are kept in their D-orthogonal complement.
  const Components components = DistributedComponents(comm, mesh, numbering, lumped.Object);
  const int zeros = std::min(m, components.Count);
  if (components.Count > 1 && m <= components.Count)
  {
    warn("NumberOfHarmonics " + std::to_string(m) + " does not exceed the " +
      std::to_string(components.Count) +
      " connected components: every harmonic is constant on one component (eigenvalue 0), so "
      "filtering can only move whole components.");
  }

  // 3. The interval (unless the constants are all the harmonics asked for): Weyl's law for
  // its upper end, widened until the inertia counts m (the zero eigenvalues among them; they
  // are at most the number of components, so that at least m - zeros non-zero eigenvalues lie
  // below it).
  stage("Interval");
  const double first =
    spectral::WeylEigenvalue(1.0, std::max(measure, std::numeric_limits<double>::min()), dimension);
  const double lower = -0.5 * first;
  double upper = 1.2 *
    spectral::WeylEigenvalue(
      m + 1.0, std::max(measure, std::numeric_limits<double>::min()), dimension);
  PetscInt below = zeros;
  if (zeros < m)
  {
    below = CountBelow(Q.Object, D.Object, upper);
  }
  else
  {
    upper = 0.0;
  }
  for (int attempt = 0; below < m; ++attempt)
  {
    if (attempt > 60)
    {
      throw std::runtime_error("the inertia count stays below " + std::to_string(m) +
        " however far the interval is widened");
    }
    upper *= below > 0 ? std::max(1.25, 1.1 * m / below) : 2.0;
    below = CountBelow(Q.Object, D.Object, upper);
  }
  progress(0.2);

  // The eigensolve: [lower, upper] in slices of about SliceHarmonics eigenvalues by Weyl's law,
  // ascending, until m pairs are found. Between slices, progress and the abort flag (SLEPc's
  // spectrum slicing calls no monitor).
  stage("Eigensolve");
  int partitions = std::max(1, settings.Partitions);
  if (partitions > size)
  {
    warn("SlepcPartitions " + std::to_string(partitions) + " reduced to the " +
      std::to_string(size) + " processes of the run.");
    partitions = size;
  }
  const PetscInt owned = numbering.OwnedCount;
  const int slices = zeros < m ? std::max(1, (m + SliceHarmonics - 1) / SliceHarmonics) : 0;

  // The rows of this piece's points are the only full copy of the harmonics a process keeps:
  // each slice's pairs are checked, then written there (seam copies from their owners), and
  // the D-orthonormality of later slices is measured against the written rows.
  const vtkIdType n = piece.Vertices.rows();
  vtkManifoldHarmonicsParallel::PieceBasis& rows = result.Rows;
  rows.Harmonics = vtkSmartPointer<vtkDoubleArray>::New();
  rows.Harmonics->SetNumberOfComponents(std::max(m, 1));
  rows.Harmonics->SetNumberOfTuples(n);
  rows.Harmonics->FillValue(0.0);
  double* harmonics = rows.Harmonics->GetPointer(0);
  RowWriter writer(lumped.Object, numbering.Global, prepared.InputPointIds);
  std::vector<vtkIdType> ownedTuples(static_cast<std::size_t>(owned));
  std::vector<int> ownedLabels(static_cast<std::size_t>(owned));
  {
    PetscInt first = 0;
    PetscInt end = 0;
    MH_PETSC(MatGetOwnershipRange(Q.Object, &first, &end));
    for (Eigen::Index i = 0; i < used; ++i)
    {
      if (numbering.Owned[i])
      {
        ownedTuples[numbering.Global[i] - first] = prepared.InputPointIds[i];
        ownedLabels[numbering.Global[i] - first] = components.Label[i];
      }
    }
  }
  const Constants constants(components, std::move(ownedLabels), lumped.Object);
  PairChecks checks(Q.Object, D.Object);
  spectral::Vector lambda(m);
  std::vector<double> residualNorms(static_cast<std::size_t>(m), 0.0);
  std::vector<double> backwardErrors(static_cast<std::size_t>(m), 0.0);
  spectral::DenseMatrix gram = spectral::DenseMatrix::Zero(m, m);
  // M-normalized harmonics scale as s^(-d/2), the mass as s^d.
  const double inverseScale = std::pow(s, -0.5 * dimension);
  OwnedVec vector;
  MH_PETSC(MatCreateVecs(Q.Object, &vector.Object, nullptr));
  spectral::DenseMatrix DX(owned, GramColumns);
  // Pairs written (columns of the harmonics), and those of them whose Gram matrix against the
  // written rows is still to be taken (the columns of DX, up to GramColumns at once).
  int found = 0;
  int pending = 0;
  const auto takeGram = [&]()
  {
    if (pending > 0)
    {
      gram.block(0, found - pending, found, pending) =
        WrittenTimes(harmonics, m, found, ownedTuples, DX.leftCols(pending)) / inverseScale;
      pending = 0;
    }
  };
  // The pair (value, vector) as the next column: D-normalized, checked and written (scaled
  // back from the mesh's units).
  const auto add = [&](double value)
  {
    const int k = found;
    lambda[k] = value;
    const PairError error = checks.NormalizeAndCheck(vector.Object, value, DX.col(pending).data());
    residualNorms[k] = error.ResidualNorm;
    backwardErrors[k] = error.Backward;
    result.MaxBackwardError = std::max(result.MaxBackwardError, error.Backward);
    writer.Write(vector.Object,
      [&](vtkIdType tuple, double h) { harmonics[tuple * m + k] = h * inverseScale; });
    ++found;
    if (++pending == GramColumns)
    {
      takeGram();
    }
  };
  for (int r = 0; r < zeros; ++r)
  {
    constants.Set(vector.Object, components.Order[r]);
    add(0.0);
  }
  // SLEPc's pairs in the span of the constants (their eigenvalues are those of Q 1 = 0 as
  // rounded: tiny, or on debris with near-coincident points as large as 1e-5 of the
  // component's largest) are left out; the others are deflated (Constants::Deflate).
  int zeroModes = 0;
  for (int j = 0; j < slices && found < m; ++j)
  {
    if (AnyCancelled(comm, settings))
    {
      throw vtkManifoldHarmonicsSlepc::Cancelled();
    }
    const double from = j == 0 ? lower : upper * j / slices;
    const double to = upper * (j + 1) / slices;
    OwnedEPS eps;
    const Slice slice = SolveSlice(eps, Q.Object, D.Object, from, to, partitions, settings);
    result.InertiaCount += static_cast<int>(slice.Count);
    result.Computed += static_cast<int>(slice.Order.size());
    result.Shifts += static_cast<int>(slice.Shifts);
    for (std::size_t c = 0; c < slice.Order.size() && found < m; ++c)
    {
      MH_PETSC(EPSGetEigenvector(eps.Object, slice.Order[c].second, vector.Object, nullptr));
      if (constants.Deflate(vector.Object, 0.5) > 0.5)
      {
        ++zeroModes;
        continue;
      }
      NormalizeSign(vector.Object);
      add(slice.Order[c].first);
    }
    progress(0.2 + 0.7 * found / m);
  }
  takeGram();
  if (zeroModes > components.Count)
  {
    throw std::runtime_error("SLEPc returned " + std::to_string(zeroModes) +
      " eigenvectors in the span of the constant harmonics of the " +
      std::to_string(components.Count) + " connected components: lower Tolerance");
  }
  if (found < m)
  {
    throw std::runtime_error("SLEPc found " + std::to_string(found - zeros) +
      " non-zero eigenpairs below " + std::to_string(upper / (s * s)) +
      ", where the inertia counts " + std::to_string(below) + " eigenvalues (" +
      std::to_string(m - zeros) + " needed besides the zero eigenvalues of the " +
      std::to_string(zeros) + " connected components)");
  }

  // 4. Checks with the core's definitions (Verification.h), on distributed vectors: the
  // relative residual needs the whole spectrum's scale, the orthonormality the whole Gram matrix.
  stage("Verify");
  const double reference = spectral::ResidualReference(lambda, checks.TraceOverMass);
  const spectral::EigenOptions tolerances;
  std::vector<double> relative(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k)
  {
    relative[k] = residualNorms[k] /
      std::max({ std::abs(lambda[k]), reference, std::numeric_limits<double>::min() });
    result.MaxResidual = std::max(result.MaxResidual, relative[k]);
  }
  // The first pair above both tolerances, or -1.
  const auto firstFailing = [&](double residualTolerance)
  {
    for (int k = 0; k < m; ++k)
    {
      if (!(relative[k] <= residualTolerance) &&
        !(backwardErrors[k] <= tolerances.BackwardErrorTolerance))
      {
        return k;
      }
    }
    return -1;
  };
  const auto failure = [&](int k, double residualTolerance)
  {
    std::ostringstream text;
    text << "eigenpair " << k << " (lambda = " << lambda[k] / (s * s) << ") has relative residual "
         << relative[k] << " and backward error " << backwardErrors[k] << ", above the tolerances "
         << residualTolerance << " and " << tolerances.BackwardErrorTolerance;
    return text.str();
  };
  // On a badly conditioned mesh the residual tolerance is what double precision achieves, as
  // for the built-in solver (Verification.h: AchievableResidual, up to MeaningfulResidual).
  double residualTolerance = tolerances.ResidualTolerance;
  int failing = firstFailing(residualTolerance);
  double ratio = 0.0;
  const double achievable = spectral::AchievableResidual(checks.GershgorinTop, diagonal / s, ratio);
  if (failing >= 0 && achievable > residualTolerance)
  {
    if (achievable > spectral::MeaningfulResidual)
    {
      throw std::runtime_error(
        failure(failing, residualTolerance) + "; " + spectral::UnresolvableResidual(ratio));
    }
    warn(spectral::RelaxedResidualWarning(achievable, residualTolerance, ratio));
    residualTolerance = achievable;
    failing = firstFailing(residualTolerance);
  }
  if (failing >= 0)
  {
    throw std::runtime_error(failure(failing, residualTolerance) + ": lower Tolerance");
  }
  spectral::DenseMatrix globalGram(m, m);
  MPI_Allreduce(gram.data(), globalGram.data(), m * m, MPI_DOUBLE, MPI_SUM, comm);
  globalGram = globalGram.selfadjointView<Eigen::Upper>();
  result.OrthonormalityError =
    m > 0 ? (globalGram - spectral::DenseMatrix::Identity(m, m)).cwiseAbs().maxCoeff() : 0.0;
  if (!(result.OrthonormalityError <= residualTolerance * 100))
  {
    // On badly conditioned operators (debris of a few triangles holding a near-coincident
    // point: masses spanning 1e8, eigenvalues 1e17) the orthogonalization in the D inner
    // product loses what a lower Tolerance cannot bring back.
    const std::string remedy = achievable > tolerances.ResidualTolerance
      ? "; " + spectral::BadConditioning(ratio) +
        ": merge close points (vtkCleanPolyData, Clean, with a tolerance), or use the Built-in "
        "solver, which solves each connected component on its own"
      : ": lower Tolerance";
    throw std::runtime_error("the eigenvectors are D-orthonormal to " +
      std::to_string(result.OrthonormalityError) + " only" + remedy);
  }
  progress(0.95);

  // 5. The mass and the DUPLICATEPOINT flags of this piece's points.
  stage("Write");
  rows.Eigenvalues = lambda / (s * s);
  rows.Mass = vtkSmartPointer<vtkDoubleArray>::New();
  rows.Mass->SetNumberOfTuples(n);
  rows.Mass->FillValue(0.0);
  rows.Duplicates = vtkSmartPointer<vtkUnsignedCharArray>::New();
  rows.Duplicates->SetNumberOfTuples(n);
  rows.Duplicates->FillValue(0);
  const double areaScale = std::pow(s, dimension);
  writer.Write(lumped.Object,
    [&](vtkIdType tuple, double value) { rows.Mass->SetValue(tuple, value * areaScale); });
  for (Eigen::Index i = 0; i < used; ++i)
  {
    if (!numbering.Owned[i])
    {
      rows.Duplicates->SetValue(prepared.InputPointIds[i], vtkDataSetAttributes::DUPLICATEPOINT);
    }
  }
  // Components that no harmonic represents (more components than m): zero mass as well, as in
  // the built-in solver (Basis.cxx, LeaveOutUnrepresented), so that the filters pass their
  // points through unchanged.
  if (zeros < components.Count)
  {
    std::vector<char> represented(static_cast<std::size_t>(components.Count), 0);
    for (int r = 0; r < zeros; ++r)
    {
      represented[components.Order[r]] = 1;
    }
    long long left = 0;
    for (int j = 0; j < components.Count; ++j)
    {
      left += represented[j] ? 0 : components.Points[j];
    }
    for (Eigen::Index i = 0; i < used; ++i)
    {
      if (!represented[components.Label[i]])
      {
        rows.Mass->SetValue(prepared.InputPointIds[i], 0.0);
      }
    }
    warn(std::to_string(left) + " points of components that none of the " + std::to_string(m) +
      " harmonics represents have zero harmonics and mass: the filters pass them through "
      "unchanged.");
  }
  result.UpperEnd = upper / (s * s);
  progress(1.0);
  return result;
}
} // namespace vtkManifoldHarmonicsSlepc
