// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Common/Seams.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace spectral
{
namespace
{
//------------------------------------------------------------------------------
bool Finite(const double x[3])
{
  return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
}

double Distance2(const double a[3], const double b[3])
{
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
    (a[2] - b[2]) * (a[2] - b[2]);
}

//------------------------------------------------------------------------------
// The bounding box of the finite points of `xyz` (n by 3); zeros if there are none.
void FiniteBounds(const double* xyz, long long n, double bounds[6])
{
  double box[6] = { std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity() };
  bool any = false;
  for (long long i = 0; i < n; ++i)
  {
    const double* x = xyz + 3 * i;
    if (Finite(x))
    {
      any = true;
      for (int d = 0; d < 3; ++d)
      {
        box[2 * d] = std::min(box[2 * d], x[d]);
        box[2 * d + 1] = std::max(box[2 * d + 1], x[d]);
      }
    }
  }
  if (any)
  {
    std::copy(box, box + 6, bounds);
  }
}

//------------------------------------------------------------------------------
// A hash grid of cells four times the merge radius (still far smaller than the spacing of
// distinct points): a search looks at the cell of the point, and at a neighbouring cell only
// along an axis where the point lies within the radius of the cell's side (3.4 cells on average).
class WeldGrid
{
public:
  WeldGrid(const double bounds[6], double radius)
    : Origin{ bounds[0], bounds[2], bounds[4] }
    , Radius(radius)
  {
    const double extent =
      std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4], 1e-300 });
    // Cell indices stay far inside 64 bits (radius 0: exact matches).
    this->Size = std::max(4.0 * radius, extent * 1e-15);
  }

  void Add(const double x[3], long long welded)
  {
    CellKey key;
    for (int d = 0; d < 3; ++d)
    {
      key[d] = this->Index(x, d);
    }
    this->Cells[key].push_back(welded);
  }

  // The smallest welded id whose first copy lies within the radius of x, or -1.
  long long Find(const double x[3], const double* xyz, const std::vector<long long>& first) const
  {
    // Per axis: the cell of x, and the neighbour whose side lies within the radius (if any).
    std::array<std::array<std::int64_t, 2>, 3> candidates;
    std::array<int, 3> counts;
    for (int d = 0; d < 3; ++d)
    {
      const std::int64_t index = this->Index(x, d);
      const double offset = x[d] - this->Origin[d] - static_cast<double>(index) * this->Size;
      candidates[d] = { index, offset <= this->Radius ? index - 1 : index + 1 };
      counts[d] = offset <= this->Radius || this->Size - offset <= this->Radius ? 2 : 1;
    }
    long long found = -1;
    for (int a = 0; a < counts[0]; ++a)
    {
      for (int b = 0; b < counts[1]; ++b)
      {
        for (int c = 0; c < counts[2]; ++c)
        {
          const auto cell =
            this->Cells.find({ candidates[0][a], candidates[1][b], candidates[2][c] });
          if (cell == this->Cells.end())
          {
            continue;
          }
          for (long long j : cell->second)
          {
            if ((found < 0 || j < found) &&
              Distance2(x, xyz + 3 * first[static_cast<std::size_t>(j)]) <=
                this->Radius * this->Radius)
            {
              found = j;
            }
          }
        }
      }
    }
    return found;
  }

private:
  using CellKey = std::array<std::int64_t, 3>;
  struct KeyHash
  {
    std::size_t operator()(const CellKey& k) const
    {
      const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
      return static_cast<std::size_t>(
        (u(k[0]) * 73856093u) ^ (u(k[1]) * 19349663u) ^ (u(k[2]) * 83492791u));
    }
  };

  std::int64_t Index(const double x[3], int d) const
  {
    return static_cast<std::int64_t>(std::floor((x[d] - this->Origin[d]) / this->Size));
  }

  std::array<double, 3> Origin;
  double Radius;
  double Size = 1.0;
  std::unordered_map<CellKey, std::vector<long long>, KeyHash> Cells;
};
} // anonymous namespace

//------------------------------------------------------------------------------
Welding WeldPoints(const double* xyz,
  long long n,
  const double* bounds,
  double tolerance,
  const std::vector<unsigned char>& owned)
{
  double box[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  if (bounds)
  {
    std::copy(bounds, bounds + 6, box);
  }
  else
  {
    FiniteBounds(xyz, n, box);
  }
  const double low[3] = { box[0], box[2], box[4] };
  const double high[3] = { box[1], box[3], box[5] };
  const double radius = tolerance * std::sqrt(Distance2(low, high));
  WeldGrid grid(box, radius);
  Welding welding;
  welding.Map.resize(static_cast<std::size_t>(n));
  const bool hasOwnership = static_cast<long long>(owned.size()) == n;
  std::vector<bool> countedIsOwned;
  for (long long i = 0; i < n; ++i)
  {
    const double* x = xyz + 3 * i;
    const bool finite = Finite(x);
    // The earliest welded point within the radius (non-finite points stay apart).
    long long j = finite ? grid.Find(x, xyz, welding.First) : -1;
    const bool isOwned = !hasOwnership || owned[static_cast<std::size_t>(i)] != 0;
    if (j < 0)
    {
      j = static_cast<long long>(welding.First.size());
      welding.First.push_back(i);
      welding.Counted.push_back(i);
      countedIsOwned.push_back(isOwned);
      if (finite)
      {
        grid.Add(x, j);
      }
    }
    else if (isOwned && !countedIsOwned[static_cast<std::size_t>(j)])
    {
      // A copy of an earlier point: it owns it if it is the first owned one.
      welding.Counted[static_cast<std::size_t>(j)] = i;
      countedIsOwned[static_cast<std::size_t>(j)] = true;
    }
    welding.Map[static_cast<std::size_t>(i)] = j;
  }
  return welding;
}
} // namespace spectral
