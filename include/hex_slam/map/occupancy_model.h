// Log-odds occupancy: how a "hit" or a "pass" changes a cell, and how a cell reads as probability.
#ifndef HEX_SLAM_MAP_OCCUPANCY_MODEL_H_
#define HEX_SLAM_MAP_OCCUPANCY_MODEL_H_

#include <cmath>

namespace hex_slam {

struct OccupancyModel {
  float free_delta = 0.0f;      // added to a cell a beam passes through (negative)
  float occupied_delta = 0.0f;  // added to the cell a beam ends in (positive)
  float min_log_odds = 0.0f;    // clamps keep a cell able to change its mind after many scans
  float max_log_odds = 0.0f;

  // hector_mapping's parametrisation: update factors are the probabilities one observation
  // implies (free < 0.5 < occupied).
  static OccupancyModel FromFactors(double update_factor_free, double update_factor_occupied,
                                    double log_odds_limit);

  static float LogOdds(double probability) {
    return static_cast<float>(std::log(probability / (1.0 - probability)));
  }
  static float Probability(float log_odds) { return 1.0f - 1.0f / (1.0f + std::exp(log_odds)); }
};

}  // namespace hex_slam

#endif  // HEX_SLAM_MAP_OCCUPANCY_MODEL_H_
