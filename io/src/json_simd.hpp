// io/src/json_simd.hpp: simdjson's on-demand parser behind qmotion's readers. Internal to
// qmotion_io (not installed: simdjson is a private dependency).
#pragma once
#include <simdjson.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/poses.hpp>
#include <string>

static_assert(simdjson::SIMDJSON_PADDING <= qmotion::io::kReadPadding);

namespace qmotion::io::simd {

namespace sj = simdjson::ondemand;

/// Texts longer than this are read with a parser of their own (Document::own).
inline constexpr std::size_t kOwnParserChars = std::size_t(1) << 20;
/// Members longer than this are read with a parser of their own (read_member).
inline constexpr std::size_t kSharedParserChars = std::size_t(64) << 10;

/// A text with simdjson's padding readable past its end: the text itself when its spare
/// capacity holds the padding (read_text_file leaves it), else a padded copy. Slices of
/// view() can be read in place (read_member).
struct Padded {
  explicit Padded(const std::string& text);  ///< text must outlive the Padded
  Padded(const Padded&) = delete;            // view() may point into copy_
  Padded& operator=(const Padded&) = delete;
  std::string_view view() const { return text_; }

 private:
  simdjson::padded_string copy_;
  std::string_view text_;
};

/// A document being read with this thread's parser (a long text: with its own), in place or
/// from a padded copy (Padded). `ok` is false when simdjson refused the text outright.
struct Document {
  explicit Document(const std::string& text);  ///< text must outlive the Document
  Padded padded;
  /// A parser of its own for a text above kOwnParserChars, freed with the document: the
  /// thread's parser would keep an index the size of the longest text it ever read (4 bytes
  /// a character reserved, about 5 MB touched for a 10^4-pose motion).
  std::unique_ptr<sj::parser> own;
  sj::document doc;
  bool ok = false;
  /// True when nothing but white space follows the root value (the on-demand parser
  /// stops after it, so trailing content is checked here).
  bool at_end();
};

/// Builds `out` from v, as parse_json would: float literals as their source text, or as
/// doubles when `plain`. False on any error (the caller then falls back to nlohmann, which
/// words the message), and for arrays and objects nested more than kMaxJsonDepth levels
/// deep in the document, v lying `depth` levels deep.
bool build(sj::value v, nlohmann::json& out, bool plain, std::size_t depth = 0);
/// Validates v whole without building anything (v lying `depth` levels deep, as in build).
bool check(sj::value v, std::size_t depth = 0);

/// The number at v (a JSON number, or a string holding a plain decimal literal) with its
/// source text, as read_number would read it. False for anything else (including "p/q"
/// strings): the caller falls back to the DOM reader. With `lean`, a decimal whose text is
/// the shortest round-trip text of its value is kept without its text (Number::source()
/// gives it back).
bool number(sj::value v, Number& out, bool lean = false);

/// Appends the numbers of the array at v to `out` (as number() reads each, `lean` too);
/// false for anything else.
bool numbers(sj::value v, std::vector<Number>& out, bool lean = false);

/// Reads `text`, a JSON array of rows of numbers ("[[1, 2.5], [3, 4]]") with `width`
/// numbers a row (0: as many as the first row has), each number as number(..., lean) reads
/// it, by a strict scanner of its own that cuts a long text at row ends and reads the parts
/// on every core. `rows(n, w)` is told the row count and width once, before any number, and
/// returns false to refuse them; `row(i)` is where row i's w numbers go (called from several
/// threads, each row once). False for anything the scanner does not take (a string, a
/// nested array, an integer of 19 characters or more, a number out of double's range, rows
/// of another width, bad syntax): the caller then reads the text with read_value.
bool number_rows(std::string_view text, std::size_t width,
                 const std::function<bool(std::size_t, std::size_t)>& rows,
                 const std::function<Number*(std::size_t)>& row, bool lean);

/// One member of a JSON object as members() finds it: the key as written (no escapes) and
/// the text of its value.
struct Member {
  std::string_view key;
  std::string_view value;
};

/// The members of the JSON object that is `text` (white space around it allowed), found by
/// a scanner that indexes nothing: each value's extent comes from its brackets and quotes,
/// and is not validated (read_member does that when it reads the value). False when the text
/// is not an object of that form, or a key holds an escape, a control character or bytes
/// that are not UTF-8: the caller then reads the text with a full parser, which words any
/// refusal.
bool members(std::string_view text, std::vector<Member>& out);

/// Calls each(slice) with the text of each element of the JSON array that is `text`, the
/// extents found as members() finds them (nothing indexed, nothing validated). False when
/// the text is not an array of that form, or as soon as `each` returns false.
bool elements(std::string_view text, const std::function<bool(std::string_view)>& each);

/// Validates the value whose text is `slice` (a slice of a Padded view, `depth` levels deep)
/// as check() does; an array or object longer than kSharedParserChars part by part
/// (elements(), members()), so no parser indexes more than that: simdjson reserves about 5
/// bytes a character of what it reads.
bool check_slice(std::string_view slice, std::size_t depth);

/// Reads one value's text, a slice of a Padded view (members() gives them), and hands the
/// value to `read`: arrays and objects in place, with a parser whose index covers the slice
/// alone (a parser of its own above kSharedParserChars); a scalar through a small bracketed
/// copy, since simdjson does not hand out a document's scalar root as a value. False when the
/// slice is not one valid JSON value or `read` returns false.
bool read_member(std::string_view slice, const std::function<bool(sj::value)>& read);

/// The JSON string whose text is `slice` (read by read_member) into `out`; false for
/// anything else.
bool string_value(std::string_view slice, std::string& out);
/// The JSON integer from lo to hi whose text is `slice` into `out`; false for anything else.
bool integer_value(std::string_view slice, std::int64_t lo, std::int64_t hi, int& out);

/// Reads `text`, one JSON value's text cut out of a document (sj::array::raw_json), with a
/// parser of its own, and hands the value to `read`; false when it is not valid or `read`
/// returns false.
bool read_value(std::string_view text, const std::function<bool(sj::value)>& read);

/// The pose document whose text is `text` (a slice of a Padded view): parse_poses_fast's
/// reader, also for a pose document inside another file. The poses array is cut into poses
/// (elements()), each read alone, so no index covers more than one pose. std::nullopt as
/// parse_poses_fast; throws the set's checks.
std::optional<PoseSet> poses_text(std::string_view text, const std::string& source);

}  // namespace qmotion::io::simd
