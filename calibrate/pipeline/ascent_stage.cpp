// Stage 2: path of steepest ascent (or descent) from the screening centre along the first-order
// model of the primary target (Box & Wilson 1951; Montgomery, DAE 8th ed., sec. 11.2), until the
// DEM responses bracket the target. When the first-order model already reaches the target inside
// the screening box, no run is needed: the surrogate box is the screening box. Otherwise the
// surrogate box is centred where the path crosses the target (linear interpolation between the
// bracketing points) with a half-width of `box_half_width` coded units, moved (not shrunk) to stay
// inside each parameter's hard limits.
// The path is projected onto the limits (bound-constrained steepest ascent): a factor that reaches
// its min or max stays there while the others go on along their components of the direction. The
// target counts as unreachable only when every factor that moves has stopped at a limit.
#include <cmath>
#include <cstdio>

#include "calibrate/pipeline/pipeline.hpp"
#include "doe/rsm/steepest_ascent.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

struct Coding {
  Eigen::VectorXd centre, half, lo_limit, hi_limit;  // per kept factor; limits in coded units
};

Coding coding(const StudyConfig& s, const PipelineState& st) {
  const auto n = static_cast<Eigen::Index>(st.kept.size());
  Coding c{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto& p = s.parameters[static_cast<std::size_t>(st.kept[static_cast<std::size_t>(k)])];
    c.centre(k) = 0.5 * (p.low + p.high);
    c.half(k) = 0.5 * (p.high - p.low);
    c.lo_limit(k) = (p.min - c.centre(k)) / c.half(k);
    c.hi_limit(k) = (p.max - c.centre(k)) / c.half(k);
  }
  return c;
}

}  // namespace

nlohmann::json run_ascent(StudyEvaluator& ev, PipelineState& st, StudyStore& store) {
  const StudyConfig& s = ev.study();
  const Coding c = coding(s, st);
  const auto n = static_cast<Eigen::Index>(st.kept.size());
  const int primary = primary_target(s);
  const double target = s.targets[static_cast<std::size_t>(primary)].value;
  const Eigen::VectorXd& b = st.first_order;
  const double reach = b.cwiseAbs().sum();
  nlohmann::json report = {{"target", s.targets[static_cast<std::size_t>(primary)].name},
                           {"target_value", target}, {"centre_response", st.screen_mean},
                           {"first_order", std::vector<double>(b.data(), b.data() + b.size())}};
  auto set_box = [&](const Eigen::VectorXd& centre_coded, double w) {
    st.box_lo.resize(n);
    st.box_hi.resize(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      double lo = centre_coded(k) - w, hi = centre_coded(k) + w;
      if (lo < c.lo_limit(k)) { hi = std::min(c.hi_limit(k), hi + (c.lo_limit(k) - lo)); lo = c.lo_limit(k); }
      if (hi > c.hi_limit(k)) { lo = std::max(c.lo_limit(k), lo - (hi - c.hi_limit(k))); hi = c.hi_limit(k); }
      st.box_lo(k) = c.centre(k) + c.half(k) * lo;
      st.box_hi(k) = c.centre(k) + c.half(k) * hi;
    }
  };
  if (std::fabs(target - st.screen_mean) <= reach || b.norm() == 0.0 || s.ascent.max_steps == 0) {
    set_box(Eigen::VectorXd::Zero(n), 1.0);
    report["skipped"] = b.norm() == 0.0 || s.ascent.max_steps == 0
                            ? "no first-order direction (or max_steps = 0): the screening box is used"
                            : "the first-order model reaches the target inside the screening box";
    report["points"] = nlohmann::json::array();
  } else {
    doe::SteepestAscentOptions o;
    o.descent = target < st.screen_mean;
    o.base_step = s.ascent.step;
    o.max_steps = s.ascent.max_steps;
    const Eigen::VectorXd dx = doe::steepest_step(b, o);
    report["direction"] = o.descent ? "descent" : "ascent";
    report["step_coded"] = std::vector<double>(dx.data(), dx.data() + dx.size());
    Eigen::VectorXd prev = Eigen::VectorXd::Zero(n), crossing = Eigen::VectorXd::Zero(n);
    double prev_y = st.screen_mean, best_gap = std::fabs(st.screen_mean - target);
    Eigen::VectorXd best = prev;
    std::string stop = "max steps";
    bool bracketed = false;
    report["points"] = nlohmann::json::array();
    for (int k = 1; k <= s.ascent.max_steps; ++k) {
      Eigen::VectorXd x = prev + dx;
      for (Eigen::Index j = 0; j < n; ++j) x(j) = std::clamp(x(j), c.lo_limit(j), c.hi_limit(j));
      if ((x - prev).cwiseAbs().maxCoeff() < 1e-12) { stop = "parameter limit"; break; }  // all pinned
      bool all_pinned_after = true;  // no factor can move on from x
      for (Eigen::Index j = 0; j < n; ++j)
        if (dx(j) != 0.0 && std::clamp(x(j) + dx(j), c.lo_limit(j), c.hi_limit(j)) != x(j)) all_pinned_after = false;
      const Eigen::VectorXd natural = c.centre + c.half.cwiseProduct(x);
      const auto records = ev.run(ev.plan("ascent", full_point(st, natural), s.screen.replicates));
      const double y = mean_responses(s, records, 1, s.screen.replicates)(0, primary);
      report["points"].push_back({{"coded", std::vector<double>(x.data(), x.data() + n)},
                                  {"natural", std::vector<double>(natural.data(), natural.data() + n)},
                                  {"response", std::isfinite(y) ? nlohmann::json(y) : nlohmann::json(nullptr)}});
      if (!std::isfinite(y)) { stop = "a path point failed"; break; }
      if (std::fabs(y - target) < best_gap) { best_gap = std::fabs(y - target); best = x; }
      if ((prev_y - target) * (y - target) <= 0.0) {
        const double f = (target - prev_y) / (y - prev_y);
        crossing = prev + f * (x - prev);
        bracketed = true;
        stop = "target bracketed";
        break;
      }
      prev = x;
      prev_y = y;
      if (all_pinned_after) { stop = "parameter limit"; break; }
    }
    report["stop_reason"] = stop;
    report["bracketed"] = bracketed;
    if (stop == "parameter limit" && !bracketed) {
      // The path ran into the parameters' min/max with the response still on the near side of
      // the target: no value inside the limits reaches it along the direction the screening
      // found. The study stops here as a bad study (exit 2); its runs stay in the store.
      const Eigen::VectorXd last = c.centre + c.half.cwiseProduct(prev);
      std::string at;
      for (std::size_t k = 0; k < st.kept.size(); ++k)
        at += (k ? ", " : "") + s.parameters[static_cast<std::size_t>(st.kept[k])].path + " = " +
              nlohmann::json(last(static_cast<Eigen::Index>(k))).dump();
      report["unreachable"] = true;
      store.set_stage(st.stage_prefix + "ascent", report);
      char msg[512];
      std::snprintf(msg, sizeof msg, "%s: target %s = %.6g cannot be reached inside the parameters' min/max: the "
                    "steepest %s path stopped at the limits (%s) with %.6g (screening centre %.6g); widen min/max of "
                    "the calibrated parameters, calibrate another one, or check the target",
                    s.file.c_str(), s.targets[static_cast<std::size_t>(primary)].metric.c_str(), target,
                    o.descent ? "descent" : "ascent", at.c_str(), prev_y, st.screen_mean);
      throw InputError(msg);
    }
    set_box(bracketed ? crossing : best, s.ascent.box_half_width);
  }
  nlohmann::json box = nlohmann::json::object();
  for (std::size_t k = 0; k < st.kept.size(); ++k)
    box[s.parameters[static_cast<std::size_t>(st.kept[k])].path] = {st.box_lo(static_cast<Eigen::Index>(k)),
                                                                    st.box_hi(static_cast<Eigen::Index>(k))};
  report["surrogate_box"] = box;
  store.set_stage(st.stage_prefix + "ascent", report);
  return report;
}

}  // namespace seedcal
