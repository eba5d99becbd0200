// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Distributed/Numbering.h"
#include "Common/Seams.h"
#include "Distributed/Petsc.h"
#include "Operators/Operators.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace spectral
{
namespace distributed
{
namespace
{
//------------------------------------------------------------------------------
// The border points of a piece (BorderPoints), as a list.
std::vector<int> BorderList(const TriangleMesh& mesh)
{
  const std::vector<char> border = BorderPoints(mesh);
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
// Every process's `local` values, in rank order (collective); `offsets` (size + 1 entries) is
// set to where each rank's start, in units of `width` values.
template<typename T>
std::vector<T> AllGather(MPI_Comm comm,
  const std::vector<T>& local,
  MPI_Datatype type,
  int width,
  std::vector<int>& offsets)
{
  int size = 1;
  MPI_Comm_size(comm, &size);
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(size);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  std::vector<int> displacements(size + 1, 0);
  std::partial_sum(counts.begin(), counts.end(), displacements.begin() + 1);
  std::vector<T> all(static_cast<std::size_t>(displacements[size]));
  MPI_Allgatherv(
    local.data(), count, type, all.data(), counts.data(), displacements.data(), type, comm);
  offsets.resize(displacements.size());
  for (std::size_t r = 0; r < displacements.size(); ++r)
  {
    offsets[r] = displacements[r] / width;
  }
  return all;
}

//------------------------------------------------------------------------------
// Contiguous global numbers of the owned points after those of the lower ranks.
void NumberOwned(MPI_Comm comm, Numbering& numbering)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
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
  numbering.Global.assign(numbering.Owned.size(), -1);
  PetscInt next = static_cast<PetscInt>(start);
  for (std::size_t i = 0; i < numbering.Owned.size(); ++i)
  {
    if (numbering.Owned[i])
    {
      numbering.Global[i] = next++;
    }
  }
}
} // anonymous namespace

//------------------------------------------------------------------------------
Numbering NumberPoints(MPI_Comm comm,
  const TriangleMesh& mesh,
  const double bounds[6],
  bool weld,
  double tolerance,
  const std::vector<unsigned char>& ownedPoints)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // Every process receives the border points of all, in rank order, with their ownership.
  const std::vector<int> border = BorderList(mesh);
  const int count = static_cast<int>(border.size());
  std::vector<double> coordinates(3 * border.size());
  std::vector<unsigned char> flags(border.size(), 1);
  for (int b = 0; b < count; ++b)
  {
    for (int c = 0; c < 3; ++c)
    {
      coordinates[3 * b + c] = mesh.Vertices(border[b], c);
    }
    flags[b] = ownedPoints.empty() ? 1 : ownedPoints[static_cast<std::size_t>(border[b])];
  }
  std::vector<int> offsets;
  const std::vector<double> all = AllGather(comm, coordinates, MPI_DOUBLE, 3, offsets);
  const std::vector<unsigned char> allFlags = AllGather(comm, flags, MPI_UNSIGNED_CHAR, 1, offsets);
  const int gathered = offsets.back();

  // The same merge on every process: the owner rule (Seams.h) names the copy that owns a point.
  // Without welding (a serial run with WeldSeams off) every point is its own.
  std::vector<long long> owner(static_cast<std::size_t>(gathered));
  std::iota(owner.begin(), owner.end(), 0LL);
  if (weld)
  {
    const Welding welding = WeldPoints(all.data(), gathered, bounds, tolerance, allFlags);
    for (int g = 0; g < gathered; ++g)
    {
      owner[g] = welding.Counted[static_cast<std::size_t>(welding.Map[g])];
    }
  }
  Numbering numbering;
  numbering.Owned.assign(static_cast<std::size_t>(mesh.Vertices.rows()), 1);
  for (int b = 0; b < count; ++b)
  {
    numbering.Owned[border[b]] = owner[offsets[rank] + b] == offsets[rank] + b ? 1 : 0;
  }
  NumberOwned(comm, numbering);

  // The owners' numbers of the border points, for the copies held by other processes.
  std::vector<PetscInt> mine(border.size());
  for (int b = 0; b < count; ++b)
  {
    mine[b] = numbering.Global[border[b]];
  }
  const std::vector<PetscInt> numbers = AllGather(comm, mine, MPIU_INT, 1, offsets);
  for (int b = 0; b < count; ++b)
  {
    if (!numbering.Owned[border[b]])
    {
      numbering.Global[border[b]] = numbers[owner[offsets[rank] + b]];
    }
  }
  return numbering;
}

//------------------------------------------------------------------------------
Components DistributedComponents(MPI_Comm comm,
  const TriangleMesh& mesh,
  const Numbering& numbering,
  Vec lumped)
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const int n = static_cast<int>(mesh.Vertices.rows());

  // Local components, numbered after those of the lower ranks.
  const ComponentLabels local = LabelComponents(mesh);
  const int localCount = local.Count;
  int offset = 0;
  int nodes = 0;
  MPI_Exscan(&localCount, &offset, 1, MPI_INT, MPI_SUM, comm);
  MPI_Allreduce(&localCount, &nodes, 1, MPI_INT, MPI_SUM, comm);
  offset = rank == 0 ? 0 : offset;

  // Every process's links (global point number, local component + offset), in rank order.
  std::vector<long long> links;
  for (const int point : BorderList(mesh))
  {
    links.push_back(numbering.Global[point]);
    links.push_back(offset + local.Label[point]);
  }
  std::vector<int> offsets;
  const std::vector<long long> all = AllGather(comm, links, MPI_LONG_LONG, 2, offsets);
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
  SparseMatrix graph(nodes, nodes);
  graph.setFromTriplets(joined.begin(), joined.end());
  const ComponentLabels global = LabelComponents(graph);
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
} // namespace distributed
} // namespace spectral
