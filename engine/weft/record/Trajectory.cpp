#include <weft/record/Trajectory.h>

namespace weft {

std::vector<double> Trajectory::flattenedPositions() const {
  const std::size_t m = static_cast<std::size_t>(nodeCount());
  std::vector<double> out(positions.size() * m * 3);
  std::size_t k = 0;
  for (const NodeMatrix& x : positions)
    for (std::size_t i = 0; i < m; ++i)
      for (int c = 0; c < 3; ++c) out[k++] = x(static_cast<Eigen::Index>(i), c);
  return out;
}

}  // namespace weft
