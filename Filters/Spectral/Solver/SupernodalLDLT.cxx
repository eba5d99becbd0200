// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/SupernodalLDLT.h"
#include "Common/Threads.h"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <queue>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>

namespace spectral
{
namespace
{
using Stride = Eigen::OuterStride<>;
/// A column-major block of a supernode (or a part of it) in place.
using BlockView = Eigen::Map<DenseMatrix, 0, Stride>;
using ConstBlockView = Eigen::Map<const DenseMatrix, 0, Stride>;
using RowBlock = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using RowBlockView = Eigen::Map<RowBlock>;

/// Matrices of fewer rows are factored and solved on one thread: a thread costs more than it saves.
constexpr Eigen::Index ParallelRows = 2000;

/**
 * Factorize splits the elimination tree into subtrees of at most 1 / (SubtreesPerThread x
 * threads) of the work, factored whole by one thread each, largest first: enough pieces to keep
 * every thread busy while the separators above them wait for their children.
 */
constexpr double SubtreesPerThread = 8.0;

/// Columns of a supernode factored together by FactorPanel (a multiple of the SIMD width).
constexpr int PanelColumns = 64;

/// The tree-parallel solve splits subtrees until no thread has more than this times its share.
constexpr double SolveImbalance = 1.1;

/// The solves read the factor front to back, then back to front, fetching this many bytes ahead
/// (its index array a quarter of it): 32 KB measured best (4 KB to 128 KB tried).
constexpr std::ptrdiff_t PrefetchDistance = 32768;

/// Scratch space of the factorization: aligned (AlignedBuffer, Common/Mesh.h), so that the
/// rounding of a product does not depend on the thread that computes it.
using ScratchBuffer = AlignedBuffer;

/// Grow a scratch buffer to at least `size` entries and return its storage.
double* Scratch(ScratchBuffer& buffer, std::size_t size)
{
  if (buffer.size() < size)
  {
    buffer.resize(size);
  }
  return buffer.data();
}

/// Right-hand sides solved together by SolveRows: the width of one row of its block, a multiple
/// of 4 (one or more SIMD registers); fewer right-hand sides are padded with zeros.
constexpr int MaxWidth = 16;

/// The row width that holds `used` right-hand sides (at most MaxWidth): the next multiple of 4.
int PaddedWidth(Eigen::Index used)
{
  return static_cast<int>((used + 3) / 4 * 4);
}

/**
 * Rows index[k] - first of `base` (row-major, width W), k < count, minus the sum over j <
 * columns of l[j * stride + k] times row j of y: the forward update of the rows below a
 * supernode (first > 0: into a block that holds only the rows from `first` on).
 * Eight rows at a time, so that eight independent sums are under way (one sum alone waits for
 * each multiply-add before the next).
 */
template<int W>
void SubtractRows(double* base,
  int first,
  const int* index,
  int count,
  const double* l,
  int stride,
  int columns,
  const double* y)
{
  using Row = Eigen::Matrix<double, W, 1>;
  using ConstRowView = Eigen::Map<const Row>;
  int k = 0;
  for (; k + 8 <= count; k += 8)
  {
    Row a[8];
    for (int p = 0; p < 8; ++p)
    {
      a[p].setZero();
    }
    const double* lj = l + k;
    for (int j = 0; j < columns; ++j, lj += stride)
    {
      const Row yj = ConstRowView(y + static_cast<std::size_t>(j) * W);
      for (int p = 0; p < 8; ++p)
      {
        a[p] += lj[p] * yj;
      }
    }
    for (int p = 0; p < 8; ++p)
    {
      Eigen::Map<Row>(base + static_cast<std::size_t>(index[k + p] - first) * W) -= a[p];
    }
  }
  for (; k < count; ++k)
  {
    Row a = Row::Zero();
    const double* lj = l + k;
    for (int j = 0; j < columns; ++j, lj += stride)
    {
      a += *lj * ConstRowView(y + static_cast<std::size_t>(j) * W);
    }
    Eigen::Map<Row>(base + static_cast<std::size_t>(index[k] - first) * W) -= a;
  }
}

/**
 * x_q -= sum over i < count of l[q * stride + i] times row index[i] of Y (row-major, width W),
 * for the G rows x_q at x + q * W: the backward update of G columns of a supernode from the rows
 * below it. Each sum is split into P partial sums over interleaved rows: G * P independent
 * chains of multiply-adds, where one chain alone would wait for every multiply-add to finish.
 */
template<int W, int G, int P>
void GatherColumns(const double* Y,
  const int* index,
  int count,
  const double* l,
  int stride,
  double* x)
{
  using Row = Eigen::Matrix<double, W, 1>;
  using ConstRowView = Eigen::Map<const Row>;
  Row a[G][P];
  for (int k = 0; k < G; ++k)
  {
    for (int p = 0; p < P; ++p)
    {
      a[k][p].setZero();
    }
  }
  int i = 0;
  for (; i + P <= count; i += P)
  {
    for (int p = 0; p < P; ++p)
    {
      const Row z = ConstRowView(Y + static_cast<std::size_t>(index[i + p]) * W);
      for (int k = 0; k < G; ++k)
      {
        a[k][p] += l[static_cast<std::size_t>(k) * stride + i + p] * z;
      }
    }
  }
  for (; i < count; ++i)
  {
    const Row z = ConstRowView(Y + static_cast<std::size_t>(index[i]) * W);
    for (int k = 0; k < G; ++k)
    {
      a[k][0] += l[static_cast<std::size_t>(k) * stride + i] * z;
    }
  }
  for (int k = 0; k < G; ++k)
  {
    Row sum = a[k][0];
    for (int p = 1; p < P; ++p)
    {
      sum += a[k][p];
    }
    Eigen::Map<Row>(x + static_cast<std::size_t>(k) * W) -= sum;
  }
}

/**
 * Software prefetch of a stream read in order (forward for a positive distance, backward for a
 * negative one), `distance` bytes ahead of the reader: the factor's values and row indices,
 * read supernode after supernode in pieces too short for the hardware prefetcher to follow.
 */
class StreamPrefetch
{
public:
  /// The stream [begin, begin + bytes), read forward if distance > 0, backward if < 0.
  StreamPrefetch(const void* begin, std::size_t bytes, std::ptrdiff_t distance)
    : Begin(static_cast<const char*>(begin))
    , Size(static_cast<std::ptrdiff_t>(bytes))
    , Distance(distance)
    , Next(distance > 0 ? 0 : static_cast<std::ptrdiff_t>(bytes))
  {
  }

  /// Reading has reached `position`: fetch up to `distance` bytes beyond it.
  void Reached(const void* position)
  {
    const std::ptrdiff_t at = static_cast<const char*>(position) - this->Begin;
    if (this->Distance > 0)
    {
      const std::ptrdiff_t target = std::min(this->Size, at + this->Distance);
      for (; this->Next < target; this->Next += 64)
      {
        Fetch(this->Begin + this->Next);
      }
    }
    else
    {
      const std::ptrdiff_t target = std::max<std::ptrdiff_t>(0, at + this->Distance);
      while (this->Next > target)
      {
        this->Next = std::max(target, this->Next - 64);
        Fetch(this->Begin + this->Next);
      }
    }
  }

private:
  static void Fetch(const char* line)
  {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(line, 0, 2);
#else
    (void)line;
#endif
  }

  const char* Begin;
  std::ptrdiff_t Size;
  std::ptrdiff_t Distance;
  std::ptrdiff_t Next;
};

/// The prefetch of the supernodes [range.first, range.second) of one of the factor's arrays
/// (`start[s]`: where supernode s begins in it), read forward (distance > 0) or backward.
template<typename T, typename Offset>
StreamPrefetch FactorPart(const T* array,
  const std::vector<Offset>& start,
  std::pair<int, int> range,
  std::ptrdiff_t distance)
{
  const std::size_t first = static_cast<std::size_t>(start[static_cast<std::size_t>(range.first)]);
  const std::size_t last = static_cast<std::size_t>(start[static_cast<std::size_t>(range.second)]);
  return StreamPrefetch(array + first, (last - first) * sizeof(T), distance);
}

/**
 * The tasks of a factorization on several threads. The elimination tree is cut into subtrees of
 * at most 1 / (SubtreesPerThread x threads) of the work: the largest subtree is split until none
 * is larger, and the supernodes split off become tasks of one supernode each. A subtree is
 * factored whole by one thread in increasing supernode order (children come before parents); a
 * supernode above the cut becomes ready when the tasks of its children are done.
 */
struct TaskPlan
{
  /// The supernodes of the task rooted at t: Members[Start[t] .. Start[t+1]), increasing.
  std::vector<int> Start;
  std::vector<int> Members;
  /// Pending[t]: the children of t whose tasks are not done yet (0 for a subtree's root).
  std::vector<int> Pending;
  /// The roots of the subtrees, ready from the start, smallest work first.
  std::vector<int> Ready;
  /// Number of tasks.
  int Tasks = 0;
};

/// The tree given by `parent` (-1 at roots) as the cuts of PlanTasks and MakeSolvePlan start
/// from it: each node's children, and the roots with the work of their subtrees (subtreeWork).
struct Forest
{
  std::vector<std::vector<int>> Children;
  /// (work of the subtree, root), the heaviest on top.
  std::priority_queue<std::pair<double, int>> Largest;
  /// The work of all roots together.
  double Total = 0.0;
};

Forest MakeForest(const std::vector<int>& parent, const std::vector<double>& subtreeWork)
{
  Forest forest;
  forest.Children.resize(parent.size());
  for (std::size_t s = 0; s < parent.size(); ++s)
  {
    if (parent[s] == -1)
    {
      forest.Largest.emplace(subtreeWork[s], static_cast<int>(s));
      forest.Total += subtreeWork[s];
    }
    else
    {
      forest.Children[static_cast<std::size_t>(parent[s])].push_back(static_cast<int>(s));
    }
  }
  return forest;
}

/// Cut the tree given by `parent` (-1 at roots; children before parents) into tasks for
/// `threads` threads, subtreeWork[s] the work of the subtree rooted at s.
TaskPlan PlanTasks(const std::vector<int>& parent,
  const std::vector<double>& subtreeWork,
  int threads)
{
  const std::size_t count = parent.size();
  Forest forest = MakeForest(parent, subtreeWork);
  const std::vector<std::vector<int>>& children = forest.Children;
  std::priority_queue<std::pair<double, int>>& largest = forest.Largest;
  const double total = forest.Total;
  TaskPlan plan;
  plan.Pending.assign(count, 0);
  // owner[s]: the task of supernode s, its own index for the roots of tasks.
  std::vector<int> owner(count, -1);
  std::vector<std::pair<double, int>> subtrees;
  const double limit = total / (SubtreesPerThread * threads);
  while (!largest.empty())
  {
    const std::pair<double, int> top = largest.top();
    largest.pop();
    const std::vector<int>& below = children[static_cast<std::size_t>(top.second)];
    owner[static_cast<std::size_t>(top.second)] = top.second;
    ++plan.Tasks;
    if (top.first <= limit || below.empty())
    {
      subtrees.push_back(top);
      continue;
    }
    plan.Pending[static_cast<std::size_t>(top.second)] = static_cast<int>(below.size());
    for (const int child : below)
    {
      largest.emplace(subtreeWork[static_cast<std::size_t>(child)], child);
    }
  }
  std::sort(subtrees.begin(), subtrees.end());
  for (const std::pair<double, int>& subtree : subtrees)
  {
    plan.Ready.push_back(subtree.second);
  }
  // Below the cut, a supernode belongs to the task of its parent.
  plan.Start.assign(count + 1, 0);
  for (std::size_t s = count; s-- > 0;)
  {
    if (owner[s] == -1)
    {
      owner[s] = owner[static_cast<std::size_t>(parent[s])];
    }
    ++plan.Start[static_cast<std::size_t>(owner[s]) + 1];
  }
  for (std::size_t s = 0; s < count; ++s)
  {
    plan.Start[s + 1] += plan.Start[s];
  }
  plan.Members.resize(count);
  std::vector<int> next(plan.Start.begin(), plan.Start.end() - 1);
  for (std::size_t s = 0; s < count; ++s)
  {
    plan.Members[static_cast<std::size_t>(next[static_cast<std::size_t>(owner[s])]++)] =
      static_cast<int>(s);
  }
  return plan;
}

/**
 * Runs every task of a TaskPlan on up to `threads` threads (the calling thread is one of them),
 * each after the tasks of its children: run(task, thread), with thread in [0, threads), returns
 * false to stop. Ready tasks are taken from a stack under one mutex, which also orders the
 * writes of each task before the reads of its parent: the separators freed last go first (they
 * are on the longest path), then the largest subtree.
 */
template<typename Run>
class TaskRunner
{
public:
  TaskRunner(TaskPlan& plan, const std::vector<int>& parent, const Run& run)
    : Plan(plan)
    , Parent(parent)
    , Work(run)
    , Remaining(plan.Tasks)
  {
  }

  /// \return false if a run returned false (the other threads take no more tasks).
  /// \throws The first exception a run threw, after every thread has stopped.
  bool Execute(int threads)
  {
    std::vector<std::thread> helpers;
    for (int thread = 1; thread < threads; ++thread)
    {
      try
      {
        helpers.emplace_back(&TaskRunner::Loop, this, thread);
      }
      catch (const std::system_error&)
      {
        break; // no more threads to be had: the others take the tasks
      }
    }
    this->Loop(0);
    for (std::thread& helper : helpers)
    {
      helper.join();
    }
    if (this->Error)
    {
      std::rethrow_exception(this->Error);
    }
    return !this->Failed;
  }

private:
  void Loop(int thread)
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    try
    {
      for (;;)
      {
        this->Wake.wait(lock,
          [this]() { return this->Failed || this->Remaining == 0 || !this->Plan.Ready.empty(); });
        if (this->Failed || this->Remaining == 0)
        {
          return;
        }
        const int task = this->Plan.Ready.back();
        this->Plan.Ready.pop_back();
        lock.unlock();
        const bool done = this->Work(task, thread);
        lock.lock();
        this->Finished(task, done);
      }
    }
    catch (...)
    {
      if (!lock.owns_lock())
      {
        lock.lock();
      }
      this->Error = this->Error ? this->Error : std::current_exception();
      this->Failed = true;
      this->Wake.notify_all();
    }
  }

  /// Bookkeeping after a task, under the mutex: its parent may become ready.
  void Finished(int task, bool done)
  {
    const int up = this->Parent[static_cast<std::size_t>(task)];
    this->Failed = this->Failed || !done;
    if (--this->Remaining == 0 || !done)
    {
      this->Wake.notify_all();
    }
    else if (up != -1 && --this->Plan.Pending[static_cast<std::size_t>(up)] == 0)
    {
      this->Plan.Ready.push_back(up);
      this->Wake.notify_one();
    }
  }

  TaskPlan& Plan;
  const std::vector<int>& Parent;
  const Run& Work;
  std::mutex Mutex;
  std::condition_variable Wake;
  int Remaining;
  bool Failed = false;
  std::exception_ptr Error;
};

/// CHOLMOD's workspace for one analysis, released on every path out.
struct CholmodSession
{
  cholmod_common Common;
  cholmod_factor* Factor = nullptr;
  CholmodSession() { cholmod_start(&this->Common); }
  ~CholmodSession()
  {
    if (this->Factor)
    {
      cholmod_free_factor(&this->Factor, &this->Common);
    }
    cholmod_finish(&this->Common);
  }
  CholmodSession(const CholmodSession&) = delete;
  CholmodSession& operator=(const CholmodSession&) = delete;
};
} // namespace

//------------------------------------------------------------------------------
SupernodalLDLT::SupernodalLDLT(const SparseMatrix& pattern)
  : Size(pattern.rows())
{
  SparseMatrix lower = pattern.triangularView<Eigen::Lower>();
  lower.makeCompressed();
  cholmod_sparse A;
  A.nrow = static_cast<std::size_t>(this->Size);
  A.ncol = static_cast<std::size_t>(this->Size);
  A.nzmax = static_cast<std::size_t>(lower.nonZeros());
  A.p = lower.outerIndexPtr();
  A.i = lower.innerIndexPtr();
  A.nz = nullptr;
  A.x = lower.valuePtr();
  A.z = nullptr;
  A.stype = -1;
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_PATTERN;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;

  // Nested dissection (METIS) leaves about 40% less fill than AMD on surface meshes; smaller
  // relaxed supernodes than CHOLMOD's defaults (4, 16, 48) store fewer explicit zeros, which
  // the block solves would otherwise read for every right-hand side.
  CholmodSession session;
  session.Common.supernodal = CHOLMOD_SUPERNODAL;
  session.Common.nrelax[1] = 8;
  session.Common.nrelax[2] = 16;
  session.Common.nmethods = 1;
  session.Common.method[0].ordering = CHOLMOD_METIS;
  session.Factor = cholmod_analyze(&A, &session.Common);
  if (!session.Factor && session.Common.status == CHOLMOD_NOT_INSTALLED)
  {
    // CHOLMOD built without METIS: its default choice (AMD).
    session.Common.status = CHOLMOD_OK;
    session.Common.nmethods = 0;
    session.Factor = cholmod_analyze(&A, &session.Common);
  }
  const cholmod_factor* L = session.Factor;
  if (!L || !L->is_super || session.Common.status < CHOLMOD_OK)
  {
    throw SolverFailure("the symbolic analysis of L - sigma M failed (CHOLMOD status " +
      std::to_string(session.Common.status) + ")");
  }
  const std::size_t nsuper = L->nsuper;
  const int* super = static_cast<const int*>(L->super);
  const int* pi = static_cast<const int*>(L->pi);
  const int* px = static_cast<const int*>(L->px);
  const int* s = static_cast<const int*>(L->s);
  const int* perm = static_cast<const int*>(L->Perm);
  this->First.assign(super, super + nsuper + 1);
  this->RowStart.assign(pi, pi + nsuper + 1);
  this->RowIndex.assign(s, s + pi[nsuper]);
  this->ValueStart.resize(nsuper + 1);
  for (std::size_t k = 0; k <= nsuper; ++k)
  {
    this->ValueStart[k] = static_cast<std::size_t>(px[k]);
  }
  this->Values.assign(static_cast<std::size_t>(px[nsuper]), 0.0);
  this->Inverse.resize(static_cast<std::size_t>(this->Size));
  for (Eigen::Index k = 0; k < this->Size; ++k)
  {
    this->Inverse[static_cast<std::size_t>(perm[k])] = static_cast<int>(k);
  }
  this->SupernodeOf.resize(static_cast<std::size_t>(this->Size));
  for (std::size_t k = 0; k < nsuper; ++k)
  {
    std::fill(this->SupernodeOf.begin() + super[k], this->SupernodeOf.begin() + super[k + 1],
      static_cast<int>(k));
  }
  this->ScheduleUpdates();
}

//------------------------------------------------------------------------------
void SupernodalLDLT::ScheduleUpdates()
{
  // The left-looking sweep without the arithmetic: head[s] lists the supernodes whose next
  // update goes to s (last linked first); position[d] is the first row (relative to d's rows)
  // of d not yet used for an update. Each supernode records its updates in the order the sweep
  // meets them, which Factorize keeps on any number of threads.
  const int nsuper = this->Supernodes();
  std::vector<int> head(static_cast<std::size_t>(nsuper), -1);
  std::vector<int> next(static_cast<std::size_t>(nsuper), -1);
  std::vector<int> position(static_cast<std::size_t>(nsuper), 0);
  this->UpdateStart.assign(1, 0);
  this->Updates.clear();
  this->Parent.assign(static_cast<std::size_t>(nsuper), -1);
  this->SubtreeWork.assign(static_cast<std::size_t>(nsuper), 0.0);
  for (int s = 0; s < nsuper; ++s)
  {
    const Node node = this->Supernode(s);
    double work = static_cast<double>(node.Rows) * node.Columns * node.Columns;
    for (int d = head[s]; d != -1;)
    {
      const int following = next[d];
      const Node descendant = this->Supernode(d);
      const int p1 = position[d];
      int p2 = p1;
      while (p2 < descendant.Rows && descendant.RowIndex[p2] < node.First + node.Columns)
      {
        ++p2;
      }
      this->Updates.push_back({ d, p1, p2 });
      work += static_cast<double>(descendant.Rows - p1) * (p2 - p1) * descendant.Columns;
      position[d] = p2;
      if (p2 < descendant.Rows)
      {
        const int t = this->SupernodeOf[static_cast<std::size_t>(descendant.RowIndex[p2])];
        next[d] = head[t];
        head[t] = d;
      }
      d = following;
    }
    this->UpdateStart.push_back(static_cast<int>(this->Updates.size()));
    this->SubtreeWork[static_cast<std::size_t>(s)] += work;
    if (node.Rows > node.Columns)
    {
      const int t = this->SupernodeOf[static_cast<std::size_t>(node.RowIndex[node.Columns])];
      this->Parent[static_cast<std::size_t>(s)] = t;
      this->SubtreeWork[static_cast<std::size_t>(t)] +=
        this->SubtreeWork[static_cast<std::size_t>(s)];
      position[s] = node.Columns;
      next[s] = head[t];
      head[t] = s;
    }
  }
}

//------------------------------------------------------------------------------
SupernodalLDLT::Node SupernodalLDLT::Supernode(int s) const
{
  return { this->First[s], this->First[s + 1] - this->First[s],
    this->RowStart[s + 1] - this->RowStart[s], this->RowIndex.data() + this->RowStart[s],
    this->Values.data() + this->ValueStart[s] };
}

//------------------------------------------------------------------------------
/// The scratch space of one thread of Factorize.
struct SupernodalLDLT::Workspace
{
  /// local[i]: the position of row i among the rows of the supernode being factored.
  std::vector<int> Local;
  ScratchBuffer Weighted;
  ScratchBuffer Update;
  ScratchBuffer Pivots;
  ScratchBuffer Panel;
  explicit Workspace(Eigen::Index n)
    : Local(static_cast<std::size_t>(n), -1)
  {
  }
};

//------------------------------------------------------------------------------
bool SupernodalLDLT::Factorize(const SparseMatrix& A)
{
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse(
    static_cast<Eigen::Index>(this->Inverse.size()));
  std::copy(this->Inverse.begin(), this->Inverse.end(), inverse.indices().data());
  this->Permuted.resize(this->Size, this->Size);
  this->Permuted.selfadjointView<Eigen::Lower>() =
    A.selfadjointView<Eigen::Lower>().twistedBy(inverse);

  this->Negative = 0;
  const int threads = this->Size < ParallelRows ? 1 : ResolveThreads(this->Threads);
  if (this->Plan.MadeFor != threads)
  {
    this->MakeSolvePlan(threads);
  }
  if (threads > 1 && this->Supernodes() > 1)
  {
    return this->FactorOnThreads(threads);
  }
  Workspace work(this->Size);
  int negative = 0;
  for (int s = 0; s < this->Supernodes(); ++s)
  {
    if (!this->FactorSupernode(s, work, negative))
    {
      return false;
    }
  }
  this->Negative = negative;
  return true;
}

namespace
{
/**
 * LDL^T without pivoting of a supernode's columns in place: X (nsrow x nscol, column-major,
 * stride nsrow) holds the assembled columns [A11; A21] (the lower triangle of A11) and receives
 * [L11; L21] with D on the diagonal of L11 (L's unit diagonal is not stored); D receives the
 * pivots. PanelColumns columns at a time: the pivots of a block column one by one (matrix-vector
 * products), then the rows below it by a triangular solve and the columns to its right by one
 * matrix product, so that a wide supernode (a volume's separators: a few thousand columns)
 * runs at the speed of matrix products rather than of matrix-vector products.
 * \param scratch holds a copy of L D for the product.
 * \param negative incremented by the number of negative pivots.
 * \return false on a zero or non-finite pivot or a non-finite entry of L.
 */
bool FactorPanel(double* X, int nsrow, int nscol, double* D, ScratchBuffer& scratch, int& negative)
{
  for (int k0 = 0; k0 < nscol; k0 += PanelColumns)
  {
    const int kb = std::min(PanelColumns, nscol - k0);
    BlockView Akk(X + static_cast<std::ptrdiff_t>(k0) * nsrow + k0, kb, kb, Stride(nsrow));
    for (int j = 0; j < kb; ++j)
    {
      if (j > 0)
      {
        const Vector v =
          Eigen::Map<const Vector>(D + k0, j).cwiseProduct(Akk.row(j).head(j).transpose());
        Akk.col(j).tail(kb - j).noalias() -= Akk.block(j, 0, kb - j, j) * v;
      }
      const double pivot = Akk(j, j);
      if (!std::isfinite(pivot) || pivot == 0.0)
      {
        return false;
      }
      D[k0 + j] = pivot;
      negative += pivot < 0.0 ? 1 : 0;
      Akk.col(j).tail(kb - j - 1) /= pivot;
    }
    const int below = nsrow - k0 - kb;
    if (below == 0)
    {
      continue;
    }
    // The rows below the block: L D = A L_kk^-T, then L.
    BlockView P(X + static_cast<std::ptrdiff_t>(k0) * nsrow + k0 + kb, below, kb, Stride(nsrow));
    Akk.transpose().triangularView<Eigen::UnitUpper>().solveInPlace<Eigen::OnTheRight>(P);
    const int right = nscol - k0 - kb;
    BlockView LD(Scratch(scratch, static_cast<std::size_t>(right) * kb), right, kb, Stride(right));
    LD = P.topRows(right);
    for (int j = 0; j < kb; ++j)
    {
      P.col(j) /= D[k0 + j];
      if (!P.col(j).allFinite())
      {
        return false;
      }
    }
    if (right == 0)
    {
      continue;
    }
    // The columns to the right: A -= L D L^T, the lower triangle of their diagonal block and
    // every row below it.
    BlockView A22(
      X + static_cast<std::ptrdiff_t>(k0 + kb) * nsrow + k0 + kb, below, right, Stride(nsrow));
    A22.topRows(right).triangularView<Eigen::Lower>() -= P.topRows(right) * LD.transpose();
    if (below > right)
    {
      A22.bottomRows(below - right).noalias() -= P.bottomRows(below - right) * LD.transpose();
    }
  }
  return true;
}
} // namespace

//------------------------------------------------------------------------------
bool SupernodalLDLT::FactorSupernode(int s, Workspace& work, int& negative)
{
  const Node node = this->Supernode(s);
  const int k1 = node.First;
  const int nscol = node.Columns;
  const int nsrow = node.Rows;
  const int* rows = node.RowIndex;
  double* X = this->Values.data() + this->ValueStart[s];
  std::fill(X, this->Values.data() + this->ValueStart[s + 1], 0.0);
  std::vector<int>& local = work.Local;
  for (int k = 0; k < nsrow; ++k)
  {
    local[static_cast<std::size_t>(rows[k])] = k;
  }

  // Assemble the columns of A.
  for (int j = 0; j < nscol; ++j)
  {
    for (SparseMatrix::InnerIterator it(this->Permuted, k1 + j); it; ++it)
    {
      X[local[static_cast<std::size_t>(it.row())] + static_cast<std::ptrdiff_t>(j) * nsrow] +=
        it.value();
    }
  }

  // Subtract L_d D_d L_d^T from every descendant d with rows in [k1, k1 + nscol), in the order
  // of ScheduleUpdates.
  for (int u = this->UpdateStart[s]; u < this->UpdateStart[s + 1]; ++u)
  {
    const Update& update = this->Updates[static_cast<std::size_t>(u)];
    const Node descendant = this->Supernode(update.Descendant);
    const int* drows = descendant.RowIndex;
    const int ndrow = descendant.Rows;
    const int ndcol = descendant.Columns;
    const int p1 = update.Begin;
    const int ndrow1 = update.End - p1;
    const int ndrow2 = ndrow - p1;
    const ConstBlockView Ld(descendant.Values, ndrow, ndcol, Stride(ndrow));
    BlockView W(Scratch(work.Weighted, static_cast<std::size_t>(ndrow1) * ndcol),
      ndrow1,
      ndcol,
      Stride(ndrow1));
    for (int c = 0; c < ndcol; ++c)
    {
      W.col(c) = Ld.col(c).segment(p1, ndrow1) * Ld(c, c);
    }
    BlockView C(Scratch(work.Update, static_cast<std::size_t>(ndrow2) * ndrow1),
      ndrow2,
      ndrow1,
      Stride(ndrow2));
    C.noalias() = Ld.middleRows(p1, ndrow2) * W.transpose();
    for (int jj = 0; jj < ndrow1; ++jj)
    {
      double* target = X + static_cast<std::ptrdiff_t>(drows[p1 + jj] - k1) * nsrow;
      for (int ii = jj; ii < ndrow2; ++ii)
      {
        target[local[static_cast<std::size_t>(drows[p1 + ii])]] -= C(ii, jj);
      }
    }
  }

  return FactorPanel(
    X, nsrow, nscol, Scratch(work.Pivots, static_cast<std::size_t>(nscol)), work.Panel, negative);
}

//------------------------------------------------------------------------------
bool SupernodalLDLT::FactorOnThreads(int threads)
{
  TaskPlan plan = PlanTasks(this->Parent, this->SubtreeWork, threads);
  std::vector<std::unique_ptr<Workspace>> work(static_cast<std::size_t>(threads));
  std::vector<int> negative(static_cast<std::size_t>(threads), 0);
  const auto run = [this, &plan, &work, &negative](int task, int thread)
  {
    return this->FactorTask(plan.Members.data() + plan.Start[static_cast<std::size_t>(task)],
      plan.Members.data() + plan.Start[static_cast<std::size_t>(task) + 1],
      work[static_cast<std::size_t>(thread)],
      negative[static_cast<std::size_t>(thread)]);
  };
  if (!TaskRunner<decltype(run)>(plan, this->Parent, run).Execute(threads))
  {
    return false;
  }
  for (const int count : negative)
  {
    this->Negative += count;
  }
  return true;
}

//------------------------------------------------------------------------------
bool SupernodalLDLT::FactorTask(const int* first,
  const int* last,
  std::unique_ptr<Workspace>& work,
  int& negative)
{
  if (!work)
  {
    work.reset(new Workspace(this->Size));
  }
  for (const int* s = first; s != last; ++s)
  {
    if (!this->FactorSupernode(*s, *work, negative))
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
int SupernodalLDLT::WidestSupernode() const
{
  int widest = 0;
  for (int s = 0; s < this->Supernodes(); ++s)
  {
    widest = std::max(widest,
      this->First[static_cast<std::size_t>(s) + 1] - this->First[static_cast<std::size_t>(s)]);
  }
  return widest;
}

//------------------------------------------------------------------------------
DenseMatrix SupernodalLDLT::Solve(const Eigen::Ref<const DenseMatrix>& B) const
{
  DenseMatrix X(B.rows(), B.cols());
  const int threads = this->Size < ParallelRows ? 1 : ResolveThreads(this->Threads);
  if (this->Plan.Threads > 1 && this->Plan.MadeFor == threads)
  {
    // MaxWidth columns at a time, each block on all threads.
    this->SolveColumns(B, X, 0, B.cols(), true);
    return X;
  }
  // Contiguous ranges of at least 4 columns a thread, each solved MaxWidth columns at a time.
  const int parts = static_cast<int>(std::min<Eigen::Index>(threads, (B.cols() + 3) / 4));
  ForEachRowRange(B.cols(),
    parts,
    [this, &B, &X](int, Eigen::Index first, Eigen::Index count)
    {
      if (count > 0)
      {
        this->SolveColumns(B, X, first, count, false);
      }
    });
  return X;
}

//------------------------------------------------------------------------------
/**
 * Solve L D L^T y = b in place for W right-hand sides, with Y row-major (n x W): row k holds
 * the k-th entries of all W right-hand sides next to each other, and W is known at compile time,
 * so that every update of a row is a few vector instructions. Supernodes of a surface mesh are
 * mostly a few columns wide, too small for dense kernels to pay off. The forward solve updates
 * every row below a supernode once with all of its columns (one read and one write of the row
 * instead of one per column, and no chain of stores and loads on the same row); D is applied as
 * each supernode is finished. The backward solve reads every row below a supernode once for
 * up to eight of its columns, accumulating in registers. Both keep eight independent sums under
 * way (see SubtractRows and GatherColumns): with one sum per row or column, each multiply-add
 * waits for the one before (12 right-hand sides on the factor of the 100K benchmark mesh,
 * 5.8 million entries, factor in cache: 12.2 ms that way, 9.6 ms this way). Out of cache,
 * the solve waits for the factor instead: StreamPrefetch fetches it ahead.
 */
template<int W>
void SupernodalLDLT::Forward(const std::vector<Range>& ranges, double* Y, double* far) const
{
  using Row = Eigen::Matrix<double, W, 1>;
  using RowView = Eigen::Map<Row>;
  using ConstRowView = Eigen::Map<const Row>;
  const auto row = [Y](int k) { return Y + static_cast<std::size_t>(k) * W; };
  for (const Range& range : ranges)
  {
    // Rows from `outside` on lie above the subtree: they go to `far`.
    const int outside =
      far ? this->First[static_cast<std::size_t>(range.second)] : static_cast<int>(this->Size);
    StreamPrefetch valueStream =
      FactorPart(this->Values.data(), this->ValueStart, range, PrefetchDistance);
    StreamPrefetch indexStream =
      FactorPart(this->RowIndex.data(), this->RowStart, range, PrefetchDistance / 4);
    for (int s = range.first; s < range.second; ++s) // L D y = P b
    {
      const Node node = this->Supernode(s);
      const int c = node.Columns;
      const int r = node.Rows;
      const double* L = node.Values;
      valueStream.Reached(L);
      indexStream.Reached(node.RowIndex);
      // The supernode's own rows: unit lower triangular L11.
      for (int j = 0; j < c; ++j)
      {
        const Row y = ConstRowView(row(node.First + j));
        for (int i = j + 1; i < c; ++i)
        {
          RowView(row(node.First + i)) -= L[static_cast<std::size_t>(j) * r + i] * y;
        }
      }
      // The rows below: each updated once with all the supernode's columns; those above the
      // subtree in `far`.
      const int inside = static_cast<int>(
        std::lower_bound(node.RowIndex + c, node.RowIndex + r, outside) - node.RowIndex);
      SubtractRows<W>(Y, 0, node.RowIndex + c, inside - c, L + c, r, c, row(node.First));
      if (inside < r)
      {
        SubtractRows<W>(far,
          this->Plan.FarFirst,
          node.RowIndex + inside,
          r - inside,
          L + inside,
          r,
          c,
          row(node.First));
      }
      for (int j = 0; j < c; ++j)
      {
        RowView(row(node.First + j)) /= L[static_cast<std::size_t>(j) * (r + 1)];
      }
    }
  }
}

//------------------------------------------------------------------------------
template<int W>
void SupernodalLDLT::Backward(const std::vector<Range>& ranges, double* Y) const
{
  using Row = Eigen::Matrix<double, W, 1>;
  using RowView = Eigen::Map<Row>;
  using ConstRowView = Eigen::Map<const Row>;
  const auto row = [Y](int k) { return Y + static_cast<std::size_t>(k) * W; };
  for (auto range = ranges.rbegin(); range != ranges.rend(); ++range)
  {
    StreamPrefetch valueStream =
      FactorPart(this->Values.data(), this->ValueStart, *range, -PrefetchDistance);
    StreamPrefetch indexStream =
      FactorPart(this->RowIndex.data(), this->RowStart, *range, -PrefetchDistance / 4);
    for (int s = range->second - 1; s >= range->first; --s) // L^T x = z
    {
      const Node node = this->Supernode(s);
      const int c = node.Columns;
      const int r = node.Rows;
      const double* L = node.Values;
      valueStream.Reached(L + static_cast<std::size_t>(c) * r);
      indexStream.Reached(node.RowIndex + r);
      // The rows below: each read once for up to eight of the supernode's columns. Narrower
      // groups split every sum over interleaved rows, so that at least eight sums are under way.
      const auto gather = [&](auto group, auto phases, int j)
      {
        GatherColumns<W, decltype(group)::value, decltype(phases)::value>(Y,
          node.RowIndex + c,
          r - c,
          L + static_cast<std::size_t>(j) * r + c,
          r,
          row(node.First + j));
      };
      using One = std::integral_constant<int, 1>;
      using Two = std::integral_constant<int, 2>;
      using Three = std::integral_constant<int, 3>;
      using Four = std::integral_constant<int, 4>;
      using Eight = std::integral_constant<int, 8>;
      int j0 = 0;
      for (; j0 + 8 <= c; j0 += 8)
      {
        gather(Eight(), One(), j0);
      }
      if (j0 + 4 <= c)
      {
        gather(Four(), Two(), j0);
        j0 += 4;
      }
      switch (c - j0)
      {
        case 3:
          gather(Three(), Three(), j0);
          break;
        case 2:
          gather(Two(), Four(), j0);
          break;
        case 1:
          gather(One(), Eight(), j0);
          break;
        default:
          break;
      }
      // The supernode's own rows: unit upper triangular L11^T.
      for (int j = c - 1; j >= 0; --j)
      {
        RowView target(row(node.First + j));
        Row x = target;
        for (int i = j + 1; i < c; ++i)
        {
          x -= L[static_cast<std::size_t>(j) * r + i] * ConstRowView(row(node.First + i));
        }
        target = x;
      }
    }
  }
}

//------------------------------------------------------------------------------
template<int W>
void SupernodalLDLT::SolveRows(double* Y, bool planned) const
{
  const SolvePlan& plan = this->Plan;
  if (!planned || plan.Threads <= 1)
  {
    const std::vector<Range> all = { Range(0, this->Supernodes()) };
    this->Forward<W>(all, Y, nullptr);
    this->Backward<W>(all, Y);
    return;
  }
  // Each thread's updates of the rows above its subtrees, in its own block of the rows from
  // FarFirst on (the first row above the subtrees; only those rows above are touched).
  const std::size_t offset = static_cast<std::size_t>(plan.FarFirst) * W;
  const std::size_t size = static_cast<std::size_t>(this->Size) * W - offset;
  std::vector<std::unique_ptr<double[]>> far(static_cast<std::size_t>(plan.Threads));
  // The entries [begin, end) of Y's rows above the subtrees, range by range.
  const auto topEntries = [this, &plan](const auto& visit)
  {
    for (const Range& range : plan.Top)
    {
      visit(static_cast<std::size_t>(this->First[static_cast<std::size_t>(range.first)]) * W,
        static_cast<std::size_t>(this->First[static_cast<std::size_t>(range.second)]) * W);
    }
  };
  ForEachRowRange(plan.Threads,
    plan.Threads,
    [&](int, Eigen::Index thread, Eigen::Index count)
    {
      for (Eigen::Index t = thread; t < thread + count; ++t)
      {
        std::unique_ptr<double[]>& mine = far[static_cast<std::size_t>(t)];
        mine.reset(new double[size]);
        topEntries([&mine, offset](std::size_t begin, std::size_t end)
          { std::fill(mine.get() + (begin - offset), mine.get() + (end - offset), 0.0); });
        this->Forward<W>(plan.Subtrees[static_cast<std::size_t>(t)], Y, mine.get());
      }
    });
  // In thread order: the sum does not depend on which thread finished first.
  for (const std::unique_ptr<double[]>& mine : far)
  {
    topEntries(
      [Y, &mine, offset](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = begin; k < end; ++k)
        {
          Y[k] += mine[k - offset];
        }
      });
  }
  this->Forward<W>(plan.Top, Y, nullptr);
  this->Backward<W>(plan.Top, Y);
  ForEachRowRange(plan.Threads,
    plan.Threads,
    [&](int, Eigen::Index thread, Eigen::Index count)
    {
      for (Eigen::Index t = thread; t < thread + count; ++t)
      {
        this->Backward<W>(plan.Subtrees[static_cast<std::size_t>(t)], Y);
      }
    });
}

//------------------------------------------------------------------------------
void SupernodalLDLT::MakeSolvePlan(int threads)
{
  this->Plan = SolvePlan();
  this->Plan.MadeFor = threads;
  const int count = this->Supernodes();
  if (threads <= 1 || count < 2)
  {
    return;
  }
  // Work of a subtree: the entries of the factor its solve reads; size: its supernodes.
  std::vector<double> work(static_cast<std::size_t>(count));
  std::vector<int> size(static_cast<std::size_t>(count), 1);
  for (int s = 0; s < count; ++s)
  {
    const std::size_t u = static_cast<std::size_t>(s);
    work[u] += static_cast<double>(this->ValueStart[u + 1] - this->ValueStart[u]);
    const int parent = this->Parent[u];
    // Children before parents, and each supernode's rows below its own columns ascending: the
    // split of Forward depends on both.
    if (parent != -1 && parent <= s)
    {
      return;
    }
    const Node node = this->Supernode(s);
    if (!std::is_sorted(node.RowIndex + node.Columns, node.RowIndex + node.Rows))
    {
      return;
    }
    if (parent != -1)
    {
      work[static_cast<std::size_t>(parent)] += work[u];
      size[static_cast<std::size_t>(parent)] += size[u];
    }
  }
  Forest forest = MakeForest(this->Parent, work);
  const std::vector<std::vector<int>>& children = forest.Children;
  std::priority_queue<std::pair<double, int>>& largest = forest.Largest;
  const double total = forest.Total;
  // Split the heaviest subtree until the subtrees can be shared out evenly (Geist and Ng's
  // rule): the largest-first assignment of the subtrees to the threads leaves none with more than
  // SolveImbalance times its share, or the heaviest is a single supernode. A tree whose
  // supernodes above the subtrees would hold half of the factor (a chain) gets no plan.
  std::vector<char> top(static_cast<std::size_t>(count), 0);
  double above = 0.0;
  std::vector<std::pair<double, int>> subtrees;
  std::vector<double> load;
  while (!largest.empty())
  {
    subtrees.clear();
    auto queue = largest;
    double sum = 0.0;
    while (!queue.empty())
    {
      subtrees.push_back(queue.top());
      sum += queue.top().first;
      queue.pop();
    }
    load.assign(static_cast<std::size_t>(threads), 0.0);
    for (const std::pair<double, int>& subtree : subtrees)
    {
      *std::min_element(load.begin(), load.end()) += subtree.first;
    }
    const std::pair<double, int> heaviest = largest.top();
    const std::vector<int>& below = children[static_cast<std::size_t>(heaviest.second)];
    if (*std::max_element(load.begin(), load.end()) <= SolveImbalance * sum / threads ||
      below.empty())
    {
      break;
    }
    largest.pop();
    top[static_cast<std::size_t>(heaviest.second)] = 1;
    const std::size_t h = static_cast<std::size_t>(heaviest.second);
    above += static_cast<double>(this->ValueStart[h + 1] - this->ValueStart[h]);
    if (above > 0.5 * total)
    {
      return;
    }
    for (const int child : below)
    {
      largest.emplace(work[static_cast<std::size_t>(child)], child);
    }
  }
  SolvePlan plan;
  plan.MadeFor = threads;
  plan.Threads = threads;
  plan.Subtrees.resize(static_cast<std::size_t>(threads));
  load.assign(static_cast<std::size_t>(threads), 0.0);
  for (const std::pair<double, int>& subtree : subtrees)
  {
    // A subtree must be its consecutive supernodes, its root last (a postordered tree): the
    // size[root] - 1 supernodes before the root all have their parent at most the root (parents
    // come after children, so each one's ancestors lead to the root).
    const int root = subtree.second;
    const int first = root - size[static_cast<std::size_t>(root)] + 1;
    for (int s = first; s < root; ++s)
    {
      const int parent = this->Parent[static_cast<std::size_t>(s)];
      if (parent == -1 || parent > root)
      {
        return;
      }
    }
    const std::size_t least =
      static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    load[least] += subtree.first;
    plan.Subtrees[least].emplace_back(first, root + 1);
  }
  for (std::vector<Range>& ranges : plan.Subtrees)
  {
    std::sort(ranges.begin(), ranges.end());
  }
  for (int s = 0; s < count; ++s)
  {
    if (top[static_cast<std::size_t>(s)])
    {
      if (!plan.Top.empty() && plan.Top.back().second == s)
      {
        ++plan.Top.back().second;
      }
      else
      {
        plan.Top.emplace_back(s, s + 1);
      }
    }
  }
  plan.FarFirst = plan.Top.empty() ? static_cast<int>(this->Size)
                                   : this->First[static_cast<std::size_t>(plan.Top.front().first)];
  this->Plan = std::move(plan);
}

//------------------------------------------------------------------------------
void SupernodalLDLT::SolveRowsOfWidth(int width, double* Y, bool planned) const
{
  switch (width)
  {
    case 4:
      this->SolveRows<4>(Y, planned);
      break;
    case 8:
      this->SolveRows<8>(Y, planned);
      break;
    case 12:
      this->SolveRows<12>(Y, planned);
      break;
    default:
      this->SolveRows<16>(Y, planned);
      break;
  }
}

//------------------------------------------------------------------------------
void SupernodalLDLT::SolveColumns(const Eigen::Ref<const DenseMatrix>& B,
  DenseMatrix& X,
  Eigen::Index first,
  Eigen::Index count,
  bool planned) const
{
  const Eigen::Index n = this->Size;
  // Not initialized: the copy below writes every entry (a zero fill of a few MB per solve showed
  // as 2.5% of a benchmark profile).
  const int widest = PaddedWidth(std::min<Eigen::Index>(count, MaxWidth));
  std::unique_ptr<double[]> rows(new double[static_cast<std::size_t>(n) * widest]);
  for (Eigen::Index done = 0; done < count;)
  {
    const int used = static_cast<int>(std::min<Eigen::Index>(count - done, MaxWidth));
    const int width = PaddedWidth(used);
    RowBlockView Y(rows.get(), n, width);
    const Eigen::Index column = first + done;
    // Rows of B in their own order (each column streamed), each to its place in the permuted
    // order: one scattered write of a short row instead of a scattered read per column.
    for (Eigen::Index i = 0; i < n; ++i)
    {
      auto target = Y.row(this->Inverse[static_cast<std::size_t>(i)]);
      target.head(used) = B.row(i).segment(column, used);
      target.tail(width - used).setZero();
    }
    this->SolveRowsOfWidth(width, rows.get(), planned);
    for (Eigen::Index i = 0; i < n; ++i)
    {
      X.row(i).segment(column, used) = Y.row(this->Inverse[static_cast<std::size_t>(i)]).head(used);
    }
    done += used;
  }
}
} // namespace spectral
