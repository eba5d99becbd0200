// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Distributed/Solve.h"
#include "Common/Eigenvalues.h"
#include "Distributed/Assembly.h"
#include "Distributed/Numbering.h"
#include "Distributed/Pairs.h"
#include "Distributed/Petsc.h"
#include "Operators/Operators.h"
#include "Problem.h"
#include "Solver/Acceptance.h"
#include "Solver/Verification.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace spectral
{
namespace distributed
{
namespace
{
// Eigenvalues per spectrum slicing run: the solve checks the cancel flag and reports progress
// between runs. Each run adds the factorizations at its ends.
constexpr int SliceHarmonics = 200;
// Eigenvectors whose D-products a process keeps at once (owned rows by GramColumns) to take
// their Gram matrix against the written rows: memory against passes over those rows.
constexpr int GramColumns = 32;

/// The stages of SolveDistributed (Solve.h) and the state they share, in the order they run.
class Engine
{
public:
  Engine(MPI_Comm comm, const DistributedOptions& options, const Monitor& monitor)
    : Comm(comm)
    , Options(options)
    , Progress(monitor)
  {
    MPI_Comm_rank(comm, &this->Rank);
    MPI_Comm_size(comm, &this->Size);
  }

  void Piece(const TriangleMesh& piece);
  void Number();
  void Assemble();
  void ZeroModes();
  void Interval();
  void WindowInterval();
  void Eigensolve(Eigen::Index rows);
  void Verify();
  void Write(Eigen::Index rows);

  DistributedResult Result;

private:
  void Warn(const std::string& text) const
  {
    if (this->Rank == 0)
    {
      this->Progress.Warn(text);
    }
  }
  bool AnyCancelled() const;
  void Add(double value);
  void TakeGram();

  MPI_Comm Comm;
  const DistributedOptions& Options;
  const Monitor& Progress;
  int Rank = 0;
  int Size = 1;
  // Piece
  PreparedMesh Prepared;
  TriangleMesh Mesh;
  int Dimension = 2;
  double Bounds[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  double Diagonal = 0.0;
  // Number, Assemble
  Numbering Numbers;
  int M = 0;
  double S = 1.0;
  double TotalMeasure = 0.0;
  Operators Ops;
  // ZeroModes, Interval
  Components Parts;
  int Zeros = 0;
  double Lower = 0.0;
  double Upper = 0.0;
  PetscInt Below = 0;
  // Eigensolve, Verify
  double* Harmonics = nullptr;
  std::unique_ptr<RowWriter> Writer;
  std::unique_ptr<PairChecks> Checks;
  std::vector<Eigen::Index> OwnedRows;
  OwnedVec Current;
  DenseMatrix DX;
  DenseMatrix Gram;
  Vector Lambda;
  std::vector<double> ResidualNorms;
  Vector BackwardErrors;
  double InverseScale = 1.0;
  int Found = 0;
  int Pending = 0;
};

//------------------------------------------------------------------------------
// 1. This piece's cells of non-zero size and the points they use; the global bounding box.
void Engine::Piece(const TriangleMesh& piece)
{
  this->Progress.Begin("Assemble");
  this->Prepared = PrepareMesh(piece);
  this->Mesh = this->Prepared.Mesh;
  const Points& points = this->Mesh.Vertices;
  // Triangles on some processes and tetrahedra on others: refused on all alike.
  int kinds[2] = { this->Mesh.Faces.rows() > 0 ? 1 : 0, this->Mesh.IsVolume() ? 1 : 0 };
  MPI_Allreduce(MPI_IN_PLACE, kinds, 2, MPI_INT, MPI_MAX, this->Comm);
  if (kinds[0] && kinds[1])
  {
    throw std::runtime_error("some processes hold triangles and others tetrahedra: the mesh "
                             "must be a surface or a volume on every process");
  }
  this->Dimension = kinds[1] ? 3 : 2;
  long long used = points.rows();
  MPI_Allreduce(MPI_IN_PLACE, &used, 1, MPI_LONG_LONG, MPI_SUM, this->Comm);
  if (used == 0)
  {
    throw std::runtime_error(
      "no triangle of non-zero area and no tetrahedron of non-zero volume on any process");
  }
  // The global bounding box (BoundingBoxDiagonal of all pieces' points).
  const double huge = std::numeric_limits<double>::max();
  double low[3] = { huge, huge, huge };
  double high[3] = { -huge, -huge, -huge };
  for (int c = 0; c < 3 && points.rows() > 0; ++c)
  {
    low[c] = points.col(c).minCoeff();
    high[c] = points.col(c).maxCoeff();
  }
  MPI_Allreduce(MPI_IN_PLACE, low, 3, MPI_DOUBLE, MPI_MIN, this->Comm);
  MPI_Allreduce(MPI_IN_PLACE, high, 3, MPI_DOUBLE, MPI_MAX, this->Comm);
  Points box(2, 3);
  for (int c = 0; c < 3; ++c)
  {
    this->Bounds[2 * c] = box(0, c) = low[c];
    this->Bounds[2 * c + 1] = box(1, c) = high[c];
  }
  this->Diagonal = BoundingBoxDiagonal(box);
}

//------------------------------------------------------------------------------
// 2. Global numbers (the seam and owner rules), and m clamped to the points.
void Engine::Number()
{
  std::vector<unsigned char> owned;
  if (!this->Options.OwnedPoints.empty())
  {
    for (const int id : this->Prepared.InputPointIds)
    {
      owned.push_back(this->Options.OwnedPoints[static_cast<std::size_t>(id)]);
    }
  }
  this->Numbers = NumberPoints(this->Comm,
    this->Mesh,
    this->Bounds,
    this->Options.WeldSeams || this->Size > 1,
    this->Options.SeamTolerance,
    owned);
  this->Result.GlobalPoints = this->Numbers.Total;
  this->Result.OwnedPoints = this->Numbers.OwnedCount;
  if (IsFrequencyWindow(this->Options.LowerFrequency, this->Options.UpperFrequency))
  {
    return; // The window's inertia counts decide m (Interval).
  }
  std::string warning;
  this->M = ClampHarmonics(this->Options.NumberOfHarmonics,
    this->Numbers.Total,
    this->Dimension == 3 ? "tetrahedra use" : "triangles use",
    warning);
  if (!warning.empty())
  {
    this->Warn(warning);
  }
}

//------------------------------------------------------------------------------
// 3. Operators of the local cells in the unit of the global diameter, added up by global
// numbers.
void Engine::Assemble()
{
  this->S = UnitScale(this->Diagonal);
  this->Mesh.Vertices /= this->S;
  double measure = Measure(this->Mesh);
  MPI_Allreduce(&measure, &this->TotalMeasure, 1, MPI_DOUBLE, MPI_SUM, this->Comm);
  distributed::Assemble(
    this->Comm, this->Mesh, this->Numbers, this->Options.ConsistentMass, this->Ops);
  this->Progress.Report(0.05);
}

//------------------------------------------------------------------------------
// 4. The connected components: each one's constant harmonic is written with eigenvalue 0, the
// largest components' first; SLEPc's pairs are kept in their D-orthogonal complement.
void Engine::ZeroModes()
{
  this->Parts =
    DistributedComponents(this->Comm, this->Mesh, this->Numbers, this->Ops.Lumped.Object);
  if (IsFrequencyWindow(this->Options.LowerFrequency, this->Options.UpperFrequency))
  {
    return; // The window decides m and whether the constants are among its pairs (Interval).
  }
  this->Zeros = std::min(this->M, this->Parts.Count);
  if (this->Parts.Count > 1 && this->M <= this->Parts.Count)
  {
    this->Warn(NoMoreHarmonicsThanComponents(this->M, this->Parts.Count));
  }
}

//------------------------------------------------------------------------------
// 5. The interval (unless the constants are all the harmonics asked for): Weyl's law for its
// upper end, widened until the inertia counts m (the zero eigenvalues among them; they are at
// most the number of components, so that at least m - zeros non-zero eigenvalues lie below it).
void Engine::Interval()
{
  this->Progress.Begin("Interval");
  if (IsFrequencyWindow(this->Options.LowerFrequency, this->Options.UpperFrequency))
  {
    this->WindowInterval();
    return;
  }
  const double measure = std::max(this->TotalMeasure, std::numeric_limits<double>::min());
  const int m = this->M;
  this->Lower = -0.5 * WeylEigenvalue(1.0, measure, this->Dimension);
  this->Upper = 1.2 * WeylEigenvalue(m + 1.0, measure, this->Dimension);
  this->Below = this->Zeros;
  if (this->Zeros < m)
  {
    this->Below = CountBelow(this->Ops.Q.Object, this->Ops.D.Object, this->Upper);
  }
  else
  {
    this->Upper = 0.0;
  }
  for (int attempt = 0; this->Below < m; ++attempt)
  {
    if (attempt > 60)
    {
      throw std::runtime_error("the inertia count stays below " + std::to_string(m) +
        " however far the interval is widened");
    }
    this->Upper *= this->Below > 0 ? std::max(1.25, 1.1 * m / this->Below) : 2.0;
    this->Below = CountBelow(this->Ops.Q.Object, this->Ops.D.Object, this->Upper);
  }
  this->Progress.Report(0.2);
}

//------------------------------------------------------------------------------
// 5'. A frequency window: its ends, and m the eigenvalues between them by the inertia counts
// (the zero eigenvalues among them when it starts at 0: then the constants come first).
void Engine::WindowInterval()
{
  const DistributedOptions& options = this->Options;
  const std::pair<double, double> ends =
    WindowEigenvalues(options.LowerFrequency, options.UpperFrequency, this->S);
  const double measure = std::max(this->TotalMeasure, std::numeric_limits<double>::min());
  const bool fromZero = !(ends.first > 0.0);
  this->Lower = fromZero ? -0.5 * WeylEigenvalue(1.0, measure, this->Dimension) : ends.first;
  this->Upper = ends.second;
  const PetscInt first =
    fromZero ? 0 : CountBelow(this->Ops.Q.Object, this->Ops.D.Object, this->Lower);
  this->Below = CountBelow(this->Ops.Q.Object, this->Ops.D.Object, this->Upper);
  if (this->Below - first <= 0)
  {
    throw InvalidInput(
      EmptyWindow(options.LowerFrequency, options.UpperFrequency, static_cast<int>(first)));
  }
  this->M = static_cast<int>(this->Below - first);
  this->Result.FirstIndex = static_cast<int>(first);
  this->Zeros = fromZero ? std::min(this->M, this->Parts.Count) : 0;
  this->Progress.Report(0.2);
}

//------------------------------------------------------------------------------
bool Engine::AnyCancelled() const
{
  int local = this->Progress.Cancelled && this->Progress.Cancelled() ? 1 : 0;
  int any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, this->Comm);
  return any != 0;
}

//------------------------------------------------------------------------------
// The Gram matrix of the pending columns against the written rows.
void Engine::TakeGram()
{
  if (this->Pending > 0)
  {
    this->Gram.block(0, this->Found - this->Pending, this->Found, this->Pending) =
      WrittenTimes(
        this->Harmonics, this->M, this->Found, this->OwnedRows, this->DX.leftCols(this->Pending)) /
      this->InverseScale;
    this->Pending = 0;
  }
}

//------------------------------------------------------------------------------
// The pair (value, Current) as the next column: D-normalized, measured and written (scaled back
// from the mesh's units).
void Engine::Add(double value)
{
  const int k = this->Found;
  const int m = this->M;
  this->Lambda[k] = value;
  const PairError error = this->Checks->NormalizeAndCheck(
    this->Current.Object, value, this->DX.col(this->Pending).data());
  this->ResidualNorms[k] = error.ResidualNorm;
  this->BackwardErrors[k] = error.Backward;
  this->Result.MaxBackwardError = std::max(this->Result.MaxBackwardError, error.Backward);
  double* harmonics = this->Harmonics;
  const double scale = this->InverseScale;
  this->Writer->Write(
    this->Current.Object, [&](Eigen::Index row, double h) { harmonics[row * m + k] = h * scale; });
  ++this->Found;
  if (++this->Pending == GramColumns)
  {
    this->TakeGram();
  }
}

//------------------------------------------------------------------------------
// 6. The constants, then [Lower, Upper] in slices of about SliceHarmonics eigenvalues by Weyl's
// law, ascending, until m pairs are found; between slices, progress and the cancel flag
// (SLEPc's spectrum slicing calls no monitor).
void Engine::Eigensolve(Eigen::Index rows)
{
  this->Progress.Begin("Eigensolve");
  const int m = this->M;
  SliceSettings slicing{
    this->Options.Tolerance, this->Options.MaxIterations, std::max(1, this->Options.Partitions)
  };
  if (slicing.Partitions > this->Size)
  {
    this->Warn("SlepcPartitions " + std::to_string(slicing.Partitions) + " reduced to the " +
      std::to_string(this->Size) + " processes of the run.");
    slicing.Partitions = this->Size;
  }
  const PetscInt owned = this->Numbers.OwnedCount;
  const int slices = this->Zeros < m ? std::max(1, (m + SliceHarmonics - 1) / SliceHarmonics) : 0;
  if (this->Options.HarmonicsStorage)
  {
    this->Harmonics = this->Options.HarmonicsStorage(rows, m);
    std::fill(this->Harmonics, this->Harmonics + rows * m, 0.0);
  }
  else
  {
    this->Result.Harmonics = RowMatrix::Zero(rows, m);
    this->Harmonics = this->Result.Harmonics.data();
  }
  this->Writer = std::make_unique<RowWriter>(
    this->Ops.Lumped.Object, this->Numbers.Global, this->Prepared.InputPointIds);
  this->OwnedRows.assign(static_cast<std::size_t>(owned), 0);
  std::vector<int> ownedLabels(static_cast<std::size_t>(owned));
  PetscInt first = 0;
  MH_PETSC(MatGetOwnershipRange(this->Ops.Q.Object, &first, nullptr));
  for (std::size_t i = 0; i < this->Numbers.Owned.size(); ++i)
  {
    if (this->Numbers.Owned[i])
    {
      this->OwnedRows[this->Numbers.Global[i] - first] = this->Prepared.InputPointIds[i];
      ownedLabels[this->Numbers.Global[i] - first] = this->Parts.Label[i];
    }
  }
  const Constants constants(this->Parts, std::move(ownedLabels), this->Ops.Lumped.Object);
  this->Checks = std::make_unique<PairChecks>(this->Ops.Q.Object, this->Ops.D.Object);
  this->Lambda = Vector::Zero(m);
  this->ResidualNorms.assign(static_cast<std::size_t>(m), 0.0);
  this->BackwardErrors = Vector::Zero(m);
  this->Gram = DenseMatrix::Zero(m, m);
  // M-normalized harmonics scale as s^(-d/2).
  this->InverseScale = std::pow(this->S, -0.5 * this->Dimension);
  MH_PETSC(MatCreateVecs(this->Ops.Q.Object, &this->Current.Object, nullptr));
  this->DX.resize(owned, GramColumns);
  for (int r = 0; r < this->Zeros; ++r)
  {
    constants.Set(this->Current.Object, this->Parts.Order[r]);
    this->Add(0.0);
  }
  // SLEPc's pairs in the span of the constants (their eigenvalues are those of Q 1 = 0 as
  // rounded: tiny, or on debris with near-coincident points as large as 1e-5 of the
  // component's largest) are left out; the others are deflated (Constants::Deflate).
  int zeroModes = 0;
  for (int j = 0; j < slices && this->Found < m; ++j)
  {
    if (this->AnyCancelled())
    {
      throw spectral::Cancelled();
    }
    // Slices of [start, Upper], the first from Lower (below the zero eigenvalues, or a window's
    // lower end).
    const double start = this->Lower > 0.0 ? this->Lower : 0.0;
    const double from = j == 0 ? this->Lower : start + (this->Upper - start) * j / slices;
    const double to = start + (this->Upper - start) * (j + 1) / slices;
    OwnedEPS eps;
    const Slice slice = SolveSlice(eps, this->Ops.Q.Object, this->Ops.D.Object, from, to, slicing);
    this->Result.InertiaCount += static_cast<int>(slice.Count);
    this->Result.Computed += static_cast<int>(slice.Order.size());
    this->Result.Shifts += static_cast<int>(slice.Shifts);
    for (std::size_t c = 0; c < slice.Order.size() && this->Found < m; ++c)
    {
      MH_PETSC(EPSGetEigenvector(eps.Object, slice.Order[c].second, this->Current.Object, nullptr));
      if (constants.Deflate(this->Current.Object, 0.5) > 0.5)
      {
        ++zeroModes;
        continue;
      }
      NormalizeSign(this->Current.Object);
      this->Add(slice.Order[c].first);
    }
    this->Progress.Report(0.2 + 0.7 * this->Found / m);
  }
  this->TakeGram();
  if (zeroModes > this->Parts.Count)
  {
    throw std::runtime_error("SLEPc returned " + std::to_string(zeroModes) +
      " eigenvectors in the span of the constant harmonics of the " +
      std::to_string(this->Parts.Count) + " connected components: lower Tolerance");
  }
  if (this->Found < m)
  {
    throw std::runtime_error("SLEPc found " + std::to_string(this->Found - this->Zeros) +
      " non-zero eigenpairs below " + std::to_string(this->Upper / (this->S * this->S)) +
      ", where the inertia counts " + std::to_string(this->Below) + " eigenvalues (" +
      std::to_string(m - this->Zeros) + " needed besides the zero eigenvalues of the " +
      std::to_string(this->Zeros) + " connected components)");
  }
}

//------------------------------------------------------------------------------
// 7. The pairs decided by the acceptance module, as for the core's engine: the relative
// residual needs the whole spectrum's scale, the orthonormality the whole Gram matrix.
void Engine::Verify()
{
  this->Progress.Begin("Verify");
  const int m = this->M;
  const double reference = ResidualReference(this->Lambda, this->Checks->TraceOverMass);
  const EigenOptions defaults;
  const PairTolerances tolerances = { defaults.ResidualTolerance, defaults.BackwardErrorTolerance };
  Vector relative(m);
  for (int k = 0; k < m; ++k)
  {
    relative[k] = this->ResidualNorms[k] /
      std::max({ std::abs(this->Lambda[k]), reference, std::numeric_limits<double>::min() });
    this->Result.MaxResidual = std::max(this->Result.MaxResidual, relative[k]);
  }
  // On a badly conditioned mesh the residual tolerance is what double precision achieves.
  double ratio = 0.0;
  const double achievable =
    AchievableResidual(this->Checks->GershgorinTop, this->Diagonal / this->S, ratio);
  const Decision decision = AcceptPairs(this->Lambda / (this->S * this->S),
    relative,
    this->BackwardErrors,
    tolerances,
    achievable,
    ratio);
  if (!decision.Warning.empty())
  {
    this->Warn(decision.Warning);
  }
  if (decision.Outcome == Verdict::Fail)
  {
    throw std::runtime_error(decision.Error + (decision.Resolvable ? ": lower Tolerance" : ""));
  }
  DenseMatrix gram(m, m);
  MPI_Allreduce(this->Gram.data(), gram.data(), m * m, MPI_DOUBLE, MPI_SUM, this->Comm);
  gram = gram.selfadjointView<Eigen::Upper>();
  this->Result.OrthonormalityError = GramError(gram);
  if (!Orthonormal(this->Result.OrthonormalityError, decision.ResidualTolerance))
  {
    // On badly conditioned operators (debris of a few triangles holding a near-coincident
    // point: masses spanning 1e8, eigenvalues 1e17) the orthogonalization in the D inner
    // product loses what a lower Tolerance cannot bring back.
    const std::string remedy = achievable > tolerances.Residual ? "; " + BadConditioning(ratio) +
        ": merge close points (vtkCleanPolyData, Clean, with a tolerance), or use the Built-in "
        "solver, which solves each connected component on its own"
                                                                : ": lower Tolerance";
    throw std::runtime_error("the eigenvectors are D-orthonormal to " +
      std::to_string(this->Result.OrthonormalityError) + " only" + remedy);
  }
  this->Progress.Report(0.95);
}

//------------------------------------------------------------------------------
// 8. The eigenvalues, and the mass and the duplicate flags of this piece's points.
void Engine::Write(Eigen::Index rows)
{
  this->Progress.Begin("Write");
  const double s = this->S;
  this->Result.Eigenvalues = this->Lambda / (s * s);
  this->Result.Mass = Vector::Zero(rows);
  this->Result.Duplicate.assign(static_cast<std::size_t>(rows), 0);
  const double measureScale = std::pow(s, this->Dimension);
  Vector& mass = this->Result.Mass;
  this->Writer->Write(this->Ops.Lumped.Object,
    [&](Eigen::Index row, double value) { mass[row] = value * measureScale; });
  const std::vector<int>& ids = this->Prepared.InputPointIds;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    this->Result.Duplicate[static_cast<std::size_t>(ids[i])] = this->Numbers.Owned[i] ? 0 : 1;
  }
  // Components that no harmonic represents (more components than m, in a basis that starts at
  // the zero eigenvalues: a window above 0 holds no constant): zero mass as well, as in the core
  // (Basis.cxx, LeaveOutUnrepresented), so that the filters pass their points through.
  if (this->Result.FirstIndex == 0 && this->Zeros < this->Parts.Count)
  {
    std::vector<char> represented(static_cast<std::size_t>(this->Parts.Count), 0);
    for (int r = 0; r < this->Zeros; ++r)
    {
      represented[this->Parts.Order[r]] = 1;
    }
    long long left = 0;
    for (int j = 0; j < this->Parts.Count; ++j)
    {
      left += represented[j] ? 0 : this->Parts.Points[j];
    }
    for (std::size_t i = 0; i < ids.size(); ++i)
    {
      if (!represented[this->Parts.Label[i]])
      {
        mass[ids[i]] = 0.0;
      }
    }
    this->Warn(std::to_string(left) + " points of components that none of the " +
      std::to_string(this->M) +
      " harmonics represents have zero harmonics and mass: the filters pass them through "
      "unchanged.");
  }
  this->Result.UpperEnd = this->Upper / (s * s);
  this->Progress.Report(1.0);
}
} // anonymous namespace
} // namespace distributed

//------------------------------------------------------------------------------
DistributedResult SolveDistributed(MPI_Comm comm,
  const TriangleMesh& piece,
  const DistributedOptions& options,
  const Monitor& monitor)
{
  distributed::Initialize();
  const distributed::Session session(options.Options);
  distributed::Engine engine(comm, options, monitor);
  engine.Piece(piece);
  engine.Number();
  engine.Assemble();
  engine.ZeroModes();
  engine.Interval();
  engine.Eigensolve(piece.Vertices.rows());
  engine.Verify();
  engine.Write(piece.Vertices.rows());
  return std::move(engine.Result);
}
} // namespace spectral
