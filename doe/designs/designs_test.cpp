// Designs: orthogonality and balance of every two-level design, the published Plackett-Burman
// generator rows, Box-Behnken and central composite run counts and axial distances, Latin
// hypercube stratification and maximin improvement. Two-level checks are exact: the entries are
// +-1 and sums of a few dozen of them are exact in double precision.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "doe/core/errors.hpp"
#include "doe/designs/box_behnken.hpp"
#include "doe/designs/central_composite.hpp"
#include "doe/designs/factorial.hpp"
#include "doe/designs/latin_hypercube.hpp"
#include "doe/designs/plackett_burman.hpp"
#include "doe/regression/model_terms.hpp"

namespace seedcal::doe {
namespace {

// Every column sums to zero (balance) and X'X = N I (orthogonality).
void expect_orthogonal_and_balanced(const Eigen::MatrixXd& c, const std::string& what) {
  const Eigen::Index n = c.rows();
  EXPECT_TRUE((c.array().abs() == 1.0).all()) << what;
  EXPECT_TRUE(c.colwise().sum().isZero(0.0)) << what << ": columns unbalanced";
  const Eigen::MatrixXd g = c.transpose() * c;
  EXPECT_TRUE(g.isApprox(Eigen::MatrixXd::Identity(c.cols(), c.cols()) * static_cast<double>(n), 0.0) ||
              (g - Eigen::MatrixXd::Identity(c.cols(), c.cols()) * static_cast<double>(n)).isZero(0.0))
      << what << ": columns not orthogonal\n" << g;
}

TEST(PlackettBurman, PublishedGeneratorRows) {
  // Plackett & Burman (1946); Montgomery DAE Table 8.23; NIST/SEMATECH e-Handbook 5.3.3.5.
  auto str = [](const std::vector<int>& g) {
    std::string s;
    for (int v : g) s += v > 0 ? '+' : '-';
    return s;
  };
  EXPECT_EQ(str(plackett_burman_generator(12)), "++-+++---+-");
  EXPECT_EQ(str(plackett_burman_generator(20)), "++--++++-+-+----++-");
  EXPECT_EQ(str(plackett_burman_generator(24)), "+++++-+-++--++--+-+----");
}

TEST(PlackettBurman, EverySizeIsOrthogonalBalancedWithLastRowAllMinus) {
  for (int runs : {8, 12, 16, 20, 24}) {
    PlackettBurmanOptions o;
    o.runs = runs;
    o.factors = runs - 1;
    const Design d = plackett_burman(o);
    ASSERT_EQ(d.runs(), runs);
    ASSERT_EQ(d.columns(), runs - 1);
    expect_orthogonal_and_balanced(d.coded, "PB" + std::to_string(runs));
    if (runs % 8 != 0 || runs == 24) {
      // Cyclic sizes: row 2 is row 1 shifted right by one, the last row all minus.
      EXPECT_TRUE((d.coded.row(runs - 1).array() == -1.0).all());
      for (int j = 1; j < runs - 1; ++j) EXPECT_EQ(d.coded(1, j), d.coded(0, j - 1));
    }
  }
}

TEST(PlackettBurman, DummyColumnsCenterPointsAndSeededRandomOrder) {
  PlackettBurmanOptions o;
  o.runs = 12;
  o.factors = 7;
  o.center_points = 3;
  const Design d = plackett_burman(o);
  EXPECT_EQ(d.n_dummy, 4);
  EXPECT_EQ(d.factors(), 7);
  EXPECT_EQ(d.names[7], "dummy1");
  EXPECT_EQ(d.runs(), 15);
  EXPECT_TRUE(d.coded.bottomRows(3).isZero(0.0));
  o.randomize = true;
  o.seed = 42;
  const Design r1 = plackett_burman(o), r2 = plackett_burman(o);
  EXPECT_EQ(r1.std_order, r2.std_order);  // same seed, same order
  o.seed = 43;
  EXPECT_NE(plackett_burman(o).std_order, r1.std_order);
  std::set<int> s(r1.std_order.begin(), r1.std_order.end());
  EXPECT_EQ(s.size(), 15u);  // a permutation
  for (int i = 0; i < r1.runs(); ++i)
    EXPECT_TRUE(r1.coded.row(i).isApprox(d.coded.row(r1.std_order[static_cast<std::size_t>(i)] - 1)) ||
                r1.coded.row(i).isZero(0.0));
}

TEST(PlackettBurman, InvalidOptionsNameOptionValueAndConstraint) {
  PlackettBurmanOptions o;
  o.runs = 10;
  o.factors = 12;
  std::string e;
  EXPECT_FALSE(o.IsValid(&e));
  EXPECT_NE(e.find("PlackettBurmanOptions.runs = 10: must be one of 8, 12, 16, 20, 24"), std::string::npos) << e;
  EXPECT_NE(e.find("PlackettBurmanOptions.factors = 12"), std::string::npos) << e;
}

TEST(Factorial, FullAndFractionalAreOrthogonalAndFollowTheirGenerators) {
  for (int k = 1; k <= 6; ++k) expect_orthogonal_and_balanced(full_factorial_2level(k).coded, "2^" + std::to_string(k));
  const Design f = fractional_factorial(5, {"D=AB", "E=-AC"});  // 2^(5-2), resolution III
  EXPECT_EQ(f.runs(), 8);
  expect_orthogonal_and_balanced(f.coded, "2^(5-2)");
  EXPECT_TRUE(f.coded.col(3).isApprox(interaction_column(f.coded, {0, 1})));
  EXPECT_TRUE(f.coded.col(4).isApprox(-interaction_column(f.coded, {0, 2})));
  // Standard (Yates) order: (1), a, b, ab, ...
  const Design g = full_factorial_2level(2);
  EXPECT_EQ(g.coded(0, 0), -1.0);
  EXPECT_EQ(g.coded(1, 0), 1.0);
  EXPECT_EQ(g.coded(1, 1), -1.0);
  EXPECT_THROW(fractional_factorial(4, {"D=AE"}), DoeError);
  EXPECT_THROW(fractional_factorial(4, {"C=AB"}), DoeError);
  const Design t = full_factorial_3level(3);
  EXPECT_EQ(t.runs(), 27);
  EXPECT_TRUE(t.coded.colwise().sum().isZero(0.0));
}

TEST(BoxBehnken, RunCountsAndFullQuadraticRank) {
  // Box & Behnken (1960); NIST/SEMATECH e-Handbook 5.3.3.6.2: 15, 27, 46, 54, 62 runs with centres.
  const int expected[] = {0, 0, 0, 15, 27, 46, 54, 62};
  for (int k = 3; k <= 7; ++k) {
    BoxBehnkenOptions o;
    o.factors = k;
    const Design d = box_behnken(o);
    EXPECT_EQ(d.runs(), expected[k]) << k;
    // Three levels only, every factor balanced, and the full quadratic model estimable.
    EXPECT_TRUE((d.coded.array() == 0.0 || d.coded.array().abs() == 1.0).all());
    EXPECT_TRUE(d.coded.colwise().sum().isZero(0.0));
    const Eigen::MatrixXd M = model_matrix(model_terms(ModelKind::quadratic, default_names(k)), d.coded);
    EXPECT_EQ(Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(M).rank(), M.cols()) << k;
    // No run at a corner: at most 2 (k <= 5) or 3 (k >= 6) factors away from 0.
    for (int i = 0; i < d.runs(); ++i) EXPECT_LE((d.coded.row(i).array() != 0.0).count(), k <= 5 ? 2 : 3);
  }
}

TEST(CentralComposite, RunCountsAndAxialDistances) {
  // Rotatable alpha = n_F^(1/4): 1.414, 1.682, 2.000 for k = 2, 3, 4 (Montgomery DAE sec. 11.4.2).
  const double alpha[] = {0, 0, std::sqrt(2.0), std::pow(8.0, 0.25), 2.0};
  for (int k = 2; k <= 4; ++k) {
    CentralCompositeOptions o;
    o.factors = k;
    o.center_points = 5;
    const Design d = central_composite(o);
    EXPECT_EQ(d.runs(), (1 << k) + 2 * k + 5);
    EXPECT_NEAR(d.coded.maxCoeff(), alpha[k], 1e-15);  // one rounding of pow
    // Rotatability: the moments [iiii] = 3 [iijj] (Box & Hunter 1957), here sum x_i^4 = 3 sum x_i^2 x_j^2.
    const double s4 = d.coded.col(0).array().pow(4).sum();
    const double s22 = (d.coded.col(0).array().square() * d.coded.col(1).array().square()).sum();
    EXPECT_NEAR(s4, 3.0 * s22, 1e-12 * s4);
    o.type = CcdType::face_centered;
    EXPECT_EQ(central_composite(o).coded.cwiseAbs().maxCoeff(), 1.0);
    o.type = CcdType::inscribed;
    const Design in = central_composite(o);
    EXPECT_NEAR(in.coded.cwiseAbs().maxCoeff(), 1.0, 1e-15);
    EXPECT_NEAR(in.coded(0, 0), -1.0 / alpha[k], 1e-15);
  }
  CentralCompositeOptions bad;
  bad.type = CcdType::face_centered;
  bad.alpha = 2.0;
  std::string e;
  EXPECT_FALSE(bad.IsValid(&e));
  EXPECT_NE(e.find("CentralCompositeOptions.alpha = 2"), std::string::npos) << e;
}

TEST(LatinHypercube, OnePointPerStratumAndMaximinBeatsARandomDraw) {
  LatinHypercubeOptions o;
  o.runs = 12;
  o.factors = 3;
  const Design d = latin_hypercube(o);
  for (int j = 0; j < 3; ++j) {
    std::set<int> strata;
    for (int i = 0; i < 12; ++i) strata.insert(static_cast<int>(std::floor((d.coded(i, j) + 1.0) / 2.0 * 12.0)));
    EXPECT_EQ(strata.size(), 12u);
  }
  LatinHypercubeOptions plain = o;
  plain.candidates = 1;
  plain.swap_iterations = 0;
  EXPECT_GT(min_pairwise_distance(d.coded), min_pairwise_distance(latin_hypercube(plain).coded));
  EXPECT_TRUE(latin_hypercube(o).coded.isApprox(d.coded));  // deterministic for a seed
}

TEST(Design, CodedNaturalRoundTrip) {
  const std::vector<Factor> f{{"time", 80, 90}, {"temp", 170, 180}};
  Eigen::MatrixXd c(2, 2);
  c << -1, 1, 1.414, 0;
  const Eigen::MatrixXd n = to_natural(c, f);
  EXPECT_DOUBLE_EQ(n(0, 0), 80.0);
  EXPECT_DOUBLE_EQ(n(0, 1), 180.0);
  EXPECT_NEAR(n(1, 0), 92.07, 1e-12);
  EXPECT_TRUE(to_coded(n, f).isApprox(c, 1e-14));
}

}  // namespace
}  // namespace seedcal::doe
