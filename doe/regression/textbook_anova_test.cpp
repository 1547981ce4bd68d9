// Regression and ANOVA against published textbook examples.
//   Montgomery, D. C., Design and Analysis of Experiments, 8th ed., Wiley (2013):
//     Example 6.1  (2^2, n = 3 replicates, chemical process yield);
//     Example 6.2  (2^4 single replicate, filtration rate; Table 6.10 data, Table 6.11 effects);
//     Example 11.1 (first-order model, 2^2 + 5 centre runs, before steepest ascent; Table 11.2);
//     Example 11.2 (rotatable CCD, time and temperature, yield; the Design-Expert ANOVA is
//                   reprinted by ReliaSoft, https://reliawiki.com, "Central Composite Response
//                   Surface Method", which validates DOE++ against it).
// "To all printed digits" means |computed - printed| <= half a unit of the last printed digit.
#include <gtest/gtest.h>

#include <cmath>

#include "doe/core/errors.hpp"
#include "doe/designs/design.hpp"
#include "doe/regression/anova.hpp"
#include "doe/regression/effects.hpp"

namespace seedcal::doe {
namespace {

// Half a unit of the last printed decimal, plus 1e-12 for the binary representation of the
// printed value itself.
void expect_printed(double got, double printed, int decimals, const std::string& what) {
  EXPECT_LE(std::fabs(got - printed), 0.5 * std::pow(10.0, -decimals) + 1e-12)
      << what << ": computed " << got << ", printed " << printed;
}

TEST(Montgomery, Example6_1TwoSquaredWithReplicates) {
  // A concentration, B catalyst; three replicates at (1), a, b, ab.
  const double y[12] = {28, 25, 27, 36, 32, 32, 18, 19, 23, 31, 30, 29};
  Eigen::MatrixXd X(12, 2);
  for (int i = 0; i < 12; ++i) {
    const int cell = i / 3;
    X(i, 0) = (cell & 1) ? 1 : -1;
    X(i, 1) = (cell & 2) ? 1 : -1;
  }
  const Eigen::VectorXd yv = Eigen::Map<const Eigen::VectorXd>(y, 12);
  const auto a = analyze_regression(X, yv, model_terms(ModelKind::interaction, {"A", "B"}));
  // Book (sec. 6.2): SS_A = 208.33, SS_B = 75.00, SS_AB = 8.33, SS_T = 323.00, SS_E = 31.33 (the
  // hand computation prints 31.34 from rounded terms); exact values are 625/3, 75, 25/3, 323, 94/3.
  expect_printed(a.row("A").ss, 208.33, 2, "SS A");
  expect_printed(a.row("B").ss, 75.00, 2, "SS B");
  expect_printed(a.row("A:B").ss, 8.33, 2, "SS AB");
  expect_printed(a.row("total").ss, 323.00, 2, "SS total");
  EXPECT_NEAR(a.row("residual").ss, 94.0 / 3.0, 1e-11);  // exact: 11 sums of small integers
  EXPECT_EQ(a.row("residual").df, 8);
  // Design-Expert's F (unrounded MS_E = 3.917): A 53.19, B 19.15, AB 2.13; p 0.0024 for B.
  expect_printed(a.row("A").f, 53.19, 2, "F A");
  expect_printed(a.row("B").f, 19.15, 2, "F B");
  expect_printed(a.row("A:B").f, 2.13, 2, "F AB");
  expect_printed(a.row("B").p, 0.0024, 4, "p B");
  EXPECT_LT(a.row("A").p, 1e-4);
  // Replicates but a saturated cell model: no lack-of-fit row.
  EXPECT_FALSE(a.has_row("lack of fit"));
  // The linear model leaves AB as lack of fit (1 df) against 8 df of pure error.
  const auto l = analyze_regression(X, yv, model_terms(ModelKind::linear, {"A", "B"}));
  EXPECT_NEAR(l.row("lack of fit").ss, 25.0 / 3.0, 1e-11);
  EXPECT_EQ(l.row("lack of fit").df, 1);
  EXPECT_NEAR(l.row("pure error").ss, 94.0 / 3.0, 1e-11);
  EXPECT_NEAR(l.row("lack of fit").f, (25.0 / 3.0) / (94.0 / 24.0), 1e-12);
  // Effects: A = 8.33, B = -5.00, AB = 1.67 (Montgomery sec. 6.2).
  const auto e = main_effects(X, yv, {"A", "B"});
  EXPECT_NEAR(e.effects[0].effect, 25.0 / 3.0, 1e-12);
  EXPECT_NEAR(e.effects[1].effect, -5.0, 1e-12);
  EXPECT_EQ(e.effects[0].pareto_rank, 1);
}

// Table 6.10: filtration rate in standard order (1), a, b, ab, c, ..., abcd.
const double kFiltration[16] = {45, 71, 48, 65, 68, 60, 80, 65, 43, 100, 45, 104, 75, 86, 70, 96};

TEST(Montgomery, Example6_2FiltrationRateEffectsAndProjectedAnova) {
  Eigen::MatrixXd X(16, 4);
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 4; ++j) X(i, j) = ((i >> j) & 1) ? 1 : -1;
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(kFiltration, 16);
  // All 15 effects (Table 6.11), as main effects of the interaction columns.
  const std::vector<std::string> names{"A", "B", "AB", "C", "AC", "BC", "ABC", "D", "AD", "BD", "ABD", "CD", "ACD", "BCD", "ABCD"};
  const double book[15] = {21.625, 3.125, 0.125, 9.875, -18.125, 2.375, 1.875, 14.625,
                           16.625, -0.375, 4.125, -1.125, -1.625, -2.625, 1.375};
  Eigen::MatrixXd cols(16, 15);
  for (int s = 1; s < 16; ++s) {
    // Column order of `names`: subset s of {A, B, C, D} as a bit mask (A = 1, B = 2, C = 4, D = 8).
    cols.col(s - 1).setOnes();
    for (int j = 0; j < 4; ++j)
      if (s & (1 << j)) cols.col(s - 1) = cols.col(s - 1).cwiseProduct(X.col(j));
  }
  const auto e = main_effects(cols, y, names);
  for (int j = 0; j < 15; ++j) EXPECT_NEAR(e.effects[static_cast<std::size_t>(j)].effect, book[j], 1e-12) << names[static_cast<std::size_t>(j)];
  EXPECT_EQ(e.effects[0].name, "A");
  EXPECT_EQ(e.pareto[0], 0);   // A largest
  EXPECT_EQ(e.pareto[1], 4);   // then AC
  EXPECT_EQ(e.error_source, "none");
  // Projected model A, C, D, AC, AD (Montgomery Table 6.13): SS 1870.56, 390.06, 855.56, 1314.06,
  // 1105.56, residual 195.13 on 10 df, total 5730.94; F 95.86, 19.99, 43.85, 67.34, 56.66.
  const std::vector<std::string> f4{"A", "B", "C", "D"};
  std::vector<Term> terms{parse_term("intercept", f4), parse_term("A", f4), parse_term("C", f4), parse_term("D", f4),
                          parse_term("A:C", f4), parse_term("A:D", f4)};
  const auto a = analyze_regression(X, y, terms);
  expect_printed(a.row("A").ss, 1870.56, 2, "SS A");
  expect_printed(a.row("C").ss, 390.06, 2, "SS C");
  expect_printed(a.row("D").ss, 855.56, 2, "SS D");
  expect_printed(a.row("A:C").ss, 1314.06, 2, "SS AC");
  expect_printed(a.row("A:D").ss, 1105.56, 2, "SS AD");
  expect_printed(a.row("residual").ss, 195.13, 2, "SS residual");
  expect_printed(a.row("total").ss, 5730.94, 2, "SS total");
  EXPECT_EQ(a.row("residual").df, 10);
  expect_printed(a.row("A").f, 95.86, 2, "F A");
  expect_printed(a.row("C").f, 19.99, 2, "F C");
  expect_printed(a.row("D").f, 43.85, 2, "F D");
  expect_printed(a.row("A:C").f, 67.34, 2, "F AC");
  expect_printed(a.row("A:D").f, 56.66, 2, "F AD");
  // Coded coefficients are half the effects: 70.06 + 10.81 A + 4.94 C + 7.31 D - 9.06 AC + 8.31 AD.
  expect_printed(a.coefficient("intercept"), 70.06, 2, "b0");
  expect_printed(a.coefficient("A"), 10.81, 2, "bA");
  expect_printed(a.coefficient("A:C"), -9.06, 2, "bAC");
}

TEST(Montgomery, Example11_1FirstOrderModelWithLackOfFit) {
  // 2^2 in time (30..40 min) and temperature (150..160 F) plus five centre runs.
  Eigen::MatrixXd X(9, 2);
  X << -1, -1, -1, 1, 1, -1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0;
  Eigen::VectorXd y(9);
  y << 39.3, 40.0, 40.9, 41.5, 40.3, 40.5, 40.7, 40.2, 40.6;
  const auto a = analyze_regression(X, y, model_terms(ModelKind::linear, {"x1", "x2"}));
  // Fitted y = 40.44 + 0.775 x1 + 0.325 x2; Table 11.2: regression 2.8250 (2 df), residual 0.1772
  // (6 df) of which interaction 0.0025 + pure quadratic 0.0027 (= our lack of fit, 2 df) and pure
  // error 0.1720 (4 df); total 3.0022 (8 df); F(model) = 47.83.
  expect_printed(a.coefficient("intercept"), 40.44, 2, "b0");
  expect_printed(a.coefficient("x1"), 0.775, 3, "b1");
  expect_printed(a.coefficient("x2"), 0.325, 3, "b2");
  expect_printed(a.row("model").ss, 2.8250, 4, "SS model");
  expect_printed(a.row("residual").ss, 0.1772, 4, "SS residual");
  expect_printed(a.row("lack of fit").ss, 0.0025 + 0.0027, 4, "SS lack of fit");
  EXPECT_EQ(a.row("lack of fit").df, 2);
  expect_printed(a.row("pure error").ss, 0.1720, 4, "SS pure error");
  EXPECT_EQ(a.row("pure error").df, 4);
  expect_printed(a.row("total").ss, 3.0022, 4, "SS total");
  // The book prints F = 47.83 from the rounded MS_E 0.1772 / 6; unrounded it is 1.4125 / 0.029537
  // = 47.82, which is what a statistics package prints.
  expect_printed(a.row("model").f, 47.82, 2, "F model");
}

// The axial runs are at alpha = sqrt(2) (the book's table shows it rounded to 1.414; with 1.414
// itself the F values move in the second decimal, e.g. F(model) 79.67 instead of the printed 79.85).
struct Ccd112 {
  Eigen::MatrixXd coded{13, 2};
  Eigen::VectorXd y{13};
  Ccd112() {
    coded << -1, -1, -1, 1, 1, -1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, std::sqrt(2.0), 0, -std::sqrt(2.0), 0, 0, std::sqrt(2.0), 0, -std::sqrt(2.0);
    y << 76.5, 77.0, 78.0, 79.5, 79.9, 80.3, 80.0, 79.7, 79.8, 78.4, 75.6, 78.5, 77.0;
  }
};

TEST(Montgomery, Example11_2CentralCompositeQuadratic) {
  const Ccd112 d;
  const auto a = analyze_regression(d.coded, d.y, model_terms(ModelKind::quadratic, {"A", "B"}));
  // Coded fit (Montgomery sec. 11.3.4): 79.94 + 0.995 x1 + 0.515 x2 - 1.376 x1^2 - 1.001 x2^2 + 0.250 x1x2.
  expect_printed(a.coefficient("intercept"), 79.94, 2, "b0");
  expect_printed(a.coefficient("A"), 0.995, 3, "bA");
  expect_printed(a.coefficient("B"), 0.515, 3, "bB");
  expect_printed(a.coefficient("A^2"), -1.376, 3, "bAA");
  expect_printed(a.coefficient("B^2"), -1.001, 3, "bBB");
  expect_printed(a.coefficient("A:B"), 0.250, 3, "bAB");
  // Design-Expert ANOVA (partial SS): model 28.25 (5) F 79.85; A 7.92 F 111.93; B 2.12 F 30.01
  // p 0.0009; A^2 13.18 F 186.22; B^2 6.97 F 98.56; AB 0.25 F 3.53 p 0.1022; residual 0.50 (7) MS
  // 0.071; lack of fit 0.28 (3) MS 0.094 F 1.78 p 0.2897; pure error 0.21 (4) MS 0.053; total 28.74.
  expect_printed(a.row("model").ss, 28.25, 2, "SS model");
  EXPECT_EQ(a.row("model").df, 5);
  expect_printed(a.row("model").f, 79.85, 2, "F model");
  const auto ss = [&](const std::string& t) {
    for (std::size_t j = 0; j < a.terms.size(); ++j)
      if (a.terms[j].name == t) return a.adjusted_ss(static_cast<Eigen::Index>(j));
    return 0.0;
  };
  const double mse = a.row("residual").ms;
  expect_printed(ss("A"), 7.92, 2, "partial SS A");
  expect_printed(ss("B"), 2.12, 2, "partial SS B");
  expect_printed(ss("A^2"), 13.18, 2, "partial SS A^2");
  expect_printed(ss("B^2"), 6.97, 2, "partial SS B^2");
  expect_printed(ss("A:B"), 0.25, 2, "partial SS AB");
  expect_printed(ss("A") / mse, 111.93, 2, "F A");
  expect_printed(ss("B") / mse, 30.01, 2, "F B");
  expect_printed(ss("A^2") / mse, 186.22, 2, "F A^2");
  expect_printed(ss("B^2") / mse, 98.56, 2, "F B^2");
  expect_printed(ss("A:B") / mse, 3.53, 2, "F AB");
  // Orthogonal terms and the last term: sequential SS equal the partial SS.
  EXPECT_NEAR(a.row("A").ss, ss("A"), 1e-10);
  EXPECT_NEAR(a.row("A:B").ss, ss("A:B"), 1e-10);
  EXPECT_NEAR(a.row("B^2").ss, ss("B^2"), 1e-10);
  expect_printed(a.row("B").p, 0.0009, 4, "p B");
  expect_printed(a.row("A:B").p, 0.1022, 4, "p AB");
  expect_printed(a.row("residual").ss, 0.50, 2, "SS residual");
  expect_printed(mse, 0.071, 3, "MS residual");
  expect_printed(a.row("lack of fit").ss, 0.28, 2, "SS lack of fit");
  expect_printed(a.row("lack of fit").ms, 0.094, 3, "MS lack of fit");
  expect_printed(a.row("lack of fit").f, 1.78, 2, "F lack of fit");
  expect_printed(a.row("lack of fit").p, 0.2897, 4, "p lack of fit");
  expect_printed(a.row("pure error").ss, 0.21, 2, "SS pure error");
  expect_printed(a.row("pure error").ms, 0.053, 3, "MS pure error");
  expect_printed(a.row("total").ss, 28.74, 2, "SS total");
  EXPECT_EQ(a.row("total").df, 12);
  // In natural units (time = 85 + 5 x1, temperature = 175 + 5 x2) the same data give the printed
  // "final equation in terms of actual factors": -1430.52285 + 7.80749 time + 13.27053 temp
  // - 0.05505 time^2 - 0.04005 temp^2 + 0.01 time temp.
  const Eigen::MatrixXd nat = to_natural(d.coded, {{"time", 80, 90}, {"temp", 170, 180}});
  const auto n = analyze_regression(nat, d.y, model_terms(ModelKind::quadratic, {"time", "temp"}));
  expect_printed(n.coefficient("intercept"), -1430.52285, 5, "b0 natural");
  expect_printed(n.coefficient("time"), 7.80749, 5, "b time");
  expect_printed(n.coefficient("temp"), 13.27053, 5, "b temp");
  expect_printed(n.coefficient("time^2"), -0.05505, 5, "b time^2");
  expect_printed(n.coefficient("temp^2"), -0.04005, 5, "b temp^2");
  expect_printed(n.coefficient("time:temp"), 0.01, 5, "b time:temp");
  // The ANOVA does not depend on the coding (hierarchical terms span the same spaces).
  for (const char* r : {"model", "residual", "lack of fit", "pure error", "total"})
    EXPECT_NEAR(n.row(r).ss, a.row(r).ss, 1e-8 * a.row("total").ss) << r;  // natural-unit columns ~1e4: 1e-8 relative
}

TEST(Regression, PressEqualsBruteForceLeaveOneOut) {
  // Independent computation: refit without each run and sum the squared prediction errors.
  const Ccd112 d;
  const auto terms = model_terms(ModelKind::quadratic, {"A", "B"});
  const auto a = analyze_regression(d.coded, d.y, terms);
  double press = 0.0;
  for (int i = 0; i < 13; ++i) {
    Eigen::MatrixXd X(12, 2);
    Eigen::VectorXd y(12);
    for (int r = 0, k = 0; r < 13; ++r)
      if (r != i) { X.row(k) = d.coded.row(r); y(k++) = d.y(r); }
    const auto f = fit_least_squares(model_matrix(terms, X), y, {"1", "A", "B", "AB", "AA", "BB"});
    press += std::pow(d.y(i) - (model_row(terms, d.coded.row(i).transpose()) * f.coefficients)(0), 2);
  }
  EXPECT_NEAR(a.press, press, 1e-10 * press);  // two exact-arithmetic routes; 1e-10 covers rounding
  EXPECT_NEAR(a.pred_r2, 1.0 - press / a.row("total").ss, 1e-10);
  EXPECT_NEAR(a.r2, a.row("model").ss / a.row("total").ss, 1e-14);
  EXPECT_NEAR(a.adj_r2, 1.0 - a.row("residual").ms / (a.row("total").ss / 12.0), 1e-14);
}

TEST(Regression, AliasedTermIsNamed) {
  Eigen::MatrixXd X(4, 2);
  X << -1, -1, 1, -1, -1, 1, 1, 1;
  Eigen::VectorXd y(4);
  y << 1, 2, 3, 4;
  try {
    analyze_regression(X, y, model_terms(ModelKind::quadratic, {"a", "b"}));
    FAIL() << "expected an error";
  } catch (const DoeError& e) {
    // 4 runs, 6 terms: refused for too few runs first.
    EXPECT_NE(std::string(e.what()).find("observations = 4"), std::string::npos) << e.what();
  }
  Eigen::MatrixXd X2(6, 2);
  X2 << -1, -1, 1, -1, -1, 1, 1, 1, -1, -1, 1, 1;
  Eigen::VectorXd y2(6);
  y2 << 1, 2, 3, 4, 5, 6;
  // a^2 equals the intercept column on a two-level design.
  try {
    analyze_regression(X2, y2, model_terms(ModelKind::quadratic, {"a", "b"}));
    FAIL() << "expected an error";
  } catch (const DoeError& e) {
    EXPECT_NE(std::string(e.what()).find("term a^2: aliased"), std::string::npos) << e.what();
  }
}

TEST(Effects, DummyColumnsAndResidualAgreeOnASaturatedPlackettBurman) {
  // With all columns orthogonal, the residual of the main-effects model is exactly the dummy
  // columns' sum of squares, so both routes give the same standard error (Montgomery sec. 8.7).
  Eigen::MatrixXd D(12, 11);
  const int g[11] = {1, 1, -1, 1, 1, 1, -1, -1, -1, 1, -1};
  for (int i = 0; i < 11; ++i)
    for (int j = 0; j < 11; ++j) D(i, j) = g[((j - i) % 11 + 11) % 11];
  D.row(11).setConstant(-1);
  Eigen::VectorXd y(12);
  for (int i = 0; i < 12; ++i) y(i) = 10 + 3 * D(i, 0) - 2 * D(i, 1) + 0.5 * D(i, 2) + 0.1 * std::sin(7.0 * i);
  const std::vector<std::string> names{"a", "b", "c", "d", "e", "f", "g", "h"};
  const auto viaDummies = main_effects(D.leftCols(8), y, names, D.rightCols(3));
  const auto viaResidual = main_effects(D.leftCols(8), y, names);
  EXPECT_EQ(viaDummies.df_error, 3);
  EXPECT_EQ(viaResidual.df_error, 3);
  for (std::size_t j = 0; j < 8; ++j) {
    EXPECT_NEAR(viaDummies.effects[j].se, viaResidual.effects[j].se, 1e-12);
    EXPECT_NEAR(viaDummies.effects[j].p, viaResidual.effects[j].p, 1e-10);
  }
  EXPECT_EQ(viaDummies.pareto[0], 0);
  EXPECT_EQ(viaDummies.pareto[1], 1);
  EXPECT_LT(viaDummies.effects[0].p, 1e-3);
}

}  // namespace
}  // namespace seedcal::doe
