#include <weft/contact/SpatialHashGrid.h>

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace weft {
namespace {

// Cell coordinates stay far inside int range for any cloth-sized scene; clamp anyway so a
// blown-up node cannot overflow them (the simulator stops such runs right after the step).
int cellCoordinate(double v, double inverseCell) {
  const double c = std::floor(v * inverseCell);
  return static_cast<int>(std::max(-1e9, std::min(1e9, c)));
}

unsigned hashCell(const int c[3], unsigned mask) {
  return (static_cast<unsigned>(c[0]) * 73856093u ^ static_cast<unsigned>(c[1]) * 19349663u ^
          static_cast<unsigned>(c[2]) * 83492791u) &
         mask;
}

}  // namespace

void SpatialHashGrid::overlappingPairs(const std::vector<Vec3>& lower,
                                       const std::vector<Vec3>& upper, double cellSize,
                                       std::vector<std::pair<int, int>>& out) {
  const int n = static_cast<int>(lower.size());
  // 1. Cells per box, and where each box's entries go. Should a few huge boxes (a blow-up in
  // progress) cover too many cells, coarser cells keep the table linear in the box count.
  const long long budget = 64LL * n + 4096;
  double inv = 1.0 / cellSize;
  itemStart_.resize(n + 1);
  for (int attempt = 0;; ++attempt, inv *= 0.5) {
    itemStart_[0] = 0;
    long long total = 0;
    for (int i = 0; i < n && total <= budget; ++i) {
      long long count = 1;
      for (int k = 0; k < 3; ++k)
        count *= static_cast<long long>(cellCoordinate(upper[i][k], inv)) -
                 cellCoordinate(lower[i][k], inv) + 1;
      total += count;
      itemStart_[i + 1] = static_cast<int>(std::min(total, budget + 1));
    }
    if (total <= budget || attempt == 60) break;
  }
  const int total = itemStart_[n];
  unsigned buckets = 1;
  while (buckets < 2u * static_cast<unsigned>(total)) buckets <<= 1;
  const unsigned mask = buckets - 1;
  unsorted_.resize(total);
  lowerCell_.resize(3 * static_cast<std::size_t>(n));
  bucketOf_.resize(total);
  // 2. The entries, with their buckets.
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k)
      lo[k] = cellCoordinate(lower[i][k], inv), hi[k] = cellCoordinate(upper[i][k], inv);
    for (int k = 0; k < 3; ++k) lowerCell_[3 * static_cast<std::size_t>(i) + k] = lo[k];
    int e = itemStart_[i];
    for (int x = lo[0]; x <= hi[0]; ++x)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int z = lo[2]; z <= hi[2]; ++z, ++e) {
          unsorted_[e] = Entry{i, {x, y, z}};
          bucketOf_[e] = hashCell(unsorted_[e].cell, mask);
        }
  }
  // 3. Counting sort of the entries by bucket.
  bucketStart_.assign(buckets + 1, 0);
  for (int e = 0; e < total; ++e) ++bucketStart_[bucketOf_[e] + 1];
  for (unsigned b = 0; b < buckets; ++b) bucketStart_[b + 1] += bucketStart_[b];
  entries_.resize(total);
  {
    std::vector<int>& cursor = itemStart_;  // reuse: item offsets are no longer needed
    cursor.assign(bucketStart_.begin(), bucketStart_.end() - 1);
    for (int e = 0; e < total; ++e) entries_[cursor[bucketOf_[e]]++] = unsorted_[e];
  }
  // 4. Pairs within each bucket that share a cell, reported from the cell holding the lower
  // corner of their boxes' intersection.
  const int threads = omp_get_max_threads();
  if (static_cast<int>(perThread_.size()) < threads) perThread_.resize(threads);
  int used = 1;
#pragma omp parallel
  {
    std::vector<std::pair<int, int>>& local = perThread_[omp_get_thread_num()];
    local.clear();
#pragma omp single
    used = omp_get_num_threads();
#pragma omp for schedule(dynamic, 256)
    for (int b = 0; b < static_cast<int>(buckets); ++b) {
      for (int p = bucketStart_[b]; p < bucketStart_[b + 1]; ++p) {
        const Entry& ep = entries_[p];
        for (int q = p + 1; q < bucketStart_[b + 1]; ++q) {
          const Entry& eq = entries_[q];
          if (ep.cell[0] != eq.cell[0] || ep.cell[1] != eq.cell[1] || ep.cell[2] != eq.cell[2])
            continue;
          // Reported from this cell only if it holds the intersection's lower corner: the larger
          // of the two boxes' lower cells in each axis (floor is monotonic).
          const int a = ep.item, c = eq.item;
          const int* cellA = lowerCell_.data() + 3 * static_cast<std::size_t>(a);
          const int* cellC = lowerCell_.data() + 3 * static_cast<std::size_t>(c);
          if (std::max(cellA[0], cellC[0]) != ep.cell[0] ||
              std::max(cellA[1], cellC[1]) != ep.cell[1] ||
              std::max(cellA[2], cellC[2]) != ep.cell[2])
            continue;
          const Vec3 &lowA = lower[a], &lowC = lower[c], &upA = upper[a], &upC = upper[c];
          if (lowA.x() <= upC.x() && lowC.x() <= upA.x() && lowA.y() <= upC.y() &&
              lowC.y() <= upA.y() && lowA.z() <= upC.z() && lowC.z() <= upA.z())
            local.emplace_back(std::min(a, c), std::max(a, c));
        }
      }
    }
  }
  for (int t = 0; t < used; ++t) out.insert(out.end(), perThread_[t].begin(), perThread_[t].end());
}

}  // namespace weft
