// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SupernodalLDLT.h
 * @brief Supernodal LDL^T factorization of sparse symmetric (possibly indefinite) matrices.
 *
 * Shift-invert needs L - sigma M factored for shifts inside the spectrum, where the matrix is
 * indefinite. CHOLMOD's supernodal factorization (dense BLAS-3 kernels, fast) is LL^T only, its
 * LDL^T is simplicial (one column at a time, slow). This class keeps CHOLMOD for what it does
 * best, the symbolic analysis (fill-reducing ordering, elimination tree, relaxed supernodes), and
 * computes the numeric LDL^T on that supernodal structure itself: left-looking, each supernode
 * a dense column block, updates from its descendants by dense products, the diagonal block
 * factored without pivoting. Without pivoting it is the same factorization as CHOLMOD's
 * simplicial LDL^T, so the pivots D give the inertia (Sylvester's law) of the matrix.
 *
 * Solves take a block of right-hand sides at once, stored row by row, so that reading the
 * factor is shared by all of them and every update of a row is a short vector operation.
 *
 * Threads (SetThreads, the count as in Common/Threads.h): Factorize factors the supernodes of
 * disjoint subtrees of the supernodal elimination tree at the same time, then the separators
 * above them as soon as their children are done. Left-looking, a supernode is written only by
 * the thread that factors it, and it takes the updates of its descendants in one fixed order
 * (recorded by the symbolic analysis), so the factor and the pivots are bitwise the same on any
 * number of threads. Solve gives each thread disjoint subtrees for all right-hand sides at once
 * (each part of the factor is read once, by one thread), then solves the separators above them.
 *
 * Tested by Testing/Core/TestSupernodalLDLT.cxx.
 *
 * Reference for the structure: T. A. Davis, "Direct Methods for Sparse Linear Systems", SIAM
 * 2006, chapter 4; Y. Chen, T. A. Davis, W. W. Hager, S. Rajamanickam, "Algorithm 887:
 * CHOLMOD, Supernodal Sparse Cholesky Factorization and Update/Downdate", ACM TOMS 35(3), 2008.
 */
#ifndef spectral_SupernodalLDLT_h
#define spectral_SupernodalLDLT_h

#include "Common/Mesh.h"

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace spectral
{
class SupernodalLDLT
{
public:
  /**
   * Fill-reducing ordering and supernodal symbolic factorization of the pattern of A (its lower
   * triangle is read). Every matrix later passed to Factorize must have its nonzeros inside this
   * pattern.
   * \throws SolverFailure if CHOLMOD's analysis fails (out of memory).
   */
  explicit SupernodalLDLT(const SparseMatrix& pattern);

  /**
   * Threads of Factorize and Solve: >= 1 as is, 0 (default) every core (ResolveThreads in
   * Common/Threads.h). Matrices of fewer than 2000 rows use one. The results do not depend on
   * it: the factor bitwise, solves up to rounding (the right-hand sides go to kernels of
   * different widths).
   */
  void SetThreads(int threads) { this->Threads = threads; }
  int GetThreads() const { return this->Threads; }

  /**
   * Numeric factorization P A P^T = L D L^T (L unit lower triangular, D diagonal, no pivoting).
   * Only the lower triangle of A is read.
   * \return false if a pivot is zero or not finite (A is singular to working precision, or
   *         unpivoted elimination broke down), on whichever thread it happens; the factor is
   *         then unusable.
   * \throws What a thread threw (std::bad_alloc), after every thread has stopped.
   */
  bool Factorize(const SparseMatrix& A);

  /// Number of negative pivots of the last successful Factorize: the number of negative
  /// eigenvalues of A.
  int NegativePivots() const { return this->Negative; }

  /**
   * X = A^-1 B for the last factored A, at most 16 columns at a time, each block on all threads
   * (disjoint subtrees of the elimination tree, SolvePlan), or, where the tree does not allow
   * it, the columns of B split over the threads, at least 4 a thread (one SIMD-wide kernel).
   */
  DenseMatrix Solve(const Eigen::Ref<const DenseMatrix>& B) const;

  /// Entries stored for L (with the zeros of relaxed supernodes).
  std::size_t FactorEntries() const { return this->Values.size(); }

  /// Number of supernodes.
  int Supernodes() const { return static_cast<int>(this->First.size()) - 1; }

  /// The most columns of one supernode (a volume's top separators have thousands).
  int WidestSupernode() const;

  /// Threads among which Solve shares each block of right-hand sides by subtrees (SolvePlan;
  /// 1: it splits the columns instead), as planned by the last Factorize.
  int SolveThreads() const { return this->Plan.Threads; }

private:
  /// Supernode s in place: columns [First, First + Columns), Rows row indices (its own columns
  /// first), Values the column-major Rows x Columns block.
  struct Node
  {
    int First;
    int Columns;
    int Rows;
    const int* RowIndex;
    const double* Values;
  };
  Node Supernode(int s) const;

  /// Record the updates of the left-looking sweep (Updates), the elimination tree (Parent) and
  /// the work of its subtrees (SubtreeWork) from the symbolic structure.
  void ScheduleUpdates();

  /// The scratch space of one thread of Factorize (defined in the .cxx).
  struct Workspace;

  /// Factor supernode s in place, its descendants done: false on a zero or non-finite pivot.
  /// \param negative incremented by the number of negative pivots.
  bool FactorSupernode(int s, Workspace& work, int& negative);

  /// Factorize's supernodes on `threads` threads, each task of the tree after its children.
  bool FactorOnThreads(int threads);

  /// Factor the supernodes [first, last) in order with the workspace `work` (made if null).
  bool FactorTask(const int* first,
    const int* last,
    std::unique_ptr<Workspace>& work,
    int& negative);

  /// Solve columns [first, first + count) of B into X (with SolveRows, `planned` as there).
  void SolveColumns(const Eigen::Ref<const DenseMatrix>& B,
    DenseMatrix& X,
    Eigen::Index first,
    Eigen::Index count,
    bool planned) const;

  /**
   * Solve L D L^T y = b in place for W right-hand sides, with Y row-major (n x W): row k holds
   * the k-th entries of all W right-hand sides next to each other (defined in the .cxx). On
   * the threads of the solve plan if `planned` (see SolvePlan), else on the calling thread.
   */
  template<int W>
  void SolveRows(double* Y, bool planned) const;

  /// SolveRows for a width known only at run time: 4, 8, 12 or 16.
  void SolveRowsOfWidth(int width, double* Y, bool planned) const;

  /// Consecutive supernodes [first, second).
  using Range = std::pair<int, int>;

  /**
   * The forward solve L D z = y of the supernodes of `ranges`, in order. A range is a subtree
   * (its supernodes consecutive, its root last) when `far` is not null: its updates of rows
   * outside it (the supernodes above the subtree) go to `far` instead of Y, which holds the rows
   * from Plan.FarFirst on.
   */
  template<int W>
  void Forward(const std::vector<Range>& ranges, double* Y, double* far) const;

  /// The backward solve L^T x = z of the supernodes of `ranges`, last range first, each from its
  /// last supernode down; the rows above them must be solved already.
  template<int W>
  void Backward(const std::vector<Range>& ranges, double* Y) const;

  /**
   * How Solve shares one block of right-hand sides among threads (MakeSolvePlan): each thread
   * solves whole subtrees of the supernodal elimination tree (Subtrees[t]), reading only its part
   * of the factor, its updates of the rows above its subtrees kept apart; one thread then adds
   * those up and solves the supernodes above the subtrees (Top) forward and backward, and the
   * threads finish their subtrees backward. Threads 1: no plan (one thread, a tree that is not
   * postordered, or one whose supernodes above the subtrees would hold half of the factor); Solve
   * then splits the right-hand sides over the threads instead.
   */
  struct SolvePlan
  {
    /// The threads it was made for (0: none yet); Threads is 1 when the tree does not allow it.
    int MadeFor = 0;
    int Threads = 1;
    std::vector<std::vector<Range>> Subtrees;
    std::vector<Range> Top;
    /// The first row above the subtrees: the threads keep their updates of the rows from it on.
    int FarFirst = 0;
  };

  /// Plan the tree-parallel solve on `threads` threads (Factorize calls it when the count changes).
  void MakeSolvePlan(int threads);

  Eigen::Index Size = 0;
  /// Inverse[i]: the row of P A P^T that row i of A becomes (the inverse of CHOLMOD's ordering).
  std::vector<int> Inverse;
  /// Supernode s holds columns [First[s], First[s+1]).
  std::vector<int> First;
  /// Rows of supernode s: RowIndex[RowStart[s] .. RowStart[s+1]), its own columns first.
  std::vector<int> RowStart;
  std::vector<int> RowIndex;
  /// Values of supernode s: a column-major (rows x columns) block at Values[ValueStart[s]].
  /// Unit diagonal of L not stored: the diagonal holds D.
  std::vector<std::size_t> ValueStart;
  /// Aligned (AlignedBuffer): the dense kernels work on blocks of it.
  AlignedBuffer Values;
  /// Supernode of each column.
  std::vector<int> SupernodeOf;
  /// Update from descendant supernode Descendant to supernode s: the descendant's rows [Begin,
  /// End) (positions among its rows) are columns of s, and its rows from Begin on are updated.
  struct Update
  {
    int Descendant;
    int Begin;
    int End;
  };
  /// The updates to supernode s, Updates[UpdateStart[s] .. UpdateStart[s+1]), in the order of
  /// the serial left-looking sweep (the order is part of the floating-point result).
  std::vector<int> UpdateStart;
  std::vector<Update> Updates;
  /// Parent of each supernode in the supernodal elimination tree, -1 at a root.
  std::vector<int> Parent;
  /// Estimated floating-point operations of the subtree rooted at each supernode.
  std::vector<double> SubtreeWork;
  /// The permuted lower triangle, re-filled by each Factorize.
  SparseMatrix Permuted;
  SolvePlan Plan;
  int Negative = 0;
  int Threads = 0;
};
} // namespace spectral

#endif
