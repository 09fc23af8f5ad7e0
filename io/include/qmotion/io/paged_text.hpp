// <qmotion/io/paged_text.hpp>: a file's text in pages of its own, given back as it is read.
#pragma once
#include <cstdint>
#include <qmotion/io/atomic_file.hpp>
#include <string>
#include <string_view>

namespace qmotion::io {

/// A file's text, read and limited as read_text_file reads it, held in an anonymous mapping
/// of its own with kReadPadding readable bytes after the text (a JSON reader parses it in
/// place). A reader that has moved past a part gives its whole pages back (release_before),
/// and the rest goes with the object, to the system rather than to the heap. Large motion
/// files are read this way: their text leaves memory as the numbers it holds arrive, instead
/// of sitting beside them (docs/measurements.md, peak memory). A file of no known size (a
/// pipe, a device) is held in a string instead, and then nothing is given back early.
class PagedText {
 public:
  /// Throws Errc::invalid_input as read_text_file does (cannot open, too large, read error).
  static PagedText read(const std::string& path, std::uintmax_t max_bytes = kMaxFileBytes);

  PagedText(PagedText&& o) noexcept;
  PagedText& operator=(PagedText&& o) noexcept;
  PagedText(const PagedText&) = delete;
  PagedText& operator=(const PagedText&) = delete;
  ~PagedText();

  /// The text; the kReadPadding bytes past its end are readable.
  std::string_view view() const { return {data_, size_}; }
  /// Gives back the whole pages of the text below `offset`: the text there reads as zero
  /// bytes afterwards, so the caller reads no further before offset.
  void release_before(std::size_t offset);
  /// Whether release_before gave any page back (the text is then no longer whole).
  bool released() const { return released_ > 0; }
  /// The whole text as a string: a copy of it, or, once pages were given back, the file read
  /// again (for a reader that declined the text part way and needs it whole).
  std::string whole(const std::string& path) const;

 private:
  PagedText() = default;
  static PagedText in_string(std::string text);
  void unmap() noexcept;
  char* map_ = nullptr;        ///< the mapping, or null when the text is in fallback_
  std::size_t map_bytes_ = 0;  ///< its length, whole pages
  std::size_t released_ = 0;   ///< bytes given back from the mapping's start
  std::string fallback_;       ///< a file of no known size: its text, with the padding reserved
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace qmotion::io
