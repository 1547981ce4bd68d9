#include "calibrate/pipeline/scene_check.hpp"

#include <set>
#include <string>
#include <vector>

#include "calibrate/pipeline/evaluation.hpp"
#include "calibrate/scenes/scene_file.hpp"
#include "store/errors.hpp"

namespace seedcal {

std::vector<std::string> check_study_scenes(const StudyConfig& s) {
  // The parameters all at their nominal values, all at their lower limits, all at their upper
  // limits: each scene key's range is checked on its own, so this covers every value the
  // screening, the ascent and the surrogate may set.
  struct Setting {
    const char* label;
    double StudyParameter::*value;
  };
  const Setting settings[] = {{"nominal", &StudyParameter::nominal},
                              {"lower limits (min)", &StudyParameter::min},
                              {"upper limits (max)", &StudyParameter::max}};
  std::vector<std::string> problems, warnings;
  std::set<std::string> seen;
  for (const StudyModel& model : s.models) {
    for (int i = 0; i < s.scene_count(); ++i) {
      const StudyTarget& t = s.scene_of(i);
      for (const Setting& at : settings) {
        nlohmann::json inputs = nlohmann::json::object();
        for (const StudyParameter& p : s.parameters) inputs[p.path] = p.*at.value;
        try {
          for (const std::string& w : check_scene(load_scene_file(t.scene, scene_overrides(model, t, inputs))))
            if (seen.insert(w).second)
              warnings.push_back(s.file + ": test \"" + t.name + "\" under model \"" + model.name + "\": " + w);
        } catch (const InputError& e) {
          const std::string where = s.file + ": " + (i < static_cast<int>(s.targets.size()) ? "target" : "verification test") +
                                    " \"" + t.name + "\" under model \"" + model.name + "\", parameters at their " +
                                    at.label + ": ";
          for (const std::string& m : e.problems()) problems.push_back(where + m);
          break;  // one report per test and model
        } catch (const std::exception& e) {
          problems.push_back(s.file + ": scene " + t.scene + " under model \"" + model.name + "\": " + e.what());
          break;
        }
      }
    }
  }
  if (!problems.empty()) throw InputError(problems);
  return warnings;
}

}  // namespace seedcal
