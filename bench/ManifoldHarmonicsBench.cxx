// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * Benchmark of the manifold harmonic basis: for each (n, m) case it builds a noisy torus of about
 * n points, assembles the cotan stiffness and lumped mass, computes the m smallest eigenpairs and
 * prints one table row: n, m, wall time and its split, peak resident memory, the largest relative
 * residual and the M-orthonormality error. With --scipy it also solves the same matrices with
 * scipy.sparse.linalg.eigsh in shift-invert mode (through /usr/bin/python3) and prints the speed
 * ratio and the largest eigenvalue difference; with --slepc, SLEPc's Krylov-Schur with a MUMPS
 * factor the same way, nearest a target and by spectrum slicing (slepc_reference.py, Debian's
 * python3-slepc4py), and the ratio to the fastest peer that agrees (PeerAgreement). With
 * --factor it times the factorization of L - sigma M, the solver's against MUMPS's, and the
 * solver's solves of blocks of 4 to 16 right-hand sides (FactorComparison).
 *
 * Each case runs in a child process so that its peak memory is its own.
 *
 * With --filter it also times the filter stage (gains, inverse transform and re-injection of
 * the point coordinates), the part that re-runs when a user changes the filter, through the
 * same core call as vtkSpectralFilter (spectral::FilterSignal), on 1 and 2 threads, with the
 * basis in double and in float (BasisPrecision).
 *
 * With --scan the torus carries the defects of a real range scan (near-coincident points,
 * needles, zero-area triangles, islands; see CaseMesh). --threads T sets the eigensolver's
 * threads (default 0: every core). --eigenvalues-only computes the spectrum alone
 * (BasisOptions::EigenvaluesOnly: no harmonics kept; the orthonormality column is then "-").
 *
 * With --volume the mesh is a tetrahedral unit ball of about n points (Testing/Core/Meshes.h,
 * TetrahedralBall: a cube of Kuhn tetrahedra mapped radially) instead of the torus, and the row
 * ends with the entries of the LDL^T factor per row (its fill-in: a volume's factor fills far
 * more than a surface's).
 *
 * With --cloud the torus's points alone, without its triangles, go through the point-cloud
 * Laplacian (spectral::PointCloudLaplacian, NumberOfNeighbors 30), whose steps are timed apart
 * (neighbours, local triangulations, intrinsic Delaunay flips and operators), and are solved
 * component by component with the eigensolver as ComputeBasis does (without its two fallbacks
 * and its change of units, which the torus of size 1 does not need).
 *
 * Usage: ManifoldHarmonicsBench [--case N:M]... [--band K] [--scan] [--volume] [--cloud]
 *        [--threads T] [--filter] [--eigenvalues-only] [--scipy] [--slepc] [--factor]
 *        [--scipy-max-n N]
 *        [--workdir DIR]
 * Default cases: 10000:100 100000:500.
 */
#include "Basis.h"
#include "Common/Defaults.h"
#include "Common/Eigenvalues.h"
#include "Common/Threads.h"
#include "Filtering/Transfer.h"
#include "Meshes.h"
#include "Operators/PointCloud.h"
#include "Solver/Bands.h"
#include "Solver/SupernodalLDLT.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

/// A peer's eigenvalues agree with the product's when their largest relative difference
/// (PeerDifference) is at most this; only agreeing peers count for the speed ratio.
constexpr double PeerAgreement = 1e-6;

struct Settings
{
  std::vector<std::pair<int, int>> Cases;
  int BandSize = 0;
  bool Scipy = false;
  bool Slepc = false;
  /// Also compare the factorization with MUMPS's (FactorComparison).
  bool Factor = false;
  bool Filter = false;
  int ScipyMaxN = 200000;
  /// The torus with the defects of a range scan (ScanMesh).
  bool Scan = false;
  /// A tetrahedral ball instead of the torus.
  bool Volume = false;
  /// The torus's points as a cloud (PointCloudLaplacian) instead of its triangles.
  bool Cloud = false;
  /// Threads of the eigensolver; 0 = every core.
  int Threads = 0;
  /// The spectrum alone (BasisOptions::EigenvaluesOnly).
  bool EigenvaluesOnly = false;
  std::string WorkDir = "/tmp";
  std::string ScriptDir = ".";
};

double Since(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Write a sparse symmetric matrix in Matrix Market coordinate format (lower triangle).
void WriteMatrixMarket(const spectral::SparseMatrix& A, const std::string& path)
{
  std::ofstream out(path);
  int entries = 0;
  for (int j = 0; j < A.outerSize(); ++j)
  {
    for (spectral::SparseMatrix::InnerIterator it(A, j); it; ++it)
    {
      entries += (it.row() >= it.col()) ? 1 : 0;
    }
  }
  out << "%%MatrixMarket matrix coordinate real symmetric\n";
  out << A.rows() << " " << A.cols() << " " << entries << "\n";
  out.precision(17);
  for (int j = 0; j < A.outerSize(); ++j)
  {
    for (spectral::SparseMatrix::InnerIterator it(A, j); it; ++it)
    {
      if (it.row() >= it.col())
      {
        out << it.row() + 1 << " " << it.col() + 1 << " " << it.value() << "\n";
      }
    }
  }
}

/// The wall time (negative if the file is missing or empty) and the eigenvalues a reference
/// script wrote to `path` (scipy_reference.py, slepc_reference.py); removes the file.
double ReadPeerOutput(const std::string& path, std::vector<double>& lambda)
{
  std::ifstream in(path);
  double seconds = -1.0;
  if (!(in >> seconds))
  {
    return -1.0;
  }
  double value = 0.0;
  while (in >> value)
  {
    lambda.push_back(value);
  }
  std::remove(path.c_str());
  return seconds;
}

/// One peer's solve of the case's matrices: its wall time (negative on failure) and eigenvalues.
struct PeerRun
{
  std::string Name;
  double Seconds = -1.0;
  std::vector<double> Lambda;
};

/// A case's matrices in Matrix Market files under WorkDir, for the reference scripts: written
/// once for all of them, removed with this object. Base is the prefix of every file of the case.
struct MatrixFiles
{
  MatrixFiles(const Settings& settings,
    const spectral::SparseMatrix& L,
    const spectral::SparseMatrix& M)
    : Base(settings.WorkDir + "/mh-bench-" + std::to_string(getpid()))
  {
    WriteMatrixMarket(L, this->Base + "-L.mtx");
    WriteMatrixMarket(M, this->Base + "-M.mtx");
  }
  ~MatrixFiles()
  {
    std::remove((this->Base + "-L.mtx").c_str());
    std::remove((this->Base + "-M.mtx").c_str());
  }
  MatrixFiles(const MatrixFiles&) = delete;
  MatrixFiles& operator=(const MatrixFiles&) = delete;

  /// The scripts' first two arguments, and a space.
  std::string Paths() const { return this->Base + "-L.mtx " + this->Base + "-M.mtx "; }

  const std::string Base;
};

/**
 * The peers on the same matrices, one after the other (one sitting): scipy's eigsh as LaPy
 * calls it (`--scipy`), and SLEPc's Krylov-Schur with a MUMPS factor (`--slepc`), nearest the
 * target and by spectrum slicing over [-0.01, lambda_{m-1} (1 + 1e-6)], the product's own
 * interval.
 */
std::vector<PeerRun> RunPeers(const Settings& settings,
  const MatrixFiles& files,
  int m,
  double upper)
{
  const std::string& base = files.Base;
  const std::string matrices = files.Paths() + std::to_string(m) + " ";
  std::vector<PeerRun> runs;
  if (settings.Scipy)
  {
    const std::string command = "/usr/bin/python3 " + settings.ScriptDir + "/scipy_reference.py " +
      matrices + base + "-scipy.txt";
    PeerRun run;
    run.Name = "scipy";
    if (std::system(command.c_str()) == 0)
    {
      run.Seconds = ReadPeerOutput(base + "-scipy.txt", run.Lambda);
    }
    runs.push_back(run);
  }
  if (settings.Slepc)
  {
    char interval[32];
    std::snprintf(interval, sizeof(interval), "%.17g ", upper);
    const std::string command = "/usr/bin/python3 " + settings.ScriptDir + "/slepc_reference.py " +
      matrices + interval + base + "-target.txt " + base + "-slicing.txt";
    const int status = std::system(command.c_str());
    for (const char* way : { "target", "slicing" })
    {
      PeerRun run;
      run.Name = std::string("slepc-") + way;
      const std::string output = base + "-" + way + ".txt";
      run.Seconds = ReadPeerOutput(output, run.Lambda);
      std::remove(output.c_str());
      if (status != 0 && run.Lambda.empty())
      {
        run.Seconds = -1.0;
      }
      runs.push_back(run);
    }
  }
  return runs;
}

/**
 * How the solves of the factor `ldlt` (factored, `rows` rows) grow with the number of right-hand
 * sides: the median of 21 solves of 4, 8, 12 and 16 random columns, in milliseconds, on `threads`
 * threads (0: every core) and on one. A solve bound by reading the factor would take about the same
 * time for every width; one bound by its arithmetic, a time in proportion to the width.
 */
std::string SolveWidths(spectral::SupernodalLDLT& ldlt, Eigen::Index rows, int threads)
{
  std::string out;
  char buffer[128];
  const int restore = ldlt.GetThreads();
  // The given threads, then one (a single row with --threads 1).
  const std::vector<int> counts =
    threads == 1 ? std::vector<int>{ 1 } : std::vector<int>{ threads, 1 };
  for (const int t : counts)
  {
    ldlt.SetThreads(t);
    std::snprintf(buffer,
      sizeof(buffer),
      "; solves of 4/8/12/16 columns, %s:",
      t == 1 ? "1 thread" : "threads");
    out += buffer;
    for (const int columns : { 4, 8, 12, 16 })
    {
      const spectral::DenseMatrix B = spectral::DenseMatrix::Random(rows, columns);
      std::vector<double> seconds;
      for (int k = 0; k < 21; ++k)
      {
        const Clock::time_point start = Clock::now();
        const spectral::DenseMatrix X = ldlt.Solve(B);
        seconds.push_back(Since(start));
      }
      std::nth_element(seconds.begin(), seconds.begin() + 10, seconds.end());
      std::snprintf(buffer, sizeof(buffer), " %.1f", 1e3 * seconds[10]);
      out += buffer;
    }
    out += " ms";
  }
  ldlt.SetThreads(restore);
  return out;
}

/**
 * The factorization of L - sigma M by the solver's SupernodalLDLT and by MUMPS (mumps_reference.py,
 * through PETSc), at the same shifts: -0.01 (below the spectrum, scipy's shift), the middle of
 * the pairs (between lambda_{j-1} and lambda_j for the first j >= m/2 where they differ by more
 * than 1e-6 relative) and the top (the same for the last such j <= m - 1), in that order. For each:
 * the seconds of the numerical factorization (MUMPS's first includes its analysis; the solver's
 * analysis, CHOLMOD's, is given apart), the negative pivots (which must agree) and the seconds of
 * solving FactorColumns random right-hand sides; then, at the top shift, the solver's solves of
 * 4 to 16 right-hand sides (SolveWidths).
 */
constexpr int FactorColumns = 16;
std::string FactorComparison(const Settings& settings,
  const MatrixFiles& files,
  const spectral::SparseMatrix& L,
  const spectral::SparseMatrix& M,
  const spectral::Vector& lambda)
{
  const Eigen::Index m = lambda.size();
  std::vector<double> shifts = { -0.01 };
  if (m >= 2)
  {
    // Between two distinct eigenvalues: a symmetric mesh (the ball) has multiple ones, and at
    // a shift inside a multiplet the count is decided by rounding.
    const auto distinct = [&lambda](Eigen::Index k)
    { return lambda[k] - lambda[k - 1] >= 1e-6 * std::abs(lambda[k]); };
    Eigen::Index middle = m / 2;
    while (middle + 1 < m && !distinct(middle))
    {
      ++middle;
    }
    Eigen::Index top = m - 1;
    while (top > 1 && !distinct(top))
    {
      --top;
    }
    shifts.push_back(0.5 * (lambda[middle - 1] + lambda[middle]));
    shifts.push_back(0.5 * (lambda[top - 1] + lambda[top]));
  }
  char buffer[256];
  std::string out;
  Clock::time_point start = Clock::now();
  spectral::SupernodalLDLT ldlt(L);
  ldlt.SetThreads(settings.Threads);
  std::snprintf(buffer,
    sizeof(buffer),
    "\n%17s factor, solve %d columns, negative pivots: ours "
    "(analysis %.2f s)",
    "",
    FactorColumns,
    Since(start));
  out += buffer;
  const spectral::DenseMatrix B = spectral::DenseMatrix::Random(L.rows(), FactorColumns);
  std::vector<int> ours;
  for (const double sigma : shifts)
  {
    const spectral::SparseMatrix A = L - sigma * M;
    start = Clock::now();
    const bool factored = ldlt.Factorize(A);
    const double factor = Since(start);
    start = Clock::now();
    const spectral::DenseMatrix X = factored ? ldlt.Solve(B) : spectral::DenseMatrix();
    const double solve = Since(start);
    ours.push_back(factored ? ldlt.NegativePivots() : -1);
    std::snprintf(buffer, sizeof(buffer), "  %.3f s, %.3f s, %d", factor, solve, ours.back());
    out += buffer;
  }
  // Timed before MUMPS runs, printed after its figures.
  const std::string widths =
    !ours.empty() && ours.back() >= 0 ? SolveWidths(ldlt, L.rows(), settings.Threads) : "";
  const std::string& base = files.Base;
  std::string command = "/usr/bin/python3 " + settings.ScriptDir + "/mumps_reference.py " +
    files.Paths() + std::to_string(FactorColumns) + " " + base + "-mumps.txt";
  for (const double sigma : shifts)
  {
    std::snprintf(buffer, sizeof(buffer), " %.17g", sigma);
    command += buffer;
  }
  const int status = std::system(command.c_str());
  out += "; MUMPS";
  std::ifstream in(base + "-mumps.txt");
  double sigma = 0.0;
  double factor = 0.0;
  int negative = 0;
  double solve = 0.0;
  std::size_t k = 0;
  while (status == 0 && in >> sigma >> factor >> negative >> solve)
  {
    std::snprintf(buffer,
      sizeof(buffer),
      "  %.3f s, %.3f s, %d%s",
      factor,
      solve,
      negative,
      k < ours.size() && ours[k] == negative ? "" : " (differs)");
    out += buffer;
    ++k;
  }
  if (k != shifts.size())
  {
    out += "  failed";
  }
  std::remove((base + "-mumps.txt").c_str());
  return out + widths;
}

/**
 * The largest relative difference between the first m eigenvalues of a peer and the product's:
 * relative to |lambda|, and, for the zero eigenvalues of the constant harmonics, to the first
 * non-zero eigenvalue lambda_1 (zero by IsZeroEigenvalue at lambda_{m-1}, the solver's rule; 1e-6
 * lambda_{m-1} if all are). A peer returns those zeros as round-off of either sign, whose size
 * follows the top of the whole spectrum: scipy's were up to 7.2e-9 against lambda_{m-1} = 36 on
 * the 100K scan model (`--scan --case 100000:200`), whose needles and tiny masses bound that top
 * by 1.8e13 (Gershgorin). Infinity when the peer found fewer than m.
 */
double PeerDifference(const std::vector<double>& reference, const spectral::Vector& lambda)
{
  const int m = static_cast<int>(lambda.size());
  if (static_cast<int>(reference.size()) < m)
  {
    return std::numeric_limits<double>::infinity();
  }
  const double top = m > 0 ? std::abs(lambda[m - 1]) : 0.0;
  double firstNonZero = 1e-6 * top;
  for (int k = 0; k < m; ++k)
  {
    if (!spectral::IsZeroEigenvalue(std::abs(lambda[k]), top))
    {
      firstNonZero = std::abs(lambda[k]);
      break;
    }
  }
  double difference = 0.0;
  for (int k = 0; k < m; ++k)
  {
    const bool zero = spectral::IsZeroEigenvalue(std::abs(lambda[k]), top);
    difference = std::max(
      difference, std::abs(reference[k] - lambda[k]) / (zero ? firstNonZero : std::abs(lambda[k])));
  }
  return difference;
}

/**
 * Median wall time in milliseconds of a re-run of the filter stage for the point coordinates,
 * the code path of vtkSpectralFilter::RequestData for one signal: the gains of a low pass, the
 * mean gain above the basis up to the Nyquist frequency (computed once: the filter keeps it
 * while its input does not change), then spectral::FilterSignal, which runs the inverse
 * transform with re-injection on `threads` threads (0 in the filter: automatic) on the basis in
 * place, stored point by point (n by m, row-major) as the VTK array holds it.
 * Not timed: the VTK side (shallow copies, wrapping the arrays, writing the output array).
 */
template<typename View>
double FilterStageMilliseconds(const View& H,
  const spectral::TriangleMesh& mesh,
  const spectral::Vector& lambda,
  const spectral::Vector& mass,
  const spectral::RowMatrix& points,
  const spectral::RowMatrix& coefficients,
  int threads)
{
  spectral::FilterParameters parameters;
  parameters.Kind = spectral::FilterKind::LowPass;
  parameters.Cutoff = spectral::DefaultCutoffFraction;
  // The default of vtkSpectralFilter: half the highest computed frequency.
  parameters =
    spectral::ToAbsoluteUnits(parameters, spectral::FrequencyUnits::FractionOfHighest, lambda, 0.0);
  const spectral::ConstRowView X(points.data(), points.rows(), points.cols());
  const spectral::ConstRowView C(coefficients.data(), coefficients.rows(), coefficients.cols());
  const double nyquist = spectral::NyquistFrequency(mesh);
  std::vector<double> samples;
  double checksum = 0.0;
  for (int repeat = 0; repeat < 21; ++repeat)
  {
    const Clock::time_point start = Clock::now();
    const spectral::Vector gains = spectral::Gains(parameters, lambda);
    const double hf =
      spectral::MeanGain(parameters, std::sqrt(std::max(lambda.maxCoeff(), 0.0)), nyquist);
    const spectral::RowMatrix filtered = spectral::FilterSignal(H, mass, gains, C, X, hf, threads);
    samples.push_back(1000.0 * Since(start));
    checksum += filtered(0, 0);
  }
  if (!std::isfinite(checksum))
  {
    std::printf("filter stage: non-finite result\n");
  }
  std::sort(samples.begin(), samples.end());
  return samples[samples.size() / 2];
}

/// The filter-stage column: 1 and 2 threads, on the double basis and on its float copy, for the
/// coordinates `points` (one row per row of the basis and of `mass`).
std::string FilterStageColumn(const spectral::TriangleMesh& mesh,
  const spectral::DenseMatrix& harmonics,
  const spectral::Vector& eigenvalues,
  const spectral::Vector& mass,
  const spectral::RowMatrix& points)
{
  const spectral::RowMatrix basis = harmonics;
  const spectral::BasisView H(basis.data(), basis.rows(), basis.cols());
  const spectral::RowMatrix coefficients = spectral::ForwardTransform(
    H, mass, spectral::ConstRowView(points.data(), points.rows(), points.cols()));
  const double double1 =
    FilterStageMilliseconds(H, mesh, eigenvalues, mass, points, coefficients, 1);
  const double double2 =
    FilterStageMilliseconds(H, mesh, eigenvalues, mass, points, coefficients, 2);
  const spectral::FloatRowMatrix floats = basis.cast<float>();
  const spectral::FloatBasisView Hf(floats.data(), floats.rows(), floats.cols());
  const double float1 =
    FilterStageMilliseconds(Hf, mesh, eigenvalues, mass, points, coefficients, 1);
  const double float2 =
    FilterStageMilliseconds(Hf, mesh, eigenvalues, mass, points, coefficients, 2);
  char buffer[160];
  std::snprintf(buffer,
    sizeof(buffer),
    "  filter %.1f ms (1 thread) %.1f ms (2 threads), float basis %.1f ms (1) %.1f ms (2)",
    double1,
    double2,
    float1,
    float2);
  return buffer;
}

/**
 * The mesh of a case: a noisy torus of about n points or, with --scan, the same torus with the
 * defects of a range scan in the proportions of a 437,000-point scan: a near-coincident point
 * and a needle every 1,000 points, 108 zero-area triangles and 150 islands of 3 to 80 points.
 */
spectral::TriangleMesh CaseMesh(const Settings& settings, int n)
{
  if (settings.Volume)
  {
    // (k + 1)^3 points.
    const int k = std::max(1, static_cast<int>(std::lround(std::cbrt(static_cast<double>(n)))) - 1);
    return spectral::testing::TetrahedralBall(k);
  }
  const spectral::TriangleMesh torus = spectral::testing::NoisyTorusOfSize(n, 0.02);
  if (!settings.Scan)
  {
    return torus;
  }
  spectral::testing::ScanDefects defects;
  defects.NearCoincident = n / 1000;
  defects.Needles = n / 1000;
  defects.ZeroArea = 108;
  defects.Islands = 150;
  return spectral::testing::WithScanDefects(torus, defects);
}

/**
 * The basis of a cloud: PointCloudLaplacian, with the seconds of each of its steps in `steps`,
 * then the m smallest eigenpairs one component at a time, as ComputeBasis solves a mesh's
 * operators (one pair is solved as the first of two).
 */
spectral::BasisResult CloudBasis(const Settings& settings,
  const spectral::Points& cloud,
  int m,
  spectral::DiscreteLaplacian& ops,
  std::string& steps)
{
  const Clock::time_point start = Clock::now();
  std::vector<std::pair<std::string, Clock::time_point>> stages;
  spectral::Monitor monitor;
  monitor.Stage = [&stages](const char* stage) { stages.emplace_back(stage, Clock::now()); };
  {
    const spectral::ScopedThreadLimit limit(settings.Threads);
    ops = spectral::PointCloudLaplacian(cloud, spectral::PointCloudOptions(), monitor);
  }
  spectral::BasisResult basis;
  basis.AssemblySeconds = Since(start);
  stages.emplace_back("", Clock::now());
  steps = "  cloud:";
  for (std::size_t s = 0; s + 1 < stages.size(); ++s)
  {
    char buffer[96];
    std::snprintf(buffer,
      sizeof(buffer),
      " %s %.2f s",
      stages[s].first.c_str(),
      std::chrono::duration<double>(stages[s + 1].second - stages[s].second).count());
    steps += buffer;
  }
  spectral::EigenOptions options;
  options.BandSize = settings.BandSize;
  options.Threads = settings.Threads;
  const spectral::PairSolver solve = [&options](const spectral::SparseMatrix& L,
                                       const spectral::SparseMatrix& M,
                                       const spectral::PairRequest& request,
                                       const spectral::Monitor& part)
  {
    const int k = request.Count;
    spectral::EigenOptions each = options;
    each.NumberOfEigenpairs = (k == 1 && L.rows() > 1) ? 2 : k;
    spectral::EigenResult r = spectral::SmallestEigenpairs(L, M, each, part);
    r.Eigenvalues.conservativeResize(k);
    r.Eigenvectors.conservativeResize(Eigen::NoChange, k);
    return r;
  };
  basis.Pairs = spectral::SmallestEigenpairsByComponent(ops.Stiffness,
    ops.Mass,
    ops.LumpedMass,
    ops.Components.Label,
    ops.Components.Count,
    std::min(m, static_cast<int>(ops.Stiffness.rows())),
    solve);
  return basis;
}

/// One case, run in the child process. Prints its row and returns an exit code.
int RunCase(const Settings& settings, int n, int m)
{
  const spectral::TriangleMesh mesh = CaseMesh(settings, n);
  const Clock::time_point start = Clock::now();
  // What vtkManifoldHarmonicBasis runs: the core's one entry point.
  spectral::BasisOptions options;
  options.NumberOfHarmonics = m;
  options.Solver.BandSize = settings.BandSize;
  options.Solver.Threads = settings.Threads;
  options.EigenvaluesOnly = settings.EigenvaluesOnly;
  spectral::BasisResult basis;
  spectral::DiscreteLaplacian ops;
  std::string steps = "";
  try
  {
    if (settings.Cloud)
    {
      basis = CloudBasis(settings, mesh.Vertices, m, ops, steps);
    }
    else
    {
      basis = spectral::ComputeBasis(mesh, options);
    }
  }
  catch (const std::exception& e)
  {
    std::printf("%8d %6d  failed: %s\n", static_cast<int>(mesh.Vertices.rows()), m, e.what());
    std::fflush(stdout);
    return 1;
  }
  const double total = Since(start);
  const double assembly = basis.AssemblySeconds;
  const spectral::EigenResult& result = basis.Pairs;
  if (!settings.Cloud)
  {
    // The same operators again, untimed, for the checks and for scipy.
    ops = spectral::AssembleLaplacian(spectral::PrepareMesh(mesh), options.Operators);
  }
  const spectral::SparseMatrix& L = ops.Stiffness;
  const spectral::SparseMatrix& M = ops.Mass;
  const bool vectors = result.Eigenvectors.cols() > 0;
  // The harmonics on every row of the operators: the basis leaves out the rows of the
  // components none of its harmonics represents (more components than harmonics, a scan's
  // islands), whose harmonics are zero. Both name their rows by input point.
  spectral::DenseMatrix allRows;
  if (vectors && result.Eigenvectors.rows() != L.rows() &&
    ops.InputPointIds.size() == static_cast<std::size_t>(L.rows()))
  {
    std::vector<Eigen::Index> rowOf(mesh.Vertices.rows(), -1);
    for (std::size_t j = 0; j < ops.InputPointIds.size(); ++j)
    {
      rowOf[static_cast<std::size_t>(ops.InputPointIds[j])] = static_cast<Eigen::Index>(j);
    }
    allRows = spectral::DenseMatrix::Zero(L.rows(), result.Eigenvectors.cols());
    for (std::size_t r = 0; r < basis.InputPointIds.size(); ++r)
    {
      allRows.row(rowOf[static_cast<std::size_t>(basis.InputPointIds[r])]) =
        result.Eigenvectors.row(static_cast<Eigen::Index>(r));
    }
  }
  const spectral::DenseMatrix& harmonics = allRows.size() ? allRows : result.Eigenvectors;
  char orthogonality[16] = "       -";
  if (vectors)
  {
    std::snprintf(
      orthogonality, sizeof(orthogonality), "%8.1e", spectral::OrthonormalityError(harmonics, M));
  }

  std::string filter = steps;
  if (settings.Filter && vectors && !settings.Cloud)
  {
    // The points of the operators' rows (a scan's unused points have none).
    spectral::RowMatrix points(L.rows(), 3);
    for (Eigen::Index j = 0; j < L.rows(); ++j)
    {
      points.row(j) = mesh.Vertices.row(ops.InputPointIds[static_cast<std::size_t>(j)]);
    }
    filter = FilterStageColumn(mesh, harmonics, result.Eigenvalues, M.diagonal(), points);
  }

  if (settings.Volume)
  {
    // The fill-in of the factor of L - sigma M (the symbolic analysis alone, untimed).
    const spectral::SupernodalLDLT symbolic(L);
    char buffer[64];
    std::snprintf(buffer,
      sizeof(buffer),
      "  factor %.0f entries/row",
      static_cast<double>(symbolic.FactorEntries()) / static_cast<double>(L.rows()));
    filter += buffer;
  }

  std::string peers = "";
  const bool runPeers = (settings.Scipy || settings.Slepc) && L.rows() <= settings.ScipyMaxN;
  const bool compareFactor = settings.Factor && !settings.Cloud;
  std::unique_ptr<MatrixFiles> files;
  if (runPeers || compareFactor)
  {
    files = std::make_unique<MatrixFiles>(settings, L, M);
  }
  if (runPeers)
  {
    const double upper = result.Eigenvalues[m - 1] * (1.0 + 1e-6);
    double fastest = std::numeric_limits<double>::infinity();
    std::string fastestName;
    for (const PeerRun& run : RunPeers(settings, *files, m, upper))
    {
      char buffer[160];
      const double difference = PeerDifference(run.Lambda, result.Eigenvalues);
      if (run.Seconds < 0.0)
      {
        std::snprintf(buffer, sizeof(buffer), "  %s failed", run.Name.c_str());
      }
      else
      {
        std::snprintf(buffer,
          sizeof(buffer),
          "  %s %.2f s x%.1f (%d pairs, max|dlambda|/lambda %.1e)",
          run.Name.c_str(),
          run.Seconds,
          run.Seconds / total,
          static_cast<int>(run.Lambda.size()),
          difference);
        if (difference <= PeerAgreement && run.Seconds < fastest)
        {
          fastest = run.Seconds;
          fastestName = run.Name;
        }
      }
      peers += buffer;
    }
    if (!fastestName.empty())
    {
      char buffer[96];
      std::snprintf(buffer,
        sizeof(buffer),
        "  fastest agreeing peer %s: x%.1f",
        fastestName.c_str(),
        fastest / total);
      peers += buffer;
    }
  }

  if (compareFactor)
  {
    peers += FactorComparison(settings, *files, L, M, result.Eigenvalues);
  }

  std::printf("%8d %6d %8.2f %7.2f %7.2f %7.2f %7.2f %7.2f %7.2f %5d %7lld %8.1e %8.1e %s%s\n",
    static_cast<int>(L.rows()),
    m,
    total,
    assembly,
    result.Seconds.Factorization,
    result.Seconds.Solve,
    result.Seconds.Orthogonalization,
    result.Seconds.RayleighRitz,
    result.Seconds.Verification,
    result.Bands,
    result.OperatorApplications,
    result.MaxResidual,
    result.MaxBackwardError,
    orthogonality,
    (filter + peers).c_str());
  // What the solver held of its eigenvectors at most, against the three bands the memory
  // estimate counts when it does not keep them (Solver/Memory.h).
  // and the widest Krylov basis of a band, which a retry does not widen (RetryPairs, Bands.h).
  std::printf("%17s most eigenvector columns held %d (three bands: %d), widest Krylov basis %d "
              "columns, %d band(s) run again\n",
    "",
    result.MostKeptVectors,
    3 * spectral::detail::PairsPerBand(m, settings.BandSize, L.rows()),
    result.MostKrylovColumns,
    result.Retries);
  std::fflush(stdout);
  return 0;
}

Settings Parse(int argc, char* argv[])
{
  const auto usage = [argv]()
  {
    std::fprintf(stderr,
      "usage: %s [--case N:M]... [--band K] [--scan] [--volume] [--cloud] [--threads T] "
      "[--filter] [--eigenvalues-only] [--scipy] [--slepc] [--factor] "
      "[--scipy-max-n N] [--workdir DIR]\n",
      argv[0]);
    std::exit(2);
  };
  // A whole argument as an integer of at least `least`; otherwise a message and the usage.
  const auto integer = [&usage](const std::string& option, const std::string& text, int least)
  {
    std::size_t used = 0;
    long value = 0;
    try
    {
      value = std::stol(text, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used == 0 || used != text.size() || value < least || value > INT_MAX)
    {
      std::fprintf(
        stderr, "%s: '%s' is not an integer >= %d\n", option.c_str(), text.c_str(), least);
      usage();
    }
    return static_cast<int>(value);
  };
  Settings settings;
  const std::string self = argv[0];
  const std::size_t slash = self.rfind('/');
  settings.ScriptDir = std::getenv("MH_BENCH_SCRIPTS")
    ? std::getenv("MH_BENCH_SCRIPTS")
    : (slash == std::string::npos ? "." : self.substr(0, slash));
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--case" && i + 1 < argc)
    {
      const std::string value = argv[++i];
      const std::size_t colon = value.find(':');
      if (colon == std::string::npos)
      {
        std::fprintf(stderr, "--case: '%s' is not N:M (points:harmonics)\n", value.c_str());
        usage();
      }
      settings.Cases.emplace_back(integer("--case N", value.substr(0, colon), 1),
        integer("--case M", value.substr(colon + 1), 1));
    }
    else if (arg == "--band" && i + 1 < argc)
    {
      settings.BandSize = integer("--band", argv[++i], 0);
    }
    else if (arg == "--scan")
    {
      settings.Scan = true;
    }
    else if (arg == "--volume")
    {
      settings.Volume = true;
    }
    else if (arg == "--cloud")
    {
      settings.Cloud = true;
    }
    else if (arg == "--threads" && i + 1 < argc)
    {
      settings.Threads = integer("--threads", argv[++i], 0);
    }
    else if (arg == "--eigenvalues-only")
    {
      settings.EigenvaluesOnly = true;
    }
    else if (arg == "--scipy")
    {
      settings.Scipy = true;
    }
    else if (arg == "--slepc")
    {
      settings.Slepc = true;
    }
    else if (arg == "--factor")
    {
      settings.Factor = true;
    }
    else if (arg == "--filter")
    {
      settings.Filter = true;
    }
    else if (arg == "--scipy-max-n" && i + 1 < argc)
    {
      settings.ScipyMaxN = integer("--scipy-max-n", argv[++i], 0);
    }
    else if (arg == "--workdir" && i + 1 < argc)
    {
      settings.WorkDir = argv[++i];
    }
    else
    {
      usage();
    }
  }
  if (settings.Cases.empty())
  {
    settings.Cases = { { 10000, 100 }, { 100000, 500 } };
  }
  return settings;
}
} // namespace

int main(int argc, char* argv[])
{
  const Settings settings = Parse(argc, argv);
  std::printf("%8s %6s %8s %7s %7s %7s %7s %7s %7s %5s %7s %8s %8s %8s\n",
    "n",
    "m",
    "wall[s]",
    "assem",
    "factor",
    "solve",
    "ortho",
    "ritz",
    "verify",
    "bands",
    "applies",
    "residual",
    "backward",
    "orthog");
  int failures = 0;
  for (const auto& c : settings.Cases)
  {
    std::fflush(stdout);
    const pid_t child = fork();
    if (child == 0)
    {
      std::_Exit(RunCase(settings, c.first, c.second));
    }
    int status = 0;
    struct rusage usage;
    wait4(child, &status, 0, &usage);
    std::printf("%17s peak RSS %.0f MB\n", "", usage.ru_maxrss / 1024.0);
    failures += (WIFEXITED(status) && WEXITSTATUS(status) == 0) ? 0 : 1;
  }
  return failures == 0 ? 0 : 1;
}
