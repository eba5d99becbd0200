// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/Components.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

namespace spectral
{
namespace
{
/// One component: its rows of the whole operators, its own operators and its pairs.
struct Block
{
  std::vector<int> Rows;
  SparseMatrix L;
  SparseMatrix M;
  double Area = 0.0;
  /// Pairs asked for in the last solve.
  int Asked = 0;
  EigenResult Pairs;
};

//------------------------------------------------------------------------------
// The operators of each component, with its rows in the whole ones.
std::vector<Block> SplitBlocks(const SparseMatrix& L,
  const SparseMatrix& M,
  const std::vector<int>& label,
  int count)
{
  std::vector<Block> blocks(static_cast<std::size_t>(count));
  std::vector<int> local(label.size());
  for (std::size_t i = 0; i < label.size(); ++i)
  {
    Block& block = blocks[static_cast<std::size_t>(label[i])];
    local[i] = static_cast<int>(block.Rows.size());
    block.Rows.push_back(static_cast<int>(i));
  }
  // Entries of each whole matrix, sorted into the blocks of their columns (the operators have
  // no entry between components).
  const auto split = [&blocks, &label, &local](const SparseMatrix& A, SparseMatrix Block::*part)
  {
    std::vector<std::vector<Eigen::Triplet<double>>> entries(blocks.size());
    for (int j = 0; j < A.outerSize(); ++j)
    {
      auto& list = entries[static_cast<std::size_t>(label[static_cast<std::size_t>(j)])];
      for (SparseMatrix::InnerIterator it(A, j); it; ++it)
      {
        list.emplace_back(local[static_cast<std::size_t>(it.row())],
          local[static_cast<std::size_t>(j)],
          it.value());
      }
    }
    for (std::size_t c = 0; c < blocks.size(); ++c)
    {
      const Eigen::Index size = static_cast<Eigen::Index>(blocks[c].Rows.size());
      SparseMatrix& matrix = blocks[c].*part;
      matrix.resize(size, size);
      matrix.setFromTriplets(entries[c].begin(), entries[c].end());
    }
  };
  split(L, &Block::L);
  split(M, &Block::M);
  return blocks;
}

//------------------------------------------------------------------------------
// The pairs a component is first asked for: its share of m by area, with a margin, at most m
// and at most its size.
int FirstRequest(const Block& block, double totalArea, int m)
{
  const double share = totalArea > 0.0 ? m * block.Area / totalArea : m;
  const double asked = std::ceil(1.25 * share) + 10.0;
  const int size = static_cast<int>(block.Rows.size());
  return static_cast<int>(std::min<double>({ asked, static_cast<double>(m), size * 1.0 }));
}

//------------------------------------------------------------------------------
// The union of the chosen pairs (component, index within its pairs), in the given order: the
// eigenvalues, and the eigenvectors extended by zero if the components have them.
void Gather(const std::vector<Block>& blocks,
  const std::vector<std::pair<int, int>>& chosen,
  Eigen::Index n,
  EigenResult& result)
{
  const bool vectors = std::any_of(blocks.begin(),
    blocks.end(),
    [](const Block& block) { return block.Pairs.Eigenvectors.cols() > 0; });
  result.Eigenvalues.resize(static_cast<Eigen::Index>(chosen.size()));
  result.Eigenvectors = vectors ? DenseMatrix::Zero(n, result.Eigenvalues.size()) : DenseMatrix();
  for (std::size_t j = 0; j < chosen.size(); ++j)
  {
    const Block& block = blocks[static_cast<std::size_t>(chosen[j].first)];
    const int k = chosen[j].second;
    result.Eigenvalues[static_cast<Eigen::Index>(j)] = block.Pairs.Eigenvalues[k];
    for (std::size_t r = 0; vectors && r < block.Rows.size(); ++r)
    {
      result.Eigenvectors(block.Rows[r], static_cast<Eigen::Index>(j)) =
        block.Pairs.Eigenvectors(static_cast<Eigen::Index>(r), k);
    }
  }
}

/**
 * A pair of the union, in the order of its sort key: the eigenvalue (with constant harmonics,
 * exactly 0 for the first pair of each component, whatever round-off the solver left), minus the
 * size of the component for those (the largest components first), the component and the index
 * within its pairs.
 */
using Member = std::tuple<double, int, int, int>;

//------------------------------------------------------------------------------
// The m smallest pairs of the union, ascending; the zero eigenvalues of the largest components
// first, other ties in component order.
std::vector<Member> Smallest(const std::vector<Block>& blocks, int m, bool constant)
{
  std::vector<Member> all;
  for (std::size_t c = 0; c < blocks.size(); ++c)
  {
    const Vector& lambda = blocks[c].Pairs.Eigenvalues;
    const int size = static_cast<int>(blocks[c].Rows.size());
    for (Eigen::Index k = 0; k < lambda.size(); ++k)
    {
      const bool zero = constant && k == 0;
      all.emplace_back(
        zero ? 0.0 : lambda[k], zero ? -size : 0, static_cast<int>(c), static_cast<int>(k));
    }
  }
  std::sort(all.begin(), all.end());
  all.resize(std::min<std::size_t>(all.size(), static_cast<std::size_t>(m)));
  return all;
}

//------------------------------------------------------------------------------
// Whether a component may hide eigenvalues below `threshold`: it has more pairs than it was
// asked for and its largest computed eigenvalue lies below the threshold.
bool MayHideEigenvalues(const Block& block, double threshold)
{
  const Vector& lambda = block.Pairs.Eigenvalues;
  return block.Asked < static_cast<int>(block.Rows.size()) &&
    (lambda.size() == 0 || lambda[lambda.size() - 1] < threshold);
}
} // anonymous namespace

//------------------------------------------------------------------------------
void AddStatistics(EigenResult& total, const EigenResult& part)
{
  total.MaxResidual = std::max(total.MaxResidual, part.MaxResidual);
  total.MaxBackwardError = std::max(total.MaxBackwardError, part.MaxBackwardError);
  total.Bands += part.Bands;
  total.Factorizations += part.Factorizations;
  total.OperatorApplications += part.OperatorApplications;
  total.MostKeptVectors = std::max(total.MostKeptVectors, part.MostKeptVectors);
  total.Retries += part.Retries;
  total.MostKrylovColumns = std::max(total.MostKrylovColumns, part.MostKrylovColumns);
  total.Seconds.Factorization += part.Seconds.Factorization;
  total.Seconds.Solve += part.Seconds.Solve;
  total.Seconds.Orthogonalization += part.Seconds.Orthogonalization;
  total.Seconds.RayleighRitz += part.Seconds.RayleighRitz;
  total.Seconds.Verification += part.Seconds.Verification;
}

//------------------------------------------------------------------------------
EigenResult SmallestEigenpairsByComponent(const SparseMatrix& L,
  const SparseMatrix& M,
  const Vector& weight,
  const std::vector<int>& label,
  int count,
  int m,
  const PairSolver& solve,
  const Monitor& monitor,
  bool constantHarmonics,
  ComponentChoice* choice)
{
  if (count <= 1)
  {
    EigenResult result = solve(L, M, PairRequest{ m }, monitor);
    if (choice)
    {
      choice->Asked = { m };
      choice->Tolerance = { result.ResidualTolerance };
      choice->Pairs.clear();
      for (int k = 0; k < static_cast<int>(result.Eigenvalues.size()); ++k)
      {
        choice->Pairs.emplace_back(0, k);
      }
    }
    return result;
  }
  std::vector<Block> blocks = SplitBlocks(L, M, label, count);
  for (std::size_t i = 0; i < label.size(); ++i)
  {
    blocks[static_cast<std::size_t>(label[i])].Area += weight[static_cast<Eigen::Index>(i)];
  }
  const double totalArea = weight.sum();
  const double n = static_cast<double>(L.rows());
  EigenResult result;
  double done = 0.0;
  for (Block& block : blocks)
  {
    const double share = static_cast<double>(block.Rows.size()) / n;
    block.Asked = FirstRequest(block, totalArea, m);
    block.Pairs =
      solve(block.L, block.M, PairRequest{ block.Asked }, monitor.Scaled(done, done + share));
    AddStatistics(result, block.Pairs);
    done += share;
  }
  // Components that may hide eigenvalues below the m-th smallest of the union are solved
  // again with more pairs; each pass at least doubles a request, so this ends.
  Monitor quiet;
  quiet.Cancelled = monitor.Cancelled;
  for (bool again = true; again;)
  {
    again = false;
    const std::vector<Member> smallest = Smallest(blocks, m, constantHarmonics);
    const double threshold = smallest.size() < static_cast<std::size_t>(m)
      ? std::numeric_limits<double>::infinity()
      : std::get<0>(smallest.back());
    for (Block& block : blocks)
    {
      if (MayHideEigenvalues(block, threshold))
      {
        block.Asked = std::min(static_cast<int>(block.Rows.size()), std::max(2 * block.Asked, 1));
        block.Pairs = solve(block.L, block.M, PairRequest{ block.Asked }, quiet);
        AddStatistics(result, block.Pairs);
        again = true;
      }
    }
  }

  // Which pairs: by the sort key. In what order: by the computed eigenvalues, ascending (the
  // zero eigenvalues of different components differ by round-off, in either direction).
  std::vector<Member> smallest = Smallest(blocks, m, constantHarmonics);
  const auto value = [&blocks](const Member& member)
  {
    return blocks[static_cast<std::size_t>(std::get<2>(member))]
      .Pairs.Eigenvalues[std::get<3>(member)];
  };
  std::stable_sort(smallest.begin(),
    smallest.end(),
    [&value](const Member& a, const Member& b) { return value(a) < value(b); });
  std::vector<std::pair<int, int>> chosen;
  for (const Member& member : smallest)
  {
    chosen.emplace_back(std::get<2>(member), std::get<3>(member));
  }
  Gather(blocks, chosen, L.rows(), result);
  if (choice)
  {
    choice->Asked.clear();
    choice->Tolerance.clear();
    for (const Block& block : blocks)
    {
      choice->Asked.push_back(block.Asked);
      choice->Tolerance.push_back(block.Pairs.ResidualTolerance);
    }
    choice->Pairs = std::move(chosen);
  }
  monitor.Report(1.0);
  return result;
}

//------------------------------------------------------------------------------
void ForEachChosenComponent(const SparseMatrix& L,
  const SparseMatrix& M,
  const std::vector<int>& label,
  int count,
  const ComponentChoice& choice,
  const ComponentSolver& solve,
  const Monitor& monitor)
{
  std::vector<bool> chosen(static_cast<std::size_t>(std::max(count, 1)), false);
  for (const auto& pair : choice.Pairs)
  {
    chosen[static_cast<std::size_t>(pair.first)] = true;
  }
  if (count <= 1)
  {
    std::vector<int> rows(static_cast<std::size_t>(L.rows()));
    std::iota(rows.begin(), rows.end(), 0);
    if (chosen[0])
    {
      solve(0, rows, L, M, PairRequest{ choice.Asked[0] }, monitor);
    }
    monitor.Report(1.0);
    return;
  }
  const std::vector<Block> blocks = SplitBlocks(L, M, label, count);
  const double n = static_cast<double>(L.rows());
  double done = 0.0;
  for (std::size_t c = 0; c < blocks.size(); ++c)
  {
    const Block& block = blocks[c];
    const double share = static_cast<double>(block.Rows.size()) / n;
    monitor.ThrowIfCancelled();
    if (chosen[c])
    {
      solve(static_cast<int>(c),
        block.Rows,
        block.L,
        block.M,
        PairRequest{ choice.Asked[c] },
        monitor.Scaled(done, done + share));
    }
    done += share;
  }
  monitor.Report(1.0);
}

//------------------------------------------------------------------------------
EigenResult EigenpairsInWindowByComponent(const SparseMatrix& L,
  const SparseMatrix& M,
  const std::vector<int>& label,
  int count,
  double low,
  double high,
  const PairSolver& solve,
  const WindowCounted& counted,
  int& below,
  const Monitor& monitor)
{
  std::vector<Block> blocks;
  if (count > 1)
  {
    blocks = SplitBlocks(L, M, label, count);
  }
  const std::size_t parts = std::max<std::size_t>(blocks.size(), 1);
  const auto stiffness = [&](std::size_t c) -> const SparseMatrix&
  { return count > 1 ? blocks[c].L : L; };
  const auto mass = [&](std::size_t c) -> const SparseMatrix&
  { return count > 1 ? blocks[c].M : M; };

  // Each component's eigenvalues below both ends (Sylvester's law; below omega = 0 there is
  // none, L being positive semi-definite), then their sums for the caller.
  std::vector<std::pair<int, int>> ends(parts);
  below = 0;
  int inWindow = 0;
  for (std::size_t c = 0; c < parts; ++c)
  {
    monitor.ThrowIfCancelled();
    ends[c].first = low > 0.0 ? CountEigenvaluesBelow(stiffness(c), mass(c), low) : 0;
    ends[c].second = CountEigenvaluesBelow(stiffness(c), mass(c), high);
    below += ends[c].first;
    inWindow += std::max(0, ends[c].second - ends[c].first);
  }
  if (counted)
  {
    counted(below, inWindow);
  }

  // The pairs of each component in the window, starting there; none if it has no eigenvalue
  // there.
  const auto inWindowOf = [&](std::size_t c, const Monitor& part)
  {
    monitor.ThrowIfCancelled();
    const auto [first, end] = ends[c];
    return end > first ? solve(stiffness(c), mass(c), PairRequest{ end - first, first, low }, part)
                       : EigenResult();
  };
  if (count <= 1)
  {
    EigenResult result = inWindowOf(0, monitor);
    monitor.Report(1.0);
    return result;
  }
  EigenResult result;
  const double n = static_cast<double>(L.rows());
  double done = 0.0;
  std::vector<std::tuple<double, int, int>> members;
  for (std::size_t c = 0; c < blocks.size(); ++c)
  {
    Block& block = blocks[c];
    const double share = static_cast<double>(block.Rows.size()) / n;
    block.Pairs = inWindowOf(c, monitor.Scaled(done, done + share));
    AddStatistics(result, block.Pairs);
    for (Eigen::Index k = 0; k < block.Pairs.Eigenvalues.size(); ++k)
    {
      members.emplace_back(block.Pairs.Eigenvalues[k], static_cast<int>(c), static_cast<int>(k));
    }
    done += share;
  }
  std::sort(members.begin(), members.end());
  std::vector<std::pair<int, int>> chosen;
  for (const auto& member : members)
  {
    chosen.emplace_back(std::get<1>(member), std::get<2>(member));
  }
  Gather(blocks, chosen, L.rows(), result);
  monitor.Report(1.0);
  return result;
}
} // namespace spectral
