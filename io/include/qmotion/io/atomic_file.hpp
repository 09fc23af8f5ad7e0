// <qmotion/io/atomic_file.hpp>
#pragma once
#include <cstddef>
#include <string>

namespace qmotion::io {

/// An output file that appears only when complete (docs/formats.md): writers write to temp_path(),
/// commit() renames it onto the final path; destroying an uncommitted AtomicOutput
/// removes the temporary, so a failure leaves nothing behind.
class AtomicOutput {
 public:
  explicit AtomicOutput(std::string path);
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
  bool committed_ = false;
};

/// An AtomicOutput written in pieces: append() writes to the temporary file, commit()
/// closes it and renames it onto the path. Throws Errc::invalid_input naming the path when
/// the file cannot be created or written.
class AtomicWriter {
 public:
  explicit AtomicWriter(std::string path);
  ~AtomicWriter();
  AtomicWriter(const AtomicWriter&) = delete;
  AtomicWriter& operator=(const AtomicWriter&) = delete;

  void append(const char* data, std::size_t size);
  void append(const std::string& s) { append(s.data(), s.size()); }
  void commit();

 private:
  AtomicOutput out_;
  int fd_ = -1;
};

/// The extension of the file name in `path`, lower case, with its dot (".step"); "" when
/// it has none. Output formats are chosen by it.
std::string lower_extension(const std::string& path);

/// Writes `content` to `path` atomically; throws Errc::invalid_input naming the path.
void write_file_atomic(const std::string& path, const std::string& content);

}  // namespace qmotion::io
