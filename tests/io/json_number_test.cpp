// tests/io/json_number_test.cpp mirrors io/json_number.hpp
#include <filesystem>
#include <fstream>
#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif
#include <qmotion/io/json_number.hpp>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {
using io::parse_json;
using io::parse_number_text;
#ifdef QMOTION_WITH_CGAL
using kernel::Rational;
#endif

#ifdef QMOTION_WITH_CGAL
TEST(JsonNumber, FloatLiteralsKeepTheirSourceText) {
  const auto j =
      parse_json(R"({"a": 0.1, "b": [1, -2.50e-3, 12345678901234567890123], "c": "3/4"})", "mem");
  EXPECT_EQ(io::read_number(j["a"], "a").text, "0.1");
  EXPECT_EQ(io::exact_from_text(io::read_number(j["a"], "a").text.str()),
            Rational(1) / Rational(10));
  EXPECT_EQ(io::exact_from_text(io::read_number(j["b"][1], "b").text.str()),
            Rational(-25) / Rational(10000));
  EXPECT_EQ(io::exact_from_text(io::read_number(j["b"][2], "b").text.str()),
            Rational("12345678901234567890123"));
  EXPECT_EQ(io::read_number(j["b"][0], "b").value, 1.0);
  EXPECT_EQ(io::exact_from_text(io::read_number(j["c"], "c").text.str()),
            Rational(3) / Rational(4));
  EXPECT_DOUBLE_EQ(io::read_number(j["c"], "c").value, 0.75);
}
#endif

TEST(JsonNumber, AKeptTextOfAnyLengthReadsBackWhole) {
  // The length takes one byte below 255 and nine from there: both sides of the switch,
  // the longest text a number may have, copies and moves.
  for (const std::size_t n : {std::size_t(1), std::size_t(19), std::size_t(254), std::size_t(255),
                              std::size_t(256), std::size_t(300), io::kMaxNumberChars}) {
    std::string s;
    for (std::size_t i = 0; i < n; ++i) s.push_back(static_cast<char>('0' + (i * 7 + n) % 10));
    const io::NumberText t(s);
    ASSERT_FALSE(t.empty());
    EXPECT_EQ(t.size(), n);
    EXPECT_EQ(t.view(), s);
    EXPECT_EQ(t.str(), s);
    const io::NumberText copy = t;
    EXPECT_EQ(copy, t);
    EXPECT_NE(copy.begin(), t.begin());
    io::NumberText moved = io::NumberText(s.substr(0, n - 1));
    EXPECT_EQ(moved.size(), n - 1);
    moved = copy;
    EXPECT_EQ(moved.view(), s);
  }
  const io::NumberText none("");
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.size(), 0U);
}

#ifdef QMOTION_WITH_CGAL
TEST(JsonNumber, RationalTextIsExactAndCanonical) {
  EXPECT_EQ(io::exact_from_text(parse_number_text("6/-4", "x").text.str()),
            Rational(-3) / Rational(2));
  EXPECT_EQ(io::exact_from_text(parse_number_text("1e3", "x").text.str()), Rational(1000));
  EXPECT_EQ(io::exact_from_text(parse_number_text(".5", "x").text.str()),
            Rational(1) / Rational(2));
  EXPECT_EQ(io::exact_to_text(Rational(-3) / Rational(2)), "-3/2");
  // Leading zeros are decimal, never octal (regression: gmpxx reads "010" as 8).
  EXPECT_EQ(io::exact_from_text("010"), Rational(10));
  EXPECT_EQ(io::exact_from_text("0.0189"), Rational(189) / Rational(10000));
  EXPECT_EQ(io::exact_from_text("-007/09"), Rational(-7) / Rational(9));
  EXPECT_DOUBLE_EQ(parse_number_text("1/3", "x").value, 1.0 / 3.0);
}
#endif

TEST(JsonNumber, TheScannerAcceptsExactlyTheGrammar) {
  // decimal: ws [+-]? (digits [. digits*] | . digits) ([eE] [+-]? digits)? ws
  // ratio:   ws [+-]? digits ws / ws [+-]? digits ws; the text kept is the number, trimmed.
  const std::vector<std::pair<std::string, std::string>> good{
      {"0", "0"},           {"-1.", "-1."},      {"+.5", "+.5"}, {" 2.5e-3 ", "2.5e-3"},
      {"\t7E+2\n", "7E+2"}, {"1.e5", "1.e5"},    {"3/4", "3/4"}, {" -3 / +4 ", "-3/+4"},
      {"010", "010"},       {"1e0001", "1e0001"}};
  for (const auto& [in, text] : good) {
    SCOPED_TRACE(in);
    EXPECT_EQ(parse_number_text(in, "x").text, text);
    EXPECT_EQ(parse_number_text(in, "x").value, text.find('/') == std::string::npos
                                                    ? std::strtod(text.c_str(), nullptr)
                                                    : parse_number_text(text, "x").value);
  }
  EXPECT_DOUBLE_EQ(parse_number_text(" -3 / +4 ", "x").value, -0.75);
  for (const std::string bad :
       {"",   " ",  ".",     "-",     "+-1",   "1e",   "1e+", "e5",  ".e5",  "1..2", "1.2.3", "1 2",
        "3/", "/4", "3/4/5", "1.5/2", "3/4.0", "0x10", "1,5", "- 1", "1e5x", "3 /",  "\"1\""}) {
    SCOPED_TRACE("'" + bad + "'");
    EXPECT_TRUE(throws_error([&] { parse_number_text(bad, "f"); }, Errc::invalid_input, {"f"}));
  }
}

TEST(JsonNumber, BadNumbersNameTheField) {
  EXPECT_TRUE(throws_error([] { parse_number_text("NaN", "poses[1].t"); }, Errc::invalid_input,
                           {"poses[1].t", "finite"}));
  EXPECT_TRUE(throws_error([] { parse_number_text("inf", "f"); }, Errc::invalid_input, {"finite"}));
  EXPECT_TRUE(
      throws_error([] { parse_number_text("1e999", "f"); }, Errc::invalid_input, {"range"}));
  EXPECT_TRUE(throws_error([] { parse_number_text("1/0", "f"); }, Errc::invalid_input,
                           {"zero denominator"}));
  EXPECT_TRUE(
      throws_error([] { parse_number_text("abc", "f"); }, Errc::invalid_input, {"not a number"}));
  EXPECT_TRUE(throws_error([] { io::read_number(nlohmann::json::array(), "pos"); },
                           Errc::invalid_input, {"pos", "expected a number"}));
}

TEST(JsonNumber, WorkPerNumberIsBounded) {
  // A number's text and an exact number's exponent are bounded: the big-number work of
  // exact mode stays small per number, and no conversion throws a standard exception.
  const std::string long_text = "1." + std::string(io::kMaxNumberChars, '3');
  EXPECT_TRUE(throws_error([&] { parse_number_text(long_text, "poses[0].t"); }, Errc::invalid_input,
                           {"poses[0].t", "characters", "at most 1000"}));
  EXPECT_NO_THROW(parse_number_text("1." + std::string(io::kMaxNumberChars - 3, '3'), "f"));
#ifdef QMOTION_WITH_CGAL
  EXPECT_TRUE(throws_error([] { io::exact_from_text("1e99999999999999999999"); },
                           Errc::invalid_input, {"exponent out of range"}));
  EXPECT_TRUE(throws_error([] { io::exact_from_text("1e1001"); }, Errc::invalid_input,
                           {"exponent out of range"}));
  EXPECT_EQ(io::exact_from_text("25e-1000") * io::exact_from_text("4e1000"), kernel::Rational(100));
  EXPECT_EQ(io::exact_from_text("-1.5e+0003"), kernel::Rational(-1500));
#endif
}

TEST(JsonNumber, FilesAboveTheSizeLimitAreRefused) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "qmotion_size_test.json").string();
  std::ofstream(path) << std::string(100, ' ') << "{}";
  EXPECT_TRUE(throws_error([&] { io::read_text_file(path, 50); }, Errc::invalid_input,
                           {path, "more than 50 bytes"}));
  EXPECT_EQ(io::read_text_file(path, 102).size(), 102u);
  EXPECT_GE(io::kMaxFileBytes, std::uintmax_t(256) << 20);  // a 10^5-pose motion file fits
  // A device has no size to check first: reading stops at the limit (it used to read on).
  EXPECT_TRUE(throws_error([&] { io::read_text_file("/dev/zero", 1 << 16); }, Errc::invalid_input,
                           {"/dev/zero", "more than 65536 bytes"}));
}

TEST(JsonNumber, SyntaxErrorsGiveLineAndColumn) {
  EXPECT_TRUE(throws_error([] { parse_json("{\n  \"a\": [1, 2,\n}", "f.json"); },
                           Errc::invalid_input, {"f.json", "line 3"}));
  EXPECT_TRUE(throws_error([] { parse_json(R"({"a": NaN})", "g.json"); }, Errc::invalid_input,
                           {"g.json", "NaN"}));
  EXPECT_TRUE(throws_error([] { parse_json("", "e.json"); }, Errc::invalid_input,
                           {"e.json", "invalid JSON"}));
  EXPECT_TRUE(throws_error([] { io::read_json_file("/nonexistent/x.json"); }, Errc::invalid_input,
                           {"/nonexistent/x.json", "cannot open"}));
}

TEST(JsonNumber, TheFastParserBuildsTheReferenceDocument) {
  const std::vector<std::string> texts = {
      R"({"a": 0.1, "b": [1, -2.50e-3, 12345678901234567890123, -9223372036854775808,
          18446744073709551615], "c": "3/4", "d": {"e": [true, false, null, []], "f": {}}})",
      R"([1.0, "\u00e9\n\"", {"k": 1E+2}, [[[]]], -0, -0.0, 5e-324])",
      R"({"dup": 1, "dup": 2.5})",
      "  [ 1 ,\t2 ]\n",
      R"({"method": {"x": 0.30000000000000004, "y": [1.5, 2]}, "z": 0.1})",
  };
  for (const auto& t : texts) {
    EXPECT_EQ(parse_json(t, "m"), io::parse_json_reference(t, "m")) << t;
    // The plain member keeps float literals as numbers, like nlohmann's own parse.
    const auto plain = parse_json(t, "m", "method");
    if (plain.is_object() && plain.contains("method")) {
      EXPECT_EQ(plain["method"], nlohmann::json::parse(t)["method"]) << t;
      EXPECT_EQ(plain["z"], "0.1") << t;
    }
  }
}

TEST(JsonNumber, TheFastParserRefusesWhatTheReferenceRefuses) {
  const std::vector<std::string> bad = {
      "[1] 2",      "[1,]",        R"({"a": tru})", "[01]",       "[1.]",       "[.5]",
      "[1e]",       R"({"a":1,})", R"(["\x"])",     "[\"\xff\"]", "[-]",        "[1e999]",
      R"({"a" 1})", "{",           "[1 2]",         "[NaN]",      R"({"a":[}])"};
  for (const auto& t : bad) {
    EXPECT_TRUE(throws_error([&] { io::parse_json_reference(t, "r.json"); }, Errc::invalid_input,
                             {"r.json"}))
        << t;
    EXPECT_TRUE(throws_error([&] { parse_json(t, "f.json"); }, Errc::invalid_input,
                             {"f.json", "invalid JSON"}))
        << t;
  }
}

// A file of nested brackets alone once exhausted the stack of the recursive reader (the
// pose fuzzer's finding, 6372 bytes of "["): nesting is bounded, and deeper is refused.
TEST(JsonNumber, NestingIsBoundedAndDeeperIsRefusedByName) {
  auto nested = [](std::size_t depth, const std::string& open, const std::string& close) {
    std::string t;
    for (std::size_t i = 0; i < depth; ++i) t += open;
    t += "1";
    for (std::size_t i = 0; i < depth; ++i) t += close;
    return t;
  };
  for (const auto& brackets :
       std::vector<std::pair<std::string, std::string>>{{"[", "]"}, {"{\"a\":", "}"}}) {
    const std::string open = brackets.first, close = brackets.second;
    const auto ok = nested(io::kMaxJsonDepth, open, close);
    EXPECT_EQ(parse_json(ok, "m"), io::parse_json_reference(ok, "m"));
    for (const std::size_t depth : {io::kMaxJsonDepth + 1, std::size_t(100000)}) {
      const auto deep = nested(depth, open, close);
      for (const auto& text : {deep, "{\"poses\": " + deep + "}"}) {
        EXPECT_TRUE(throws_error([&] { parse_json(text, "deep.json"); }, Errc::invalid_input,
                                 {"deep.json", "nested more than 100 levels deep"}));
        EXPECT_TRUE(throws_error([&] { parse_json(text, "deep.json", "poses"); },
                                 Errc::invalid_input, {"deep.json", "nested more than 100"}));
      }
    }
    // Unclosed, as the fuzzer's file was.
    EXPECT_TRUE(throws_error([&] { parse_json(std::string(100000, open[0]), "open.json"); },
                             Errc::invalid_input, {"open.json"}));
  }
}

TEST(JsonNumber, FilesAreReadWithRoomToParseInPlace) {
  const auto path = std::filesystem::temp_directory_path() / "qmotion_padding_test.json";
  { std::ofstream(path) << "[1, 2, 3]"; }
  const std::string text = io::read_text_file(path.string());
  std::filesystem::remove(path);
  EXPECT_EQ(text, "[1, 2, 3]");
  EXPECT_GE(text.capacity(), text.size() + io::kReadPadding);
}

}  // namespace
}  // namespace qmotion::test
