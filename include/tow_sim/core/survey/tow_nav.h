// tow_nav: where the towfish is, from the cable model and a survey's measurements (docs/survey.md).
//
// An ensemble Kalman filter over what the model does not know, each member a whole tow run. Member i holds
// the current (c_x, c_y) [m/s, world], the log of a scale on the cable's drag coefficients (ln k) and a
// horizontal offset b [m] of the fish from where its model puts it; its TowRun follows the ship from the GNSS
// track. Between analyses the members run on, their parameters a random walk. At each analysis (every
// analysis_interval) the mean fish depth, tow tension and fish heading since the last one and every USBL fix
// are compared with each member's prediction, and the parameters move by the ensemble's gain
// (perturbed observations); the offsets move only for USBL fixes. The members' runs are not moved: their
// cables follow their new currents and drags by their own dynamics, so the estimate never jumps, and each
// member's shape stays a cable's. The estimate is the members' mean fish position plus offset, its
// covariance their spread plus model_sigma^2 per axis.
//
// Why an ensemble of runs: the fish's position is a strongly nonlinear, lagged function of the current and the
// drag (a turn is where the rules fail and the cable's memory matters), the model is cheap (a 500 m cable of 25
// segments runs thousands of times faster than real time), and a run cannot be linearised about the turn's
// transient in closed form. Cost: `members` runs.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "tow_sim/core/param_table.h"
#include "tow_sim/core/run/gnss_track.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/core/survey/layback_rules.h"
#include "tow_sim/core/survey/survey_measurement.h"

namespace tow_sim
{
struct TowNavParams
{
  int members = 16;                 // [-] tow runs in the ensemble
  int seed = 1;                     // the ensemble's random draws
  double start_after = 10.0;        // [s] of ship fixes before the runs start (the ship's velocity settles)
  double gnss_smoothing = 5.0;      // [s] the ship track's smoothing time (GnssTrack)
  double ship_interval = 5.0;       // [s] the runs' ship track: a smoothed fix this often (a rough track is stiff)
  double analysis_interval = 20.0;  // [s] (the cable answers a change of current over minutes: see survey.md)
  double current_sigma = 0.3;       // [m/s] the current's prior spread per horizontal axis (mean zero)
  double current_walk = 0.003;      // [m/s/sqrt(s)] its random walk
  double drag_sigma = 0.2;          // [-] the prior spread of ln(drag scale) (mean zero: the configured drag)
  double drag_walk = 0.002;         // [1/sqrt(s)]
  double offset_blend = 30.0;       // [s] the estimate takes up an offset's change over this time (no jumps)
  double offset_walk = 0.5;         // [m/sqrt(s)] the USBL offset's random walk (zero at first; walks once a fix came)
  double depth_sigma = 0.5;         // [m] the depth's error against the model, sensor and model together
  double tension_sigma = 0.05;      // [-] the tension's, relative
  double heading_sigma = 0.05;      // [rad] the fish heading's
  double usbl_sigma = 1.0;          // [m] a USBL fix's, per axis, plus usbl_range_sigma x slant range
  double usbl_range_sigma = 0.01;   // [-]
  double usbl_latency = 1.0;        // [s] a fix is of the fish this long before its row
  double usbl_gate = 5.0;           // [-] a fix further than this many sigma from the ensemble is rejected
  double model_sigma = 1.0;         // [m] added to the ensemble's spread per axis
  double catenary_factor = 0.9;     // [-] the catenary-factor baseline's k
  double winch_time = 5.0;          // [s] the members' winches follow the cable counter with this time constant
  Eigen::Vector3d tow_point_S = Eigen::Vector3d(-20.0, 0.0, 0.0);  // [m] ship frame: the configuration's tow_point
};
const ParamTable<TowNavParams>& towNavParams();
void validate(const TowNavParams& params, const std::string& prefix);

struct TowNavEstimate
{
  double t = 0.0;
  bool valid = false;                                    // false until the runs have started
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();         // [m] the fish's CG, world ENU
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // [m^2]
  double layback = 0.0;                                  // [m] behind the tow point along the ship's heading
  double cross_track = 0.0;                              // [m] off the tow point's line, positive to port
  Eigen::Vector2d current = Eigen::Vector2d::Zero();     // [m/s] the members' mean
  double drag_scale = 1.0;                               // [-] exp of the mean ln k
  long usbl_rejected = 0, rows_rejected = 0;             // measurements refused so far
};

class TowNav
{
public:
  // Validates both (std::invalid_argument naming the key).
  TowNav(const SimulationConfig& config, const TowNavParams& params);
  ~TowNav();

  // One row of measurements, in time order (a row earlier than the last, or with a non-finite time, is counted
  // in rows_rejected and changes nothing). Returns the estimate at the row's time.
  TowNavEstimate update(const SurveyMeasurement& row);
  // The baselines at the last row (nullopt until a ship fix, a cable out and a depth have come).
  std::optional<LaybackFixes> baselines() const;
  bool started() const { return !members_.empty(); }

private:
  struct Member;
  struct Observations;
  void takeShip(const SurveyMeasurement& row);
  void holdMeasurements(const SurveyMeasurement& row);
  void startMembers(double t);
  void advanceMembers(double t);
  void analyse(double t);
  void addUsbl(const SurveyMeasurement& fix, Observations& obs);
  void ensembleUpdate(const Observations& obs);
  void rebuild(Member& m);
  void blendOffsets(double t);
  TowNavEstimate estimateAt(double t) const;

  SimulationConfig config_;
  TowNavParams params_;
  std::shared_ptr<ShipHistory> ship_;
  GnssTrack gnss_;
  LaybackRules rules_;
  std::mt19937_64 random_;
  std::vector<Member> members_;
  double t_ = -1e300, first_fix_ = NAN, heading_ = NAN, next_analysis_ = 0.0, last_analysis_ = 0.0, last_knot_ = -1e300,
         offsets_at_ = 0.0;
  double cable_out_ = NAN, depth_ = NAN;  // the latest (the baselines')
  // Since the last analysis: the sums of the depths, tensions and the fish heading's cosines and sines, and how many.
  double depth_sum_ = 0.0, tension_sum_ = 0.0, heading_cos_ = 0.0, heading_sin_ = 0.0;
  int depth_count_ = 0, tension_count_ = 0, heading_count_ = 0;
  std::vector<SurveyMeasurement> usbl_;  // fixes since the last analysis
  long usbl_rejected_ = 0, rows_rejected_ = 0;
  bool usbl_seen_ = false;
};

}  // namespace tow_sim
