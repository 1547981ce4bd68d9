// `seedcal doe`: make and analyse designs of experiments (DESIGN.md, "Interface"; docs/doe.md).
//   seedcal doe design pb|ff|bbd|ccd|lhs --factor NAME=LOW:HIGH ... --out design.csv
//   seedcal doe analyze DATA.csv --response COL --model linear|interaction|quadratic [--factors a,b] [--json]
//   seedcal doe gp DATA.csv --response COL [--predict POINTS.csv] [--json]
// Library errors (doe::DoeError) are bad input: exit 2 with the file, column and value named.
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "doe/core/errors.hpp"
#include "doe/designs/box_behnken.hpp"
#include "doe/designs/central_composite.hpp"
#include "doe/designs/factorial.hpp"
#include "doe/designs/latin_hypercube.hpp"
#include "doe/designs/plackett_burman.hpp"
#include "doe/io/csv_table.hpp"
#include "doe/regression/anova.hpp"
#include "doe/regression/effects.hpp"
#include "doe/surrogate/acquisition.hpp"
#include "doe/surrogate/gaussian_process.hpp"
#include "store/atomic_file.hpp"
#include "store/errors.hpp"

namespace seedcal {
namespace {

using nlohmann::json;
namespace d = seedcal::doe;

// NaN / Inf (an F test with no residual degrees of freedom, say) become null in JSON.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const auto end = std::min(s.find(',', start), s.size());
    if (end > start) out.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

// ------------------------------------------------------------------------------------- design

struct DesignArgs {
  std::string kind;
  std::vector<std::string> factors;  // NAME=LOW:HIGH
  int num_factors = 0;
  int runs = 0;
  int center = -1;
  std::vector<std::string> generators;
  std::string ccd_type = "circumscribed";
  double alpha = 0.0;
  bool randomize = false;
  std::string out;
};

std::vector<d::Factor> parse_factors(const DesignArgs& a) {
  std::vector<d::Factor> f;
  for (const auto& s : a.factors) {
    const auto eq = s.find('='), colon = s.find(':', eq == std::string::npos ? 0 : eq);
    const std::string bad = "--factor " + s + ": must look like NAME=LOW:HIGH with LOW < HIGH";
    if (eq == std::string::npos || eq == 0 || colon == std::string::npos) throw InputError(bad);
    d::Factor x;
    x.name = s.substr(0, eq);
    try {
      std::size_t u = 0, v = 0;
      x.low = std::stod(s.substr(eq + 1, colon - eq - 1), &u);
      x.high = std::stod(s.substr(colon + 1), &v);
      if (u != colon - eq - 1 || v != s.size() - colon - 1) throw InputError(bad);
    } catch (const std::logic_error&) {
      throw InputError(bad);
    }
    if (!(x.low < x.high)) throw InputError(bad);
    f.push_back(x);
  }
  if (f.empty()) {
    if (a.num_factors < 1) throw InputError("doe design: give --factor NAME=LOW:HIGH (repeatable) or --num-factors N");
    const auto names = d::default_names(a.num_factors);
    for (const auto& n : names) f.push_back({n, -1.0, 1.0});
  }
  return f;
}

d::Design make(const DesignArgs& a, int k, std::uint64_t seed) {
  const int centre = std::max(a.center, 0);
  if (a.kind == "pb") {
    d::PlackettBurmanOptions o;
    o.runs = a.runs > 0 ? a.runs : 4 * (k / 4 + 1);  // the smallest multiple of 4 above k
    o.factors = k;
    o.center_points = centre;
    o.randomize = a.randomize;
    o.seed = seed;
    return d::plackett_burman(o);
  }
  if (a.kind == "ff") {
    d::Design x = a.generators.empty() ? d::full_factorial_2level(k) : d::fractional_factorial(k, a.generators);
    d::add_center_points(x, centre);
    if (a.randomize) d::randomize_run_order(x, seed);
    return x;
  }
  if (a.kind == "bbd") {
    d::BoxBehnkenOptions o;
    o.factors = k;
    o.center_points = a.center;
    o.randomize = a.randomize;
    o.seed = seed;
    return d::box_behnken(o);
  }
  if (a.kind == "ccd") {
    d::CentralCompositeOptions o;
    o.factors = k;
    o.center_points = a.center < 0 ? 5 : a.center;
    o.type = a.ccd_type == "face" ? d::CcdType::face_centered
             : a.ccd_type == "inscribed" ? d::CcdType::inscribed : d::CcdType::circumscribed;
    o.alpha = a.alpha;
    o.generators = a.generators;
    o.randomize = a.randomize;
    o.seed = seed;
    return d::central_composite(o);
  }
  d::LatinHypercubeOptions o;  // lhs
  o.runs = a.runs > 0 ? a.runs : 10 * k;
  o.factors = k;
  o.seed = seed;
  return d::latin_hypercube(o);
}

void run_design(const DesignArgs& a, const GlobalOptions& g) {
  const std::vector<d::Factor> f = parse_factors(a);
  d::Design x;
  try {
    x = make(a, static_cast<int>(f.size()), g.seed);
  } catch (const d::DoeError& e) {
    throw InputError(std::string("doe design ") + a.kind + ": " + e.what());
  }
  // Columns: run, std_order, the factors in natural units, then coded (NAME_coded), then dummies.
  std::vector<std::string> cols{"run", "std_order"};
  for (const auto& v : f) cols.push_back(v.name);
  for (const auto& v : f) cols.push_back(v.name + "_coded");
  for (int j = 0; j < x.n_dummy; ++j) cols.push_back(x.names[static_cast<std::size_t>(x.factors() + j)]);
  const Eigen::MatrixXd nat = d::to_natural(x.coded, f);
  const auto k = static_cast<Eigen::Index>(f.size());
  Eigen::MatrixXd m(x.runs(), 2 + 2 * k + x.n_dummy);
  for (int i = 0; i < x.runs(); ++i) {
    m(i, 0) = i + 1;
    m(i, 1) = x.std_order[static_cast<std::size_t>(i)];
  }
  m.middleCols(2, k) = nat.leftCols(k);
  m.middleCols(2 + k, k) = x.coded.leftCols(k);
  m.rightCols(x.n_dummy) = x.coded.rightCols(x.n_dummy);
  const std::string csv = d::format_csv(cols, m);
  if (a.out.empty()) std::cout << csv;
  else {
    write_file_atomic(a.out, csv);
    std::cout << a.kind << ": " << x.runs() << " runs, " << f.size() << " factors"
              << (x.n_dummy ? ", " + std::to_string(x.n_dummy) + " dummy columns" : std::string()) << " -> " << a.out << "\n";
  }
}

// ------------------------------------------------------------------------------------ analyze

struct DataArgs {
  std::string data;
  std::string response;
  std::string factors;   // comma-separated; empty: every column but the response and bookkeeping
  std::string model = "quadratic";
  bool json = false;
  std::string out;       // also write the JSON here
  // gp
  std::string predict;
  std::string kernel = "matern52";
  std::string mean = "constant";
  int next = 0;
  std::string acquisition = "ei";
  double target = 0.0;
};

// Columns `seedcal doe design` writes for bookkeeping, never factors by default.
bool bookkeeping(const std::string& c) {
  return c == "run" || c == "std_order" || (c.size() > 6 && c.compare(c.size() - 6, 6, "_coded") == 0);
}
bool dummy(const std::string& c) { return c.rfind("dummy", 0) == 0; }

struct Data {
  d::CsvTable table;
  std::vector<std::string> factors;
  std::vector<std::string> dummies;
  Eigen::MatrixXd X, D;
  Eigen::VectorXd y;
};

Data load(const DataArgs& a) {
  Data out;
  try {
    out.table = d::read_csv(a.data);
  } catch (const d::DoeError& e) {
    throw InputError(e.what());
  }
  const auto& t = out.table;
  if (t.find(a.response) < 0)
    throw InputError(a.data + ": --response = " + a.response + ": no such column (columns: " + t.column_list() + ")");
  if (!a.factors.empty()) {
    out.factors = split_list(a.factors);
    for (const auto& f : out.factors)
      if (t.find(f) < 0 || f == a.response)
        throw InputError(a.data + ": --factors: " + f + ": not a factor column (columns: " + t.column_list() + ")");
  } else {
    for (const auto& c : t.columns)
      if (c != a.response && !bookkeeping(c)) (dummy(c) ? out.dummies : out.factors).push_back(c);
  }
  if (out.factors.empty()) throw InputError(a.data + ": no factor columns besides the response " + a.response);
  const Eigen::Index n = t.values.rows();
  out.X.resize(n, static_cast<Eigen::Index>(out.factors.size()));
  for (std::size_t j = 0; j < out.factors.size(); ++j) out.X.col(static_cast<Eigen::Index>(j)) = t.values.col(t.find(out.factors[j]));
  out.D.resize(n, static_cast<Eigen::Index>(out.dummies.size()));
  for (std::size_t j = 0; j < out.dummies.size(); ++j) out.D.col(static_cast<Eigen::Index>(j)) = t.values.col(t.find(out.dummies[j]));
  out.y = t.values.col(t.find(a.response));
  return out;
}

void emit(const DataArgs& a, const json& j, const std::string& text) {
  if (!a.out.empty()) write_json_atomic(a.out, j);
  std::cout << (a.json ? j.dump(2) + "\n" : text);
}

void run_analyze(const DataArgs& a) {
  const Data data = load(a);
  d::RegressionAnalysis r;
  try {
    r = d::analyze_regression(data.X, data.y, d::model_terms(d::parse_model_kind(a.model), data.factors));
  } catch (const d::DoeError& e) {
    throw InputError(a.data + ": --model " + a.model + ": " + e.what());
  }
  json j;
  j["data"] = a.data;
  j["response"] = a.response;
  j["model"] = a.model;
  j["factors"] = data.factors;
  j["n"] = r.fit.n;
  j["coefficients"] = json::object();
  j["coefficient_table"] = json::array();
  for (std::size_t t = 0; t < r.terms.size(); ++t) {
    const auto i = static_cast<Eigen::Index>(t);
    j["coefficients"][r.terms[t].name] = num(r.fit.coefficients(i));
    j["coefficient_table"].push_back({{"term", r.terms[t].name}, {"estimate", num(r.fit.coefficients(i))},
                                      {"se", num(r.fit.standard_errors(i))}, {"t", num(r.fit.t(i))},
                                      {"p", num(r.fit.p(i))}, {"ss_adjusted", num(r.adjusted_ss(i))}});
  }
  j["anova"] = json::array();
  for (const auto& row : r.anova)
    j["anova"].push_back({{"source", row.source}, {"df", row.df}, {"ss", num(row.ss)}, {"ms", num(row.ms)},
                          {"f", num(row.f)}, {"p", num(row.p)}});
  j["r2"] = num(r.r2);
  j["adj_r2"] = num(r.adj_r2);
  j["pred_r2"] = num(r.pred_r2);
  j["press"] = num(r.press);
  j["adequate_precision"] = num(r.adequate_precision);
  std::string text = "response " + a.response + ", " + a.model + " model, " + std::to_string(r.fit.n) + " runs\n\n" +
                     d::format_regression(r);
  // Main effects of the two-level factors (against dummy columns when the CSV has them).
  std::vector<std::string> two;
  Eigen::MatrixXd T(data.X.rows(), 0);
  for (std::size_t f = 0; f < data.factors.size(); ++f)
    if (d::is_two_level(data.X.col(static_cast<Eigen::Index>(f)))) {
      two.push_back(data.factors[f]);
      T.conservativeResize(Eigen::NoChange, T.cols() + 1);
      T.col(T.cols() - 1) = data.X.col(static_cast<Eigen::Index>(f));
    }
  if (!two.empty()) {
    try {
      const auto e = d::main_effects(T, data.y, two, data.D);
      j["effects"] = json::array();
      j["effects_error"] = e.error_source;
      text += "\nMain effects (error: " + e.error_source + ", " + std::to_string(e.df_error) + " df), Pareto order\n";
      for (int idx : e.pareto) {
        const auto& x = e.effects[static_cast<std::size_t>(idx)];
        char line[256];
        std::snprintf(line, sizeof line, "  %-16s %12.6g   t %9.4g   p %9.4g\n", x.name.c_str(), x.effect, x.t, x.p);
        text += line;
      }
      for (const auto& x : e.effects)
        j["effects"].push_back({{"factor", x.name}, {"low", x.low}, {"high", x.high}, {"effect", num(x.effect)},
                                {"se", num(x.se)}, {"t", num(x.t)}, {"p", num(x.p)}, {"pareto_rank", x.pareto_rank}});
    } catch (const d::DoeError&) {
      // Too few runs for a main-effects fit: no effects block.
    }
  }
  emit(a, j, text);
}

// ----------------------------------------------------------------------------------------- gp

void run_gp(const DataArgs& a, const GlobalOptions& g) {
  const Data data = load(a);
  d::GpOptions o;
  o.kernel = a.kernel == "se" ? d::KernelKind::squared_exponential : d::KernelKind::matern52;
  o.mean = a.mean == "linear" ? d::MeanKind::linear : d::MeanKind::constant;
  o.seed = g.seed;
  std::optional<d::GaussianProcess> gp;
  try {
    gp = d::GaussianProcess::fit(data.X, data.y, o);
  } catch (const d::DoeError& e) {
    throw InputError(a.data + ": " + e.what());
  }
  const auto h = gp->hyperparameters();
  json j;
  j["data"] = a.data;
  j["response"] = a.response;
  j["factors"] = data.factors;
  j["n"] = gp->size();
  j["kernel"] = d::to_string(o.kernel);
  j["mean"] = d::to_string(o.mean);
  j["length_scales"] = json::object();
  for (std::size_t f = 0; f < data.factors.size(); ++f) j["length_scales"][data.factors[f]] = num(h.length_scales(static_cast<Eigen::Index>(f)));
  j["signal_variance"] = num(h.signal_variance);
  j["noise_variance"] = num(h.noise_variance);
  j["noise_sd"] = num(std::sqrt(h.noise_variance));
  j["log_likelihood"] = num(gp->log_marginal_likelihood());
  j["loo_rmse"] = num(gp->loo_rmse());
  char buf[512];
  std::snprintf(buf, sizeof buf, "Gaussian process (%s kernel, %s mean), %d points\n  noise sd %.6g   signal sd %.6g   LOO RMSE %.6g\n",
                d::to_string(o.kernel), d::to_string(o.mean), gp->size(), std::sqrt(h.noise_variance),
                std::sqrt(h.signal_variance), gp->loo_rmse());
  std::string text = buf;
  for (std::size_t f = 0; f < data.factors.size(); ++f)
    text += "  length scale " + data.factors[f] + " = " + std::to_string(h.length_scales(static_cast<Eigen::Index>(f))) + "\n";
  if (!a.predict.empty()) {
    d::CsvTable p;
    try {
      p = d::read_csv(a.predict);
    } catch (const d::DoeError& e) {
      throw InputError(e.what());
    }
    Eigen::MatrixXd P(p.values.rows(), static_cast<Eigen::Index>(data.factors.size()));
    for (std::size_t f = 0; f < data.factors.size(); ++f) {
      const int c = p.find(data.factors[f]);
      if (c < 0) throw InputError(a.predict + ": factor column " + data.factors[f] + ": missing (columns: " + p.column_list() + ")");
      P.col(static_cast<Eigen::Index>(f)) = p.values.col(c);
    }
    j["predictions"] = json::array();
    text += "\nPredictions\n";
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const auto q = gp->predict(P.row(i).transpose());
      json row;
      for (std::size_t f = 0; f < data.factors.size(); ++f) row[data.factors[f]] = P(i, static_cast<Eigen::Index>(f));
      row["mean"] = num(q.mean);
      row["sd"] = num(q.sd());
      j["predictions"].push_back(row);
      std::snprintf(buf, sizeof buf, "  %4ld  mean %12.6g  sd %10.4g\n", static_cast<long>(i + 1), q.mean, q.sd());
      text += buf;
    }
  }
  if (a.next > 0) {
    d::AcquisitionOptions q;
    try {
      q.rule = d::parse_acquisition_rule(a.acquisition);
    } catch (const d::DoeError& e) {
      throw InputError(std::string("--acquisition: ") + e.what());
    }
    q.target = a.target;
    q.lower = data.X.colwise().minCoeff().transpose();
    q.upper = data.X.colwise().maxCoeff().transpose();
    q.seed = g.seed;
    const Eigen::MatrixXd nx = d::select_batch(*gp, q, a.next);
    j["next_points"] = json::array();
    text += "\nNext points (" + a.acquisition + ", within the data's range)\n";
    for (Eigen::Index i = 0; i < nx.rows(); ++i) {
      json row;
      text += " ";
      for (std::size_t f = 0; f < data.factors.size(); ++f) {
        row[data.factors[f]] = nx(i, static_cast<Eigen::Index>(f));
        text += " " + data.factors[f] + " = " + std::to_string(nx(i, static_cast<Eigen::Index>(f)));
      }
      j["next_points"].push_back(row);
      text += "\n";
    }
  }
  emit(a, j, text);
}

void add_data_options(CLI::App* s, DataArgs& a) {
  s->add_option("data", a.data, "CSV: a header row of column names, then numbers")->required()->check(CLI::ExistingFile);
  s->add_option("--response", a.response, "response column")->required();
  s->add_option("--factors", a.factors,
                "factor columns, comma-separated (default: every column but the response, run, std_order, "
                "*_coded and dummy*)");
  s->add_flag("--json", a.json, "print JSON instead of tables");
  s->add_option("--out", a.out, "also write the JSON to this file");
}

}  // namespace

void add_doe_command(CLI::App& app, GlobalOptions& g) {
  CLI::App* sub = app.add_subcommand("doe", "designs of experiments: make designs, analyse responses, fit surrogates");
  sub->require_subcommand(1);

  auto da = std::make_shared<DesignArgs>();
  CLI::App* des = sub->add_subcommand("design", "write a design (natural and coded columns) as CSV");
  des->add_option("kind", da->kind, "pb (Plackett-Burman), ff (2^k or 2^(k-p)), bbd (Box-Behnken), ccd (central "
                                    "composite), lhs (maximin Latin hypercube)")
      ->required()->check(CLI::IsMember({"pb", "ff", "bbd", "ccd", "lhs"}));
  des->add_option("--factor", da->factors, "a factor and its range: NAME=LOW:HIGH (repeat, in order)");
  des->add_option("--num-factors", da->num_factors, "without --factor: this many factors x1.. coded -1..1")->check(CLI::Range(1, 30));
  des->add_option("--runs", da->runs, "pb: 8, 12, 16, 20 or 24 (default: smallest above the factors); lhs: runs (default 10 k)");
  des->add_option("--center", da->center, "centre runs (default: pb/ff 0, ccd 5, bbd the published 3 or 6)")->check(CLI::Range(0, 1000));
  des->add_option("--generators", da->generators, "ff/ccd: fraction generators, e.g. D=ABC,E=-AB")->delimiter(',');
  des->add_option("--ccd-type", da->ccd_type, "ccd: circumscribed (rotatable), face or inscribed")
      ->check(CLI::IsMember({"circumscribed", "face", "inscribed"}));
  des->add_option("--alpha", da->alpha, "ccd circumscribed: axial distance (default n_F^(1/4))")->check(CLI::PositiveNumber);
  des->add_flag("--randomize", da->randomize, "randomise the run order (with --seed)");
  des->add_option("--out", da->out, "CSV file (default: print)");
  add_common_options(*des, g);
  des->callback([da, &g] { run_design(*da, g); });

  auto aa = std::make_shared<DataArgs>();
  CLI::App* an = sub->add_subcommand("analyze", "least-squares fit, ANOVA, R2/adjusted/predicted R2, main effects");
  add_data_options(an, *aa);
  an->add_option("--model", aa->model, "linear, interaction or quadratic")
      ->check(CLI::IsMember({"linear", "interaction", "quadratic"}));
  add_common_options(*an, g);
  an->callback([aa] { run_analyze(*aa); });

  auto ga = std::make_shared<DataArgs>();
  CLI::App* gp = sub->add_subcommand("gp", "fit a Gaussian-process surrogate (ML hyperparameters, noise), predict, propose");
  add_data_options(gp, *ga);
  gp->add_option("--predict", ga->predict, "CSV of points (columns named as the factors) to predict at");
  gp->add_option("--kernel", ga->kernel, "matern52 or se")->check(CLI::IsMember({"matern52", "se"}));
  gp->add_option("--mean", ga->mean, "constant or linear")->check(CLI::IsMember({"constant", "linear"}));
  gp->add_option("--next", ga->next, "propose this many next points (a batch)")->check(CLI::Range(0, 100));
  gp->add_option("--acquisition", ga->acquisition, "ei (minimise), target, variance")->check(CLI::IsMember({"ei", "target", "variance"}));
  gp->add_option("--target", ga->target, "target response for --acquisition target");
  add_common_options(*gp, g);
  gp->callback([ga, &g] { run_gp(*ga, g); });
}

}  // namespace seedcal
