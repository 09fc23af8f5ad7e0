// <qmotion/io/atomic_file.hpp>
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace qmotion::io {

/// Largest file qmotion reads, and so the largest it writes (docs/geometry.md, "Limits"): every
/// file qmotion writes, qmotion reads back. A 10^5-pose motion file is about 115 MB; a circle
/// swept along it, 533 MB, is read back in about 4 GB.
inline constexpr std::uintmax_t kMaxFileBytes = std::uintmax_t(512) << 20;

/// Throws Errc::invalid_input: `path` is larger than max_bytes. One message for reading and
/// writing, so that a file refused on the way out reads as one refused on the way in.
[[noreturn]] void refuse_file_size(const std::string& path, std::uintmax_t max_bytes);

/// An output file that appears only when complete (docs/formats.md): writers write to temp_path(),
/// commit() renames it onto the final path; destroying an uncommitted AtomicOutput
/// removes the temporary, so a failure leaves nothing behind. commit() refuses a temporary
/// larger than max_bytes (refuse_file_size), so no file appears that reading would refuse.
class AtomicOutput {
 public:
  explicit AtomicOutput(std::string path, std::uintmax_t max_bytes = kMaxFileBytes);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  const std::string& path() const { return path_; }
  /// Temporary file in the same folder (same file system, so the rename is atomic).
  const std::string& temp_path() const { return temp_; }
  /// Renames the temporary onto path(); throws Errc::invalid_input naming the path.
  void commit();

 private:
  std::string path_, temp_;
  std::uintmax_t max_bytes_;
  bool committed_ = false;
};

/// An AtomicOutput written in pieces: append() writes to the temporary file, commit()
/// closes it and renames it onto the path. Throws Errc::invalid_input naming the path when
/// the file cannot be created or written, or as soon as it would exceed max_bytes.
class AtomicWriter {
 public:
  explicit AtomicWriter(std::string path, std::uintmax_t max_bytes = kMaxFileBytes);
  ~AtomicWriter();
  AtomicWriter(const AtomicWriter&) = delete;
  AtomicWriter& operator=(const AtomicWriter&) = delete;

  void append(const char* data, std::size_t size);
  void append(const std::string& s) { append(s.data(), s.size()); }
  void commit();

 private:
  AtomicOutput out_;
  std::uintmax_t max_bytes_, written_ = 0;
  int fd_ = -1;
};

/// The extension of the file name in `path`, lower case, with its dot (".step"); "" when
/// it has none. Output formats are chosen by it.
std::string lower_extension(const std::string& path);

/// Writes `content` to `path` atomically; throws Errc::invalid_input naming the path (also
/// when content is larger than max_bytes, before any file is created).
void write_file_atomic(const std::string& path, const std::string& content,
                       std::uintmax_t max_bytes = kMaxFileBytes);

}  // namespace qmotion::io
