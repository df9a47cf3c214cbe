// The command-line conventions (apps/common/cli.hpp) and the CSV reader's rules
// (apps/common/csv.hpp), tested on the functions the tools call.
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli.hpp"
#include "csv.hpp"

namespace fuzzypid::cli {
namespace {

TEST(ParseUnsigned, AcceptsDigitsOnlyWithinRange) {
  EXPECT_EQ(parse_unsigned("0"), 0u);
  EXPECT_EQ(parse_unsigned("18446744073709551615"), 18446744073709551615u);
  for (const char* bad : {"-1", "+1", " 1", "1 ", "18446744073709551616", "1e3", "", "0x10"})
    EXPECT_FALSE(parse_unsigned(bad)) << bad;
}

TEST(ParseFinite, RefusesNaNInfinityAndOverflow) {
  EXPECT_EQ(parse_finite("-2.5"), -2.5);
  EXPECT_EQ(parse_finite(" 1e3 "), 1000.0);
  for (const char* bad : {"nan", "inf", "-inf", "1e999", "1x", "", " "})
    EXPECT_FALSE(parse_finite(bad)) << bad;
}

// 1e-320 is finite (a subnormal): it is a number, not "not a finite number"; the range decides.
TEST(ParseFinite, AcceptsSubnormalsAsRead) {
  EXPECT_EQ(parse_finite("1e-320"), 1e-320);
  EXPECT_EQ(parse_finite("-4.9e-324"), -4.9e-324);
  EXPECT_EQ(parse_finite("1e-400"), 0.0);  // below every subnormal: rounds to zero
  EXPECT_EQ(finite_in(0.0, 1.0)("1e-320"), "");
  EXPECT_NE(finite_in(1.0, 2.0)("1e-320").find("outside"), std::string::npos);
}

enum class Color { Red, Green };
constexpr std::array<fuzzypid::EnumName<Color>, 2> kColorNames = {
    {{Color::Red, "red"}, {Color::Green, "green"}}};

// Runs a parser of one --seed, --gain and --color option; the exit code (or -1 to run).
int parse_args(std::vector<const char*> args, std::uint64_t& seed, double& gain, Color& color) {
  CLI::App app("test", "test");
  app.add_option("--seed", seed)->check(unsigned_integer());
  app.add_option("--gain", gain)->check(finite_in(0.0, 10.0));
  add_enum_option(app, "--color", color, kColorNames, "a color");
  args.insert(args.begin(), "test");
  const auto code = parse(app, static_cast<int>(args.size()), args.data());
  return code ? *code : -1;
}

TEST(Parse, UsageErrorsExitTwoAndValidValuesRun) {
  std::uint64_t seed = 1;
  double gain = 1.0;
  Color color = Color::Red;
  EXPECT_EQ(parse_args({"--seed", "7", "--gain", "2.5", "--color", "green"}, seed, gain, color),
            -1);
  EXPECT_EQ(seed, 7u);
  EXPECT_EQ(gain, 2.5);
  EXPECT_EQ(color, Color::Green);
  for (const std::vector<const char*>& bad : {std::vector<const char*>{"--seed", "-1"},
                                              {"--seed", "18446744073709551616"},
                                              {"--gain", "nan"},
                                              {"--gain", "11"},
                                              {"--gain", "inf"},
                                              {"--color", "blue"},
                                              {"--bogus"},
                                              {"--seed"}}) {
    seed = 1;
    EXPECT_EQ(parse_args(bad, seed, gain, color), kExitUsage) << bad[0];
    EXPECT_EQ(seed, 1u);
  }
}

// The one refusal of an option that would do nothing: the first given of the named options, with
// its scope and the reason; nothing when the combination applies or none of them is given.
TEST(GivenOptions, RefusesTheFirstGivenOptionThatWouldDoNothing) {
  CLI::App app("t");
  std::string path, seed, format;
  bool flag = false;
  app.add_option("--path", path);
  app.add_option("--ik-seed", seed);
  app.add_option("--format", format);
  app.add_flag("--flag", flag);
  const char* argv[] = {"t", "--ik-seed", "1", "--flag"};
  ASSERT_EQ(parse(app, 4, argv), std::nullopt);
  const GivenOptions given(app);
  EXPECT_TRUE(given.has("--ik-seed"));
  EXPECT_TRUE(given.has("--flag"));
  EXPECT_FALSE(given.has("--path"));
  EXPECT_EQ(given.names().size(), 2u);
  EXPECT_EQ(given.refuse_unused({"--format", "--ik-seed", "--flag"}, false, "a Cartesian path file",
                                "no --path is given"),
            "--ik-seed applies only to a Cartesian path file; no --path is given");
  EXPECT_EQ(given.refuse_unused({"--ik-seed"}, true, "a Cartesian path file", "x"), "");
  EXPECT_EQ(given.refuse_unused({"--format", "--path"}, false, "--out", "x"), "");
  EXPECT_EQ(GivenOptions().refuse_unused({"--ik-seed"}, false, "s", "r"), "");
}

TEST(Parse, HelpExitsZero) {
  std::uint64_t seed = 1;
  double gain = 1.0;
  Color color = Color::Red;
  testing::internal::CaptureStdout();
  EXPECT_EQ(parse_args({"--help"}, seed, gain, color), kExitOk);
  const std::string help = testing::internal::GetCapturedStdout();
  EXPECT_NE(help.find("red or green; default red"), std::string::npos) << help;
}

// All rows the reader accepts from `text`, or the error it stops with.
std::string read_all(const std::string& text, std::vector<std::vector<double>>* rows = nullptr) {
  std::istringstream in(text);
  CsvReader reader(in);
  CsvRow row;
  while (reader.next(row))
    if (rows != nullptr) rows->push_back(row.values);
  return reader.error();
}

TEST(CsvReader, AHeaderIsALineOfText) {
  std::vector<std::vector<double>> rows;
  EXPECT_EQ(read_all("e, ec\n1,2\n", &rows), "");
  EXPECT_EQ(rows, (std::vector<std::vector<double>>{{1.0, 2.0}}));
}

TEST(CsvReader, AFirstRowOfNonFiniteNumbersIsAnErrorNotAHeader) {
  for (const char* first : {"nan,nan", "inf,-inf", "1e999,1e999", "nan,x", "x,1"})
    EXPECT_EQ(read_all(std::string(first) + "\n1,2\n").rfind("line 1: column", 0), 0u) << first;
}

// Spreadsheets quote numbers: a first row of quoted numbers is an error naming the quotes, not a
// header that silently drops the row; quoted names still make a header.
TEST(CsvReader, QuotedNumbersAreAnErrorNotAHeader) {
  EXPECT_EQ(read_all("\"0.5\",\"0.2\"\n1,2\n"),
            "line 1: column 1 ('\"0.5\"') is a number in quotes: write it without them");
  EXPECT_EQ(read_all("1,2\n3, \"4\"\n"),
            "line 2: column 2 ('\"4\"') is a number in quotes: write it without them");
  std::vector<std::vector<double>> rows;
  EXPECT_EQ(read_all("\"e\",\"ec\"\n1,2\n", &rows), "");
  EXPECT_EQ(rows, (std::vector<std::vector<double>>{{1.0, 2.0}}));
}

TEST(CsvReader, SubnormalNumbersAreFinite) {
  std::vector<std::vector<double>> rows;
  EXPECT_EQ(read_all("1e-320,0\n", &rows), "");
  EXPECT_EQ(rows, (std::vector<std::vector<double>>{{1e-320, 0.0}}));
}

TEST(CsvReader, ALineBeyondTheBoundIsAnError) {
  const std::string digits(CsvReader::kMaxLineBytes + 1, '1');
  EXPECT_EQ(read_all(digits + "\n"), "line 1: longer than 65536 bytes");
  const std::string fits(CsvReader::kMaxLineBytes, ' ');
  EXPECT_EQ(read_all("1\n" + fits + "\n2\n"), "");
}

}  // namespace
}  // namespace fuzzypid::cli
