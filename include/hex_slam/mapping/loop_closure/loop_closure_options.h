// Every option of loop closure: submaps, the constraint search, the pose graph, and how often the
// worker optimises. Names and defaults follow Cartographer's where the concept is the same.
#ifndef HEX_SLAM_MAPPING_LOOP_CLOSURE_LOOP_CLOSURE_OPTIONS_H_
#define HEX_SLAM_MAPPING_LOOP_CLOSURE_LOOP_CLOSURE_OPTIONS_H_

#include <string>
#include <vector>

#include "hex_slam/mapping/loop_closure/constraint_builder.h"
#include "hex_slam/mapping/loop_closure/pose_graph.h"
#include "hex_slam/mapping/submap.h"

namespace hex_slam {
namespace mapping {

struct LoopClosureOptions {
  // On (the default): submaps, nodes and the background pose graph. Off: one global map and no
  // back end, exactly the incremental SLAM of before (hector's way).
  bool enabled = true;
  SubmapOptions submaps;
  ConstraintBuilderOptions constraints;
  PoseGraphOptions pose_graph;
  // The worker optimises after this many new nodes (Cartographer: 90), and once more at the end.
  int optimize_every_n_nodes = 45;
  // Keep the global map (Slam::hex_maps()) current between redraws: every inserted scan is also
  // added to it at its map-frame pose (one more map insertion per inserted scan). Off, the map
  // is only drawn by Slam::RefreshGlobalMap / FinishTrajectory (an offline run's choice).
  bool live_map = true;
  // How far the worker thread steps back from the thread that starts it (a nice increment,
  // 0-19). In the node, 10: when the cores are busy, scans go first and the searches wait. An
  // offline run waits for the worker at its end anyway, so hex_slam_offline takes 0: on a loaded
  // machine a worker at +10 gets a tenth of a core beside every ordinary process.
  int worker_niceness = 10;
  // Instead of the nice value, the worker runs in the idle class (MakeThisThreadIdle): a waking
  // scan takes the worker's core at once instead of after the rest of its slice, but on a
  // machine kept busy by other processes the worker nearly stops until a core is free, and
  // whoever waits for it (the end of an offline run, a map saved with its solution) waits as
  // long. For a robot whose cores are not kept busy, where the scan path's latency counts most.
  // Off by default.
  bool worker_idle_priority = false;
  // The scan path waits while this many finished submaps are queued for the worker (0: never
  // waits). An offline run waits for the worker at its end anyway, and a queued submap holds
  // its whole pyramid: the MIT Killian log's front end ran 3600 jobs (80 submaps) ahead of the
  // worker and peaked at 1.96 GB. The node never waits (the scan path must not), so there the
  // queue is as long as the worker is behind, and max_queued_submap_pyramids bounds what it
  // holds. Waiting changes no result: the worker's decisions depend only on the order of its
  // jobs.
  int max_queued_submaps = 0;
  // Of the finished submaps queued for the worker, at most this many keep their pyramids; a
  // later one is queued as its id alone and drawn again from its nodes when the worker searches
  // it (a redrawn submap differs slightly from the front end's). The node never waits for the
  // worker, so without a bound a worker that falls behind (a bag played fast, a busy machine)
  // holds every finished submap's pyramid until it catches up: 20 MB each on the Freiburg
  // hospital. An offline run waits at max_queued_submaps before this bound is reached, so its
  // results do not depend on it. -1: every queued submap keeps its pyramid.
  int max_queued_submap_pyramids = 8;
  // Lost for this many matched scans over which odometry moved the robot (standing or turning
  // on the spot it stays within its submap's reach), the front end starts over: the
  // active submaps are finished as they are and a new one begins at odometry's pose, tied to the
  // old ones by odometry's motion and the loop constraints the worker finds. Without it
  // a robot lost outside its active submap's reach stays lost for good: the ACES log with
  // odometry was lost at 575 s for the remaining 790 s. Without odometry, and with the single
  // map (loop closure off), it never starts over: the single map relocalizes on everything
  // seen. 0: never.
  int restart_after_lost_scans = 20;
  // A poor match (scored between tracking_lost_score and tracking_ok_score) still goes into the
  // active submap when odometry predicted the scan and the match lies within these of the
  // prediction: two independent measurements agree. Below tracking_ok_score no scan goes in
  // otherwise, yet in a hall the score sinks as the robot drives into what was seen only from
  // afar or between clutter (chairs, people), and a map no longer drawn loses the robot (the
  // ACES log at 505 s, the Freiburg hospital at scan 75). Only with loop closure: a submap's
  // error is bounded and the graph places it; on the single map such scans stay in for good
  // (ACES without loop closure: 0.041 -> 0.114 m median). 0: never.
  double odometry_confirms_distance = 0.05;  // m
  double odometry_confirms_angle = 0.05;     // rad

  std::vector<std::string> Validate() const;
};

}  // namespace mapping
}  // namespace hex_slam

#endif  // HEX_SLAM_MAPPING_LOOP_CLOSURE_LOOP_CLOSURE_OPTIONS_H_
