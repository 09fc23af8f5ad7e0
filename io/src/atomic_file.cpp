// io/src/atomic_file.cpp
#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/kernel/error.hpp>
#include <random>

namespace qmotion::io {

std::string lower_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

void refuse_file_size(const std::string& path, std::uintmax_t max_bytes) {
  throw Error(Errc::invalid_input,
              path + ": more than " + std::to_string(max_bytes) +
                  " bytes (the limit of a file qmotion reads or writes, which bounds memory)");
}

AtomicOutput::AtomicOutput(std::string path, std::uintmax_t max_bytes)
    : path_(std::move(path)), max_bytes_(max_bytes) {
  if (path_.empty()) throw Error(Errc::invalid_input, "empty output path");
  if (std::filesystem::is_directory(path_))
    throw Error(Errc::invalid_input, path_ + ": is a directory, expected a file name");
  std::random_device rd;
  temp_ = path_ + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(rd() % 1000000);
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) std::remove(temp_.c_str());
}

void AtomicOutput::commit() {
  std::error_code ec;
  if (const auto size = std::filesystem::file_size(temp_, ec); !ec && size > max_bytes_) {
    std::remove(temp_.c_str());
    refuse_file_size(path_, max_bytes_);
  }
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(temp_.c_str());
    throw Error(Errc::invalid_input, path_ + ": cannot write output file: " + why);
  }
  committed_ = true;
}

AtomicWriter::AtomicWriter(std::string path, std::uintmax_t max_bytes)
    : out_(std::move(path), max_bytes), max_bytes_(max_bytes) {
  fd_ = ::open(out_.temp_path().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0)
    throw Error(Errc::invalid_input,
                out_.path() + ": cannot create output file: " + std::strerror(errno));
}

AtomicWriter::~AtomicWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void AtomicWriter::append(const char* data, std::size_t size) {
  // Refused before the bytes go out: a file reading would refuse is never finished.
  if (size > max_bytes_ - written_) refuse_file_size(out_.path(), max_bytes_);
  written_ += size;
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw Error(Errc::invalid_input,
                  out_.path() + ": write failed: " + std::strerror(n < 0 ? errno : ENOSPC));
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void AtomicWriter::commit() {
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0)
    throw Error(Errc::invalid_input, out_.path() + ": write failed: " + std::strerror(errno));
  out_.commit();
}

void write_file_atomic(const std::string& path, const std::string& content,
                       std::uintmax_t max_bytes) {
  if (content.size() > max_bytes) refuse_file_size(path, max_bytes);
  AtomicWriter file(path, max_bytes);
  file.append(content);
  file.commit();
}

}  // namespace qmotion::io
