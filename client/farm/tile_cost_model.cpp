#include "client/farm/tile_cost_model.h"

namespace glint {

TileCostModel::Key TileCostModel::keyOf(const TileJob& job) {
  return {job.rect.x, job.rect.y, job.rect.width, job.rect.height, static_cast<int>(tracedPixels(job))};
}

std::vector<double> TileCostModel::costs(std::span<const TileJob> jobs, const std::vector<std::size_t>& sent) const {
  double estimated = 0.0;
  double measured = 0.0;
  for (const auto& [key, m] : last_) {
    estimated += m.first;
    measured += m.second;
  }
  const double scale = measured > 0.0 ? estimated / measured : 0.0;
  std::vector<double> costs;
  costs.reserve(sent.size());
  for (const std::size_t j : sent) {
    const auto it = last_.find(keyOf(jobs[j]));
    costs.push_back(it != last_.end() && scale > 0.0 ? it->second.second * scale
                                                     : static_cast<double>(tracedPixels(jobs[j])));
  }
  return costs;
}

void TileCostModel::record(const TileJob& job, double estimate, double ms) { current_[keyOf(job)] = {estimate, ms}; }

void TileCostModel::nextFrame() {
  last_ = std::move(current_);
  current_.clear();
}

}  // namespace glint
