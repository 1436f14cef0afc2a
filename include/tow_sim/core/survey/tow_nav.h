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
// covariance their spread plus model_sigma^2 per axis; its depth is the latest measured one while it is
// fresh (at most 10 s old), with depth_sigma.
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

#include "tow_sim/core/environment/seabed.h"
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
  double start_after = 30.0;        // [s] of ship fixes before the runs start (the track's velocity settles)
  double gnss_smoothing = 5.0;      // [s] the ship track's smoothing time (GnssTrack)
  double ship_interval = 5.0;       // [s] the runs' ship track: a smoothed fix this often (a rough track is stiff)
  double analysis_interval = 20.0;  // [s] (the cable answers a change of current over minutes: see survey.md)
  double current_sigma = 0.3;       // [m/s] the current's prior spread per horizontal axis (mean zero)
  double current_walk = 0.0015;     // [m/s/sqrt(s)] its random walk
  double drag_sigma = 0.2;          // [-] the prior spread of ln(drag scale) (mean zero: the configured drag)
  double drag_walk = 0.002;         // [1/sqrt(s)]
  double offset_blend = 30.0;       // [s] the estimate takes up an offset's change over this time (no jumps)
  double offset_walk = 0.5;         // [m/sqrt(s)] the USBL offset's random walk (zero at first; walks once a fix came)
  double depth_sigma = 0.5;         // [m] the depth's error against the model, sensor and model together
  double tension_sigma = 0.05;      // [-] the tension's, relative
  double heading_sigma = 0.03;      // [rad] the fish heading's (its 20 s mean: the model's error, not the AHRS's)
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
  double heading = 0.0;  // [rad] the ship's heading they are along (the measured one while fresh, else the track's)
  Eigen::Vector2d current = Eigen::Vector2d::Zero();  // [m/s] the members' mean
  double drag_scale = 1.0;                            // [-] exp of the mean ln k
  // Refused so far: rows (no time, or earlier than the last), ship fixes (not after the previous fix), USBL fixes
  // (outside the gate), depths (below the configured seabed under the estimate by more than 3 depth_sigma).
  long rows_rejected = 0, fixes_rejected = 0, usbl_rejected = 0, depths_rejected = 0;
};

class TowNav
{
public:
  // Validates both (std::invalid_argument naming the key).
  TowNav(const SimulationConfig& config, const TowNavParams& params);
  ~TowNav();
  TowNav(const TowNav&) = delete;
  TowNav& operator=(const TowNav&) = delete;

  // One row of measurements, in time order (a row earlier than the last, or with a non-finite time, is counted
  // in rows_rejected and changes nothing; a ship fix at the previous fix's time is counted in fixes_rejected).
  // Returns the estimate at the row's time.
  TowNavEstimate update(const SurveyMeasurement& row);
  // The baselines at the last row (nullopt until a ship fix, a cable out and a depth have come), on the smoothed
  // ship track.
  std::optional<LaybackFixes> baselines() const;
  bool started() const { return !members_.empty(); }

private:
  // One member: its run, its parameters (c_x, c_y, ln k, b_x, b_y) and, since the last analysis, the time
  // integrals of what it predicts (to compare with the measurements' means over the same time).
  struct Member
  {
    std::unique_ptr<TowRun> run;
    Eigen::Matrix<double, 5, 1> x = Eigen::Matrix<double, 5, 1>::Zero();
    double built_ln_k = 0.0;                          // the ln k its run was built with
    TowSnapshot last;                                 // at the last advance
    Eigen::Vector2d shown = Eigen::Vector2d::Zero();  // the offset in the estimate: follows x[3], x[4] smoothly
    double duration = 0.0, depth = 0.0, tension = 0.0, heading_cos = 0.0, heading_sin = 0.0;  // integrals
  };
  // A USBL fix and, once the runs have passed its instant, each member's fish there.
  struct PendingFix
  {
    SurveyMeasurement fix;
    Eigen::Matrix3Xd members;
    bool placed = false;
  };
  struct Observations;
  void takeShip(const SurveyMeasurement& row);
  void holdMeasurements(SurveyMeasurement row);
  bool belowSeabed(double depth) const;
  void startMembers(double t);
  void advanceMembers(double t);
  void integrate(Member& m, const TowSnapshot& before);
  void placeFixes(double t, const std::vector<TowSnapshot>& before);
  void analyse(double t);
  void addWindowMeans(double t, Observations& obs);
  void addUsbl(const PendingFix& pending, Observations& obs);
  void ensembleUpdate(const Observations& obs);
  void applyParameters();
  void rebuild(Member& m);
  void blendOffsets(double t);
  // The ship's pose at t from the GNSS track's last estimate: its reference point, heading and the tow point.
  void shipAt(double t, Eigen::Vector3d& p_W, double& yaw, Eigen::Vector3d& tow_W) const;
  TowNavEstimate estimateAt(double t) const;

  SimulationConfig config_;
  TowNavParams params_;
  double max_ln_k_ = 1.5;  // the largest drag scale the configuration's ranges allow (ln)
  std::shared_ptr<ShipHistory> ship_;
  GnssTrack gnss_;
  ShipEstimate ship_now_;  // the GNSS track's latest
  LaybackRules rules_;
  std::mt19937_64 random_;
  std::vector<Member> members_;
  double t_ = -1e300, first_fix_ = NAN, last_fix_ = NAN, heading_ = NAN;
  double next_analysis_ = 0.0, last_analysis_ = 0.0, last_knot_ = -1e300, offsets_at_ = 0.0;
  double cable_out_ = NAN, depth_ = NAN;        // the latest (the baselines'; the depth also the estimate's z)
  double depth_t_ = NAN;                        // [s] the latest depth's row time
  static constexpr double kFreshDepth = 10.0;   // [s] a depth this old is still the estimate's z
  static constexpr double kFreshHeading = 5.0;  // [s] a heading this old is still the layback's direction
  double heading_t_ = NAN;                      // [s] the latest heading's row time
  std::vector<SurveyMeasurement> window_;       // rows with a depth, tension or fish heading not yet analysed
  std::vector<PendingFix> fixes_;               // USBL fixes not yet analysed
  long rows_rejected_ = 0, fixes_rejected_ = 0, usbl_rejected_ = 0, depths_rejected_ = 0;
  std::unique_ptr<Seabed> seabed_;  // the configuration's, if it has one (depths below it are refused)
  bool usbl_seen_ = false;          // a USBL fix has passed the gate: the offsets walk from then on
};

}  // namespace tow_sim
