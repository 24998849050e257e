// SPDX-License-Identifier: BSD-3-Clause
// Column expressions (io/column_expression.hpp): the grammar, units into SI and into the column's
// unit, the errors (option, character, what was expected), and readCsv with definitions.

#include "geaware/io/column_expression.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geaware/io/csv_reader.hpp"

namespace {

using geaware::io::ColumnDefinition;
using geaware::io::ColumnExpression;
using geaware::io::CsvError;
using geaware::io::CsvReadOptions;
using geaware::io::ExpressionError;
using geaware::io::parseColumnDefinition;
using geaware::io::readCsv;
using geaware::io::unitOfColumnName;

// The values of `spec` (NAME=EXPR) with the fields given in order of first use.
std::vector<double> eval(const std::string& spec, const std::vector<std::vector<double>>& fields,
                         const std::vector<std::string>& log_units = {}) {
  const ColumnDefinition d = parseColumnDefinition(spec, "--column");
  std::vector<ColumnExpression::FieldData> data;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    data.push_back({fields[k], k < log_units.size() ? log_units[k] : std::string_view()});
  }
  const std::size_t rows = fields.empty() ? 1 : fields.front().size();
  return d.expression.evaluate(data, rows, unitOfColumnName(d.name), d.name);
}

// The message of the ExpressionError `spec` throws (empty: none).
std::string error(const std::string& spec, const std::vector<std::vector<double>>& fields = {{1.0}},
                  bool constant = false) {
  try {
    const ColumnDefinition d =
        parseColumnDefinition(spec, constant ? "--const" : "--column", constant);
    std::vector<ColumnExpression::FieldData> data;
    for (std::size_t k = 0; k < d.expression.fields().size(); ++k)
      data.push_back({fields.at(0), {}});
    (void)d.expression.evaluate(data, fields.at(0).size(), unitOfColumnName(d.name), d.name);
  } catch (const ExpressionError& e) {
    return e.what();
  }
  return {};
}

TEST(ColumnExpression, UnitsConvertIntoSiAndIntoTheColumnsUnit) {
  EXPECT_DOUBLE_EQ(eval("h_m=z[mm]", {{120.0}})[0], 0.12);
  EXPECT_DOUBLE_EQ(eval("h_m=z[cm]", {{12.0}})[0], 0.12);
  EXPECT_DOUBLE_EQ(eval("gyro_x_radps=gyro.x[deg/s]", {{180.0}})[0], M_PI);
  EXPECT_DOUBLE_EQ(eval("a_x_mps2=acc.x[g]", {{-1.0}})[0], -9.80665);
  EXPECT_DOUBLE_EQ(eval("vz_mps=vz[mm/s]", {{250.0}})[0], 0.25);
  EXPECT_DOUBLE_EQ(eval("vbat_V=pm.vbatMV[mV]", {{3700.0}})[0], 3.7);
  EXPECT_DOUBLE_EQ(eval("t_s=timestamp[us]", {{1.5e6}})[0], 1.5);
  EXPECT_DOUBLE_EQ(eval("t_s=timestamp[\xC2\xB5s]", {{2e6}})[0], 2.0);
  EXPECT_DOUBLE_EQ(eval("thrust_N=Thrust[kgf]", {{0.5}})[0], 0.5 * 9.80665);
  // The column's unit is read from its name: rpm stays rpm, rad/s becomes rpm, rad becomes deg.
  EXPECT_DOUBLE_EQ(eval("n1_rpm=m1[rpm]", {{9000.0}})[0], 9000.0);
  EXPECT_DOUBLE_EQ(eval("rpm=m1[RPM] / 7", {{70000.0}})[0], 10000.0);  // a column named as its unit
  EXPECT_NEAR(eval("n1_rpm=w[rad/s]", {{100.0}})[0], 100.0 * 60.0 / (2.0 * M_PI), 1e-9);
  EXPECT_NEAR(eval("tilt_deg=pitch[rad]", {{M_PI / 4.0}})[0], 45.0, 1e-12);
  // A dimensionless column: a throttle from a PWM pulse width.
  EXPECT_NEAR(eval("throttle=(pwm[us] - 1000[us]) / 1000[us]", {{1500.0}})[0], 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(eval("throttle=cmd[%]", {{40.0}})[0], 0.4);
  // No unit anywhere: the column's unit already (a rename, a constant).
  EXPECT_DOUBLE_EQ(eval("fz_N=Fz", {{-3.5}})[0], -3.5);
  EXPECT_DOUBLE_EQ(eval("tilt_deg=0", {})[0], 0.0);
}

TEST(ColumnExpression, TheGrammarHasPrecedenceParenthesesArraysAndDelta) {
  EXPECT_DOUBLE_EQ(eval("x=1 + 2 * 3", {})[0], 7.0);
  EXPECT_DOUBLE_EQ(eval("x=(1 + 2) * 3", {})[0], 9.0);
  EXPECT_DOUBLE_EQ(eval("x=8 / 4 / 2", {})[0], 1.0);  // left to right
  EXPECT_DOUBLE_EQ(eval("x=2 - -3", {})[0], 5.0);
  EXPECT_DOUBLE_EQ(eval("x=1.5e3 * .5", {})[0], 750.0);
  // Array elements and dots belong to the field's name; blanks inside a name are kept.
  const auto d = parseColumnDefinition("n3_rpm=esc[2].esc_rpm / 7", "--column");
  ASSERT_EQ(d.expression.fields().size(), 1u);
  EXPECT_EQ(d.expression.fields()[0], "esc[2].esc_rpm");
  const auto spaced = parseColumnDefinition("n1_rpm=Motor Electrical Speed / 7", "--column");
  EXPECT_EQ(spaced.expression.fields()[0], "Motor Electrical Speed");
  const auto quoted = parseColumnDefinition("n1_rpm=\"ESC-1 (rpm)\" * 2", "--column");
  EXPECT_EQ(quoted.expression.fields()[0], "ESC-1 (rpm)");
  // A field used twice is read once.
  EXPECT_EQ(parseColumnDefinition("x=a * a + b", "--column").expression.fields().size(), 2u);
  // delta: a velocity difference over its time step, the first sample without a value.
  const auto a =
      eval("az_mps2=delta(vz[m/s]) / delta(t[ms])", {{0.0, 0.1, 0.3}, {0.0, 10.0, 20.0}});
  EXPECT_TRUE(std::isnan(a[0]));
  EXPECT_DOUBLE_EQ(a[1], 10.0);
  EXPECT_DOUBLE_EQ(a[2], 20.0);
  EXPECT_EQ(parseColumnDefinition("x=delta(delta(a))", "--column").expression.lag(), 2u);
}

TEST(ColumnExpression, TheLogsUnitIsUsedUnlessOneIsWritten) {
  EXPECT_DOUBLE_EQ(eval("h_m=z", {{250.0}}, {"mm"})[0], 0.25);
  EXPECT_DOUBLE_EQ(eval("h_m=z[cm]", {{25.0}}, {"mm"})[0], 0.25);     // the written unit wins
  EXPECT_DOUBLE_EQ(eval("h_m=z", {{250.0}}, {"furlong"})[0], 250.0);  // unknown: none
}

TEST(ColumnExpression, ErrorsNameTheOptionTheCharacterAndWhatWasExpected) {
  // Characters are counted in the option's value as typed, from 1.
  EXPECT_EQ(error("h_m=z[mm"),
            "--column 'h_m=z[mm': character 6: expected ']' closing the unit that starts here");
  EXPECT_NE(error("h_m=z[furlong]").find("character 7: unknown unit 'furlong' (expected one of: "),
            std::string::npos);
  EXPECT_EQ(error("h_m=(z + 1"),
            "--column 'h_m=(z + 1': character 11: expected ')' closing the '(' at character 5, "
            "found the end");
  EXPECT_EQ(error("h_m="),
            "--column 'h_m=': character 5: expected an expression (a field, a number or a "
            "parenthesis), found nothing");
  EXPECT_EQ(error("h_m=z +"),
            "--column 'h_m=z +': character 8: expected a field, a number or '(', found the end");
  EXPECT_EQ(
      error("h_m=z )"),
      "--column 'h_m=z )': character 7: expected an operator (+ - * /) or the end, found ')'");
  EXPECT_NE(error("h_m=Thrust (kgf)")
                .find("character 12: 'Thrust' followed by '(': the only function is delta"),
            std::string::npos);
  EXPECT_NE(error("h_m=5mm").find("character 6: expected an operator after the number"),
            std::string::npos);
  EXPECT_EQ(error("h_m z"), "--column 'h_m z': character 6: expected NAME=EXPR, e.g. h_m=z[mm]");
  EXPECT_EQ(error("=z"), "--column '=z': character 1: expected a column name before '='");
  // Units that do not fit: named with the character of the operator or the expression.
  EXPECT_EQ(error("n1_rpm=z[mm]"),
            "--column 'n1_rpm=z[mm]': character 9: the expression gives length, column "
            "'n1_rpm' holds angular velocity [rpm]");
  EXPECT_EQ(error("h_m=z[mm] + w[deg]"),
            "--column 'h_m=z[mm] + w[deg]': character 11: cannot add: the left side is "
            "length, the right side angle");
  EXPECT_NE(error("h_m=z[mm] + 5").find("character 11: one side is length, the other has no unit"),
            std::string::npos);
  EXPECT_NE(error("throttle=pwm[us]").find("gives time, column 'throttle' is dimensionless"),
            std::string::npos);
  EXPECT_EQ(error("h_m=z[mm][cm]"),
            "--column 'h_m=z[mm][cm]': character 10: expected an operator (+ - * /) or "
            "the end, found '['");
  // --const takes no field.
  EXPECT_EQ(error("tilt_deg=pitch", {{1.0}}, true),
            "--const 'tilt_deg=pitch': character 10: expected a number (with a unit, e.g. "
            "120[mm]), found the field "
            "'pitch'");
  EXPECT_EQ(error("h_m=120[mm]", {{1.0}}, true), "");
}

TEST(ColumnExpression, HostileInputIsBounded) {
  EXPECT_NE(
      error("x=" + std::string(300, '(') + "1" + std::string(300, ')')).find("too deeply nested"),
      std::string::npos);
  std::string sum = "x=1";
  for (int i = 0; i < 6000; ++i) sum += "+1";
  EXPECT_NE(error(sum).find("expression too long"), std::string::npos);
}

class CsvDefinitions : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) /
           (std::string("geaware_csv_definitions_") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  std::filesystem::path file(const std::string& text) {
    const auto f = dir_ / "log.csv";
    std::ofstream(f, std::ios::binary) << text;
    return f;
  }
  static CsvReadOptions options(const std::vector<std::string>& specs) {
    CsvReadOptions o;
    o.columns = {{"t_s"}, {"h_m", 0.0, 100.0}, {"tilt_deg", -90.0, 90.0}};
    for (const auto& s : specs) {
      o.definitions.push_back(parseColumnDefinition(s, "--column"));
    }
    return o;
  }
  static std::string csvError(const std::filesystem::path& f, const CsvReadOptions& o) {
    try {
      (void)readCsv(f, o);
    } catch (const std::exception& e) {
      return e.what();
    }
    return {};
  }
  std::filesystem::path dir_;
};

TEST_F(CsvDefinitions, ColumnsAreComputedFromTheFieldsTheLogHas) {
  const auto f = file("time[ms],z[mm],other\n0,100,1\n10,150,2\n20,400,3\n");
  const auto t = readCsv(f, options({"t_s=time", "h_m=z", "tilt_deg=0"}));
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.names, (std::vector<std::string>{"t_s", "h_m", "tilt_deg"}));
  EXPECT_DOUBLE_EQ(t.column("t_s")[2], 0.02);  // the header's unit ms
  EXPECT_DOUBLE_EQ(t.column("h_m")[1], 0.15);  // mm
  EXPECT_EQ(t.column("tilt_deg"), (std::vector<double>{0.0, 0.0, 0.0}));
  EXPECT_EQ(t.first_data_line, 2u);
  // delta leaves the first row without a value: it is dropped, and the lines move with it.
  CsvReadOptions o = options({"t_s=time", "h_m=z", "tilt_deg=delta(other) * 0"});
  const auto d = readCsv(f, o);
  ASSERT_EQ(d.rows(), 2u);
  EXPECT_EQ(d.first_data_line, 3u);
  EXPECT_DOUBLE_EQ(d.column("h_m")[0], 0.15);
  // A name the file has whole, with characters the grammar reads as operators, still reads it.
  const auto g = file("t_s,F-z,tilt\n0,1,0\n1,2,0\n");
  CsvReadOptions r;
  r.columns = {{"t_s"}, {"fz_N"}, {"tilt"}};
  r.definitions = {parseColumnDefinition("fz_N=F-z", "--column")};
  EXPECT_EQ(readCsv(g, r).column("fz_N"), (std::vector<double>{1.0, 2.0}));
}

TEST_F(CsvDefinitions, ErrorsNameTheOptionTheFileTheLineAndTheColumnsFound) {
  const auto f = file("time[ms],z[mm]\n0,100\n10,150000\n20,400\n");
  EXPECT_EQ(csvError(f, options({"t_s=time", "h_m=zz[mm]", "tilt_deg=0"})),
            "--column 'h_m=zz[mm]': character 5: " + f.string() +
                " has no column 'zz' (its columns: time[ms], z[mm])");
  // The computed value is checked against the column's range, on its line.
  EXPECT_EQ(csvError(f, options({"t_s=time", "h_m=z", "tilt_deg=0"})),
            f.string() +
                ":3: column 'h_m': value 150 (--column 'h_m=z') is outside the plausible range [0, "
                "100] for "
                "this column (wrong unit?)");
  EXPECT_NE(csvError(f, options({"t_s=time", "h_m=z", "tilt_deg=0", "x_m=z"}))
                .find("--column 'x_m=z': character 1: 'x_m' is not a column this command reads "
                      "(t_s, h_m, tilt_deg)"),
            std::string::npos);
  const auto g = file("time,z\n0,0.1\n2,0.2\n1,0.3\n");
  EXPECT_EQ(csvError(g, options({"t_s=time[s]", "h_m=z", "tilt_deg=0"})),
            g.string() +
                ":4: column 't_s': time 1 (--column 't_s=time[s]') does not increase (line 3: 2)");
  // Units are checked on the header before the rows are read (a bad row later is not reached).
  const auto u = file("time[ms],z[mm]\n0,100\n10,x\n");
  EXPECT_EQ(csvError(u, options({"t_s=time", "h_m=z[deg]", "tilt_deg=0"})),
            "--column 'h_m=z[deg]': character 6: the expression gives angle, column 'h_m' holds "
            "length [m]");
  CsvReadOptions missing = options({"t_s=time", "h_m=z"});
  EXPECT_EQ(csvError(u, missing),
            u.string() +
                ": column 'tilt_deg': not in the file (its columns: time[ms], z[mm]) "
                "and not defined: --column tilt_deg=EXPR, or --const tilt_deg=VALUE");
  const auto z = file("t_s,a,b\n0,1,0\n1,1,1\n");
  EXPECT_EQ(csvError(z, options({"h_m=a / b", "tilt_deg=0"})),
            z.string() + ":2: column 'h_m': not finite (--column 'h_m=a / b')");
}

}  // namespace
