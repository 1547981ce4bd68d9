#pragma once
// Trajectories of a calibration's runs (`seedcal calibrate STUDY --trajectory[=STAGES]`): the
// scene's trajectory.h5 and trajectory.xdmf (calibrate/output/trajectory_h5.hpp, drawn by
// scripts/paraview_open.py) of
//   verify   the first replicate of every verification test under every model, beside that run's
//            CSV and picture in OUT/scenes/MODEL/TEST/
//   confirm  the first replicate of every target at every confirmation round, in
//            OUT/trajectories/confirm/round_NN/TARGET/ (rounds numbered from 01 in plan order)
// Recording changes no result: the frame observer reads the simulation and never steers it
// (solver/sim/simulation.hpp). A run answered from the store (a resumed study) is not run again,
// so it records nothing. The setting is not part of the study, so not of its fingerprint: a study
// may be resumed with or without it.
#include <string>

namespace seedcal {

struct StudyTrajectories {
  bool verify = false;
  bool confirm = false;
  double interval_s = 0.01;  // simulated time between frames, as [output] trajectory_interval_s

  bool any() const { return verify || confirm; }
  // Whether a run of `stage` with a scene folder records its trajectory.
  bool records(const std::string& stage) const {
    return (stage == "verify" && verify) || (stage == "confirm" && confirm);
  }
  // False, with a message naming the setting, the value and the allowed range, when invalid.
  bool IsValid(std::string* error) const;
};

// From --trajectory's value: "verify" (also the empty value, the flag alone), "confirm" or "all";
// false with a message naming the value otherwise. `out` keeps its interval.
bool parse_study_trajectories(const std::string& stages, StudyTrajectories* out, std::string* error);

// A name made safe as one path component: every character but a letter or a digit becomes '_'
// (an empty name becomes "test").
std::string path_slug(const std::string& name);

}  // namespace seedcal
