#include "hex_slam/common/parameter_table.h"

#include <algorithm>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hex_slam/mapping/slam.h"
#include "hex_slam/mapping/slam_options.h"

namespace hex_slam {
namespace {

TEST(ParameterTableTest, SetsAndReadsEveryType) {
  SlamOptions options;
  ParameterTable table = SlamParameterTable(&options);
  EXPECT_EQ(table.Set("map_resolution", "0.05"), "");
  EXPECT_EQ(table.Set("map_size", "512"), "");
  EXPECT_EQ(table.Set("map_auto_grow", "false"), "");
  EXPECT_EQ(table.Set("lattice", "square"), "");
  EXPECT_EQ(table.Set("map_max_cells", "123456789"), "");
  EXPECT_DOUBLE_EQ(options.map_resolution, 0.05);
  EXPECT_EQ(options.map_size, 512);
  EXPECT_FALSE(options.map_auto_grow);
  EXPECT_EQ(options.lattice, "square");
  EXPECT_EQ(options.map_max_cells, 123456789);
  EXPECT_EQ(table.Get("map_size"), "512");
}

TEST(ParameterTableTest, UnknownKeysAndBadValuesAreErrorsNamingTheKey) {
  SlamOptions options;
  ParameterTable table = SlamParameterTable(&options);
  const auto errors = table.Apply({{"map_resoluton", "0.05"},
                                   {"map_size", "big"},
                                   {"map_auto_grow", "maybe"},
                                   {"laser_max_dist", "nan"},
                                   {"map_multi_res_levels", "99999999999"}});
  ASSERT_EQ(errors.size(), 5u);
  std::string all;
  for (const auto& e : errors) all += e + "\n";
  for (const char* key : {"map_resoluton", "map_size", "map_auto_grow", "laser_max_dist",
                          "map_multi_res_levels"}) {
    EXPECT_NE(all.find(key), std::string::npos) << key;
  }
  EXPECT_EQ(options.map_size, SlamOptions().map_size);  // a bad value leaves the default
}

TEST(ParameterTableTest, SuggestionsAreForMisspellingsOnly) {
  SlamOptions options;
  ParameterTable table = SlamParameterTable(&options);
  EXPECT_EQ(table.ClosestKey("map_resoluton"), "map_resolution");
  // A kilobyte of garbage is nobody's misspelling: named, without a suggestion.
  EXPECT_EQ(table.ClosestKey(std::string(1000, 'm')), "");
  // Nine misspellings: the first eight get the nearest name, the ninth only its own.
  std::map<std::string, std::string> values;
  for (char c = 'a'; c <= 'i'; ++c) values[std::string("map_resolution") + c] = "0.05";
  const auto errors = table.Apply(values);
  ASSERT_EQ(errors.size(), 9u);
  for (std::size_t i = 0; i < errors.size(); ++i) {
    EXPECT_EQ(errors[i].find("did you mean 'map_resolution'") != std::string::npos, i < 8)
        << errors[i];
  }
}

// The full dynamic programme, as the oracle for the banded one behind ClosestKey.
std::size_t Levenshtein(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1,
                          d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
    }
  }
  return d[a.size()][b.size()];
}

TEST(ParameterTableTest, ClosestKeyIsTheFirstKeyAtTheLeastDistanceWithinAQuarter) {
  SlamOptions options;
  const ParameterTable table = SlamParameterTable(&options);
  const std::vector<std::string> keys = table.Keys();
  std::mt19937 random(7);
  for (int trial = 0; trial < 300; ++trial) {
    // A known key with a few random edits, or a random string.
    std::string key = keys[random() % keys.size()];
    const int edits = static_cast<int>(random() % 8);
    for (int e = 0; e < edits && !key.empty(); ++e) {
      const std::size_t at = random() % key.size();
      const char c = static_cast<char>('a' + random() % 26);
      switch (random() % 3) {
        case 0: key[at] = c; break;
        case 1: key.insert(key.begin() + at, c); break;
        default: key.erase(key.begin() + at); break;
      }
    }
    const std::size_t most = std::max<std::size_t>(2, key.size() / 4);
    std::string expected;
    std::size_t best = most + 1;
    for (const std::string& k : keys) {
      const std::size_t d = Levenshtein(key, k);
      if (d < best) best = d, expected = k;
    }
    EXPECT_EQ(table.ClosestKey(key), expected) << key;
  }
}

TEST(ParameterTableTest, DuplicateRegistrationIsAProgrammingError) {
  SlamOptions options;
  ParameterTable table = SlamParameterTable(&options);
  EXPECT_THROW(table.Merge(SlamParameterTable(&options)), std::logic_error);
}

TEST(SlamOptionsTest, DefaultsAreValidAndFollowHector) {
  const SlamOptions o;
  EXPECT_TRUE(o.Validate().empty());
  EXPECT_DOUBLE_EQ(o.update_factor_free, 0.4);
  EXPECT_DOUBLE_EQ(o.update_factor_occupied, 0.9);
  EXPECT_DOUBLE_EQ(o.map_update_distance_thresh, 0.4);
  EXPECT_DOUBLE_EQ(o.map_update_angle_thresh, 0.9);
  EXPECT_EQ(o.map_multi_res_levels, 3);
}

TEST(SlamOptionsTest, TheMapIsBoundedByDefaultAndByAHardLimit) {
  SlamOptions o;
  // 16.8 million cells: 200 m x 200 m of 5 cm squares (hector's map is 1024 x 1024 cells).
  EXPECT_EQ(o.map_max_cells, std::int64_t{1} << 24);
  EXPECT_GE(o.map_max_cells, static_cast<std::int64_t>(200.0 / 0.05) * (200.0 / 0.05));
  o.map_max_cells = kMaxMapCells;
  EXPECT_TRUE(o.Validate().empty());
  o.map_max_cells = kMaxMapCells + 1;
  ASSERT_EQ(o.Validate().size(), 1u);
  EXPECT_NE(o.Validate()[0].find("map_max_cells"), std::string::npos);
  o = SlamOptions();
  o.odometry_jump_distance_thresh = 0.0;
  o.odometry_jump_angle_thresh = 4.0;
  o.recovery.max_candidates = 0;
  std::string all;
  for (const auto& e : o.Validate()) all += e + "\n";
  for (const char* key : {"odometry_jump_distance_thresh", "odometry_jump_angle_thresh",
                          "recovery_max_candidates"}) {
    EXPECT_NE(all.find(key), std::string::npos) << key << " not reported in:\n" << all;
  }
}

TEST(SlamOptionsTest, OptionsThatValidateMakeASlam) {
  // Found by the parameters fuzz target: map_max_cells = map_size^2 passed Validate, but the hex
  // lattice's initial storage holds more cells than that (its columns are 0.87 spacings apart),
  // and the map threw "initial map exceeds the cell cap" from Slam's constructor.
  for (const char* lattice : {"hex", "square"}) {
    SlamOptions o;
    o.lattice = lattice;
    o.map_size = 16;
    o.map_max_cells = 256;
    ASSERT_EQ(o.Validate().size(), 1u) << lattice;
    EXPECT_NE(o.Validate()[0].find("map_max_cells must hold the initial"), std::string::npos);
    // 0.8 m of storage with a cell's margin each side: 19 rows of 0.05 m either way; columns
    // 0.043 m apart on hexagons, -11..11 = 23 of them (437 cells), 19 on squares (361).
    o.map_max_cells = std::string(lattice) == "hex" ? 436 : 360;
    EXPECT_FALSE(o.Validate().empty()) << lattice;
    o.map_max_cells += 1;
    EXPECT_TRUE(o.Validate().empty()) << lattice;
    EXPECT_NO_THROW(Slam slam(o)) << lattice;
  }
}

TEST(SlamOptionsTest, LevelsStopBeforeCellsExceedTheCoarseLimit) {
  SlamOptions o;
  o.map_max_coarse_resolution = 0.5;
  o.map_resolution = 0.05;  // 0.05, 0.1, 0.2
  EXPECT_EQ(EffectiveLevels(o), 3);
  o.map_resolution = 0.2149;  // 0.21, 0.43 (0.86 would exceed 0.5)
  EXPECT_EQ(EffectiveLevels(o), 2);
  o.map_resolution = 0.8;  // the finest level is always built
  EXPECT_EQ(EffectiveLevels(o), 1);
  o.map_resolution = 0.01;
  o.map_multi_res_levels = 5;  // 0.01 ... 0.16
  o.map_min_coarse_resolution = 0.0;
  EXPECT_EQ(EffectiveLevels(o), 5);
}

TEST(SlamOptionsTest, ByDefaultExactlyTheLevelsAskedForAreBuilt) {
  SlamOptions o;  // hector's behaviour: neither limit is set
  for (double resolution : {0.001, 0.025, 0.05, 0.8}) {
    for (int levels : {1, 2, 3, 5}) {
      o.map_resolution = resolution;
      o.map_multi_res_levels = levels;
      EXPECT_EQ(EffectiveLevels(o), levels) << resolution << " m, " << levels << " levels";
    }
  }
}

TEST(SlamOptionsTest, LevelsAreAddedUntilTheCoarsestCellReachesTheMinimum) {
  SlamOptions o;  // 3 levels asked, 0.15 m minimum, 0.5 m cap
  o.map_min_coarse_resolution = 0.15;
  o.map_max_coarse_resolution = 0.5;
  o.map_resolution = 0.05;  // 0.05, 0.1, 0.2: enough already
  EXPECT_EQ(EffectiveLevels(o), 3);
  o.map_resolution = 0.0465;  // the equal-area square: 0.186 m, enough too
  EXPECT_EQ(EffectiveLevels(o), 3);
  o.map_resolution = 0.025;  // hector's: 0.1 m after three levels, 0.2 m after four
  EXPECT_EQ(EffectiveLevels(o), 4);
  o.map_resolution = 0.01;  // 0.16 m after five
  EXPECT_EQ(EffectiveLevels(o), 5);
  o.map_resolution = 0.001;  // never beyond kMaxMapLevels
  EXPECT_EQ(EffectiveLevels(o), kMaxMapLevels);
  o.map_resolution = 0.025;
  o.map_min_coarse_resolution = 0.0;  // hector's behaviour: exactly the levels asked for
  EXPECT_EQ(EffectiveLevels(o), 3);
  o.map_min_coarse_resolution = 0.6;  // above the cap: contradictory
  EXPECT_FALSE(o.Validate().empty());
}

TEST(SlamOptionsTest, NonsenseValuesAreRejectedByName) {
  SlamOptions o;
  o.map_resolution = -0.05;
  o.map_multi_res_levels = 0;
  o.lattice = "triangle";
  o.update_factor_free = 0.7;
  o.laser_max_dist = 0.1;
  o.matcher.max_iterations_fine = 0;
  const auto errors = o.Validate();
  std::string all;
  for (const auto& e : errors) all += e + "\n";
  for (const char* key : {"map_resolution", "map_multi_res_levels", "lattice",
                          "update_factor_free", "laser_max_dist",
                          "scan_match_max_iterations_fine"}) {
    EXPECT_NE(all.find(key), std::string::npos) << key << " not reported in:\n" << all;
  }
}

}  // namespace
}  // namespace hex_slam
