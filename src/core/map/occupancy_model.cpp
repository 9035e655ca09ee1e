#include "hex_slam/map/occupancy_model.h"

#include <stdexcept>

namespace hex_slam {

OccupancyModel OccupancyModel::FromFactors(double update_factor_free,
                                           double update_factor_occupied,
                                           double log_odds_limit) {
  if (!(update_factor_free > 0.0 && update_factor_free < 0.5)) {
    throw std::invalid_argument("update_factor_free must lie in (0, 0.5)");
  }
  if (!(update_factor_occupied > 0.5 && update_factor_occupied < 1.0)) {
    throw std::invalid_argument("update_factor_occupied must lie in (0.5, 1)");
  }
  if (!(log_odds_limit > 0.0)) throw std::invalid_argument("log_odds_limit must be positive");
  OccupancyModel model;
  model.free_delta = LogOdds(update_factor_free);
  model.occupied_delta = LogOdds(update_factor_occupied);
  model.min_log_odds = static_cast<float>(-log_odds_limit);
  model.max_log_odds = static_cast<float>(log_odds_limit);
  return model;
}

}  // namespace hex_slam
