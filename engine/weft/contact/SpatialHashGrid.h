#pragma once
// Broad phase for self-collision: all pairs of axis-aligned boxes that overlap, through a
// uniform grid stored in a hash table (Teschner et al. 2003). Each box is entered into every
// cell it covers; a pair is reported only from the cell that contains the lower corner of the
// two boxes' intersection, so exactly once. With the cell size about the typical box size, each
// box covers O(1) cells and meets O(1) others: the work and memory grow linearly with the number
// of boxes (the reference code's dense N x N table grows quadratically).

#include <weft/core/Types.h>

#include <utility>
#include <vector>

namespace weft {

class SpatialHashGrid {
 public:
  // Finds the overlapping pairs (a < b) of the boxes [lower[i], upper[i]], in no particular
  // order. Parallel over hash buckets; the buffers are kept between calls.
  void overlappingPairs(const std::vector<Vec3>& lower, const std::vector<Vec3>& upper,
                        double cellSize, std::vector<std::pair<int, int>>& out);
  int lastEntryCount() const { return static_cast<int>(entries_.size()); }
  int lastBucketCount() const { return static_cast<int>(bucketStart_.size()) - 1; }

 private:
  struct Entry {
    int item;
    int cell[3];
  };
  std::vector<int> itemStart_;  // entries of item i: [itemStart_[i], itemStart_[i + 1])
  std::vector<Entry> unsorted_, entries_;
  std::vector<unsigned> bucketOf_;
  std::vector<int> lowerCell_;  // the cell of each box's lower corner, 3 per box
  std::vector<int> bucketStart_;
  std::vector<std::vector<std::pair<int, int>>> perThread_;
};

}  // namespace weft
