#include "hex_slam/mapping/loop_closure/drift_graph.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <stdexcept>
#include <string>

namespace hex_slam {
namespace mapping {

DriftGraph::DriftGraph(double horizon) : horizon_(horizon) {
  if (!(horizon >= 0.0)) throw std::invalid_argument("DriftGraph: horizon must be >= 0");
}

void DriftGraph::AddSubmap(double first_path) {
  if (!std::isfinite(first_path) || (!first_paths_.empty() && first_path < first_paths_.back())) {
    throw std::invalid_argument("DriftGraph: submap paths must be finite and in order");
  }
  first_paths_.push_back(first_path);
  ties_.emplace_back();
  ++version_;
}

void DriftGraph::Tie(int a, int b) {
  if (a < 0 || b < 0 || a >= size() || b >= size()) {
    throw std::out_of_range("DriftGraph: tie between unknown submaps " + std::to_string(a) +
                            " and " + std::to_string(b));
  }
  if (a == b) return;
  // A submap revisited again and again is tied to the same few submaps each time.
  if (std::find(ties_[a].begin(), ties_[a].end(), b) != ties_[a].end()) return;
  ties_[a].push_back(b);
  ties_[b].push_back(a);
  ++version_;
}

std::vector<double> DriftGraph::Spread(std::vector<double> start) const {
  if (static_cast<int>(start.size()) != size()) {
    throw std::invalid_argument("DriftGraph: one start per submap");
  }
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int s = 0; s < size(); ++s) {
    start[s] = std::min(start[s], horizon_);
    if (start[s] < horizon_) queue.push({start[s], s});
  }
  std::vector<bool> settled(start.size(), false);
  const auto relax = [&](int s, double d) {
    if (d < start[s]) {
      start[s] = d;
      queue.push({d, s});
    }
  };
  while (!queue.empty()) {
    const auto [d, s] = queue.top();
    queue.pop();
    if (settled[s]) continue;
    settled[s] = true;
    for (const int t : ties_[s]) relax(t, d);
    if (s > 0) relax(s - 1, d + first_paths_[s] - first_paths_[s - 1]);
    if (s + 1 < size()) relax(s + 1, d + first_paths_[s + 1] - first_paths_[s]);
  }
  return start;
}

}  // namespace mapping
}  // namespace hex_slam
