#include "doe/core/random.hpp"
#include "doe/surrogate/acquisition.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>
#include <nlopt.hpp>

#include "doe/core/errors.hpp"

namespace seedcal::doe {

const char* to_string(AcquisitionRule r) {
  switch (r) {
    case AcquisitionRule::expected_improvement: return "ei";
    case AcquisitionRule::target: return "target";
    case AcquisitionRule::max_variance: return "variance";
  }
  return "?";
}

AcquisitionRule parse_acquisition_rule(const std::string& s) {
  if (s == "ei") return AcquisitionRule::expected_improvement;
  if (s == "target") return AcquisitionRule::target;
  if (s == "variance") return AcquisitionRule::max_variance;
  throw DoeError("acquisition = " + s + ": must be one of ei, target, variance");
}

namespace {
double Phi(double z) { return gsl_cdf_ugaussian_P(z); }
double phi(double z) { return gsl_ran_ugaussian_pdf(z); }
}  // namespace

double expected_improvement(double mean, double sd, double best, bool minimize) {
  const double d = minimize ? best - mean : mean - best;
  if (!(sd > 0.0)) return std::max(d, 0.0);
  const double z = d / sd;
  return d * Phi(z) + sd * phi(z);
}

double target_improvement(double mean, double sd, double target, double best_distance) {
  const double a = target - best_distance, b = target + best_distance;
  if (!(sd > 0.0)) return std::max(best_distance - std::fabs(mean - target), 0.0);
  const double za = (a - mean) / sd, zt = (target - mean) / sd, zb = (b - mean) / sd;
  const double left = (mean - a) * (Phi(zt) - Phi(za)) - sd * (phi(zt) - phi(za));
  const double right = (b - mean) * (Phi(zb) - Phi(zt)) + sd * (phi(zb) - phi(zt));
  return std::max(left + right, 0.0);
}

bool AcquisitionOptions::IsValid(std::string* error) const {
  Problems p;
  p.require(lower.size() > 0 && lower.size() == upper.size(), "AcquisitionOptions.lower/upper (size)", lower.size(),
            "must be > 0 and equal to upper's size");
  if (lower.size() == upper.size())
    for (Eigen::Index j = 0; j < lower.size(); ++j)
      p.require(lower(j) < upper(j), "AcquisitionOptions.lower[" + std::to_string(j) + "]", lower(j),
                "must be below upper = " + std::to_string(upper(j)));
  p.require(candidates >= 1, "AcquisitionOptions.candidates", candidates, "must be >= 1");
  return p.report(error);
}

double incumbent(const GaussianProcess& gp, const AcquisitionOptions& o) {
  double best = o.rule == AcquisitionRule::expected_improvement && !o.minimize
                    ? -std::numeric_limits<double>::infinity()
                    : std::numeric_limits<double>::infinity();
  for (int i = 0; i < gp.size(); ++i) {
    const double m = gp.predict(gp.inputs().row(i).transpose()).mean;
    if (o.rule == AcquisitionRule::target) best = std::min(best, std::fabs(m - o.target));
    else best = o.minimize ? std::min(best, m) : std::max(best, m);
  }
  return best;
}

double acquisition_value(const GaussianProcess& gp, const Eigen::VectorXd& x, const AcquisitionOptions& o,
                         double inc) {
  const GpPrediction p = gp.predict(x);
  switch (o.rule) {
    case AcquisitionRule::expected_improvement: return expected_improvement(p.mean, p.sd(), inc, o.minimize);
    case AcquisitionRule::target: return target_improvement(p.mean, p.sd(), o.target, inc);
    case AcquisitionRule::max_variance: return p.variance;
  }
  return 0.0;
}

namespace {

struct Ctx {
  const GaussianProcess* gp;
  const AcquisitionOptions* o;
  double inc;
};

double negative_acquisition(const std::vector<double>& v, std::vector<double>&, void* data) {
  const auto* c = static_cast<const Ctx*>(data);
  const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  return -acquisition_value(*c->gp, x, *c->o, c->inc);
}

Eigen::VectorXd next_point(const GaussianProcess& gp, const AcquisitionOptions& o, std::mt19937_64& rng) {
  const Ctx ctx{&gp, &o, incumbent(gp, o)};
    const auto d = o.lower.size();
  Eigen::VectorXd best_x = 0.5 * (o.lower + o.upper);
  double best = -std::numeric_limits<double>::infinity();
  for (int c = 0; c < o.candidates; ++c) {
    Eigen::VectorXd x(d);
    for (Eigen::Index j = 0; j < d; ++j) x(j) = o.lower(j) + (o.upper(j) - o.lower(j)) * unit_uniform(rng);
    const double a = acquisition_value(gp, x, o, ctx.inc);
    if (a > best) { best = a; best_x = x; }
  }
  // Local polish of the best candidate (the acquisition is multimodal; the candidates find the basin).
  nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(d));
  opt.set_lower_bounds(std::vector<double>(o.lower.data(), o.lower.data() + d));
  opt.set_upper_bounds(std::vector<double>(o.upper.data(), o.upper.data() + d));
  opt.set_min_objective(negative_acquisition, const_cast<Ctx*>(&ctx));
  opt.set_xtol_rel(1e-6);
  opt.set_maxeval(200);
  std::vector<double> v(best_x.data(), best_x.data() + d);
  double f = 0.0;
  try {
    opt.optimize(v, f);
  } catch (const std::runtime_error&) {
  }
  std::vector<double> g;
  if (-negative_acquisition(v, g, const_cast<Ctx*>(&ctx)) > best)
    best_x = Eigen::Map<const Eigen::VectorXd>(v.data(), d);
  return best_x;
}

}  // namespace

Eigen::MatrixXd select_batch(const GaussianProcess& gp, const AcquisitionOptions& o, int batch) {
  validate_or_throw(o);
  if (o.lower.size() != gp.dims()) throw DoeError("select_batch: bounds and surrogate dimensions differ");
  if (batch < 1) throw DoeError("select_batch: batch = " + std::to_string(batch) + ": must be >= 1");
  std::mt19937_64 rng(o.seed);
  Eigen::MatrixXd out(batch, gp.dims());
  GaussianProcess g = gp;
  for (int b = 0; b < batch; ++b) {
    const Eigen::VectorXd x = next_point(g, o, rng);
    out.row(b) = x.transpose();
    if (b + 1 < batch) g = g.with_observation(x, g.predict(x).mean);  // kriging believer
  }
  return out;
}

}  // namespace seedcal::doe
