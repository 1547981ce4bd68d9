// CSV reading: header, trimming, quotes, round trip, and error messages naming file, line, column
// and value.
#include <gtest/gtest.h>

#include "doe/core/errors.hpp"
#include "doe/io/csv_table.hpp"

namespace seedcal::doe {
namespace {

TEST(CsvTable, ParsesTrimsQuotesAndRoundTrips) {
  const CsvTable t = parse_csv("a, \"b, c\" ,y\n\n1, 2.5,-3e-2\n+4,5,6\n", "mem.csv");
  ASSERT_EQ(t.columns, (std::vector<std::string>{"a", "b, c", "y"}));
  ASSERT_EQ(t.values.rows(), 2);
  EXPECT_EQ(t.values(0, 2), -0.03);
  EXPECT_EQ(t.values(1, 0), 4.0);
  EXPECT_EQ(t.require("y"), 2);
  Eigen::MatrixXd m(1, 2);
  m << 0.1, 1.0 / 3.0;
  const CsvTable r = parse_csv(format_csv({"p", "q"}, m), "rt");
  EXPECT_EQ(r.values(0, 1), 1.0 / 3.0);  // shortest round-trip text: exact
}

TEST(CsvTable, ErrorsNameFileLineColumnAndValue) {
  auto msg = [](const std::string& text) {
    try {
      parse_csv(text, "d.csv");
    } catch (const DoeError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(msg("a,b\n1,2\n3,x\n"), "d.csv:3: column b = 'x': not a finite number");
  EXPECT_EQ(msg("a,b\n1,2,3\n"), "d.csv:2: 3 fields, the header has 2");
  EXPECT_EQ(msg("a,a\n"), "d.csv:1: column a: named twice");
  EXPECT_EQ(msg("a,b\n1,nan\n"), "d.csv:2: column b = 'nan': not a finite number");
  EXPECT_EQ(msg(""), "d.csv: empty file (expected a header row of column names)");
  const CsvTable t = parse_csv("a,b\n", "d.csv");
  EXPECT_THROW(t.require("c"), DoeError);
}

}  // namespace
}  // namespace seedcal::doe
