// io/atomic_file.cpp
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

AtomicOutput::AtomicOutput(std::string path) : path_(std::move(path)) {
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
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(temp_.c_str());
    throw Error(Errc::invalid_input, path_ + ": cannot write output file: " + why);
  }
  committed_ = true;
}

void write_file_atomic(const std::string& path, const std::string& content) {
  AtomicOutput out(path);
  {
    std::ofstream f(out.temp_path(), std::ios::binary | std::ios::trunc);
    if (!f)
      throw Error(Errc::invalid_input,
                  path + ": cannot create output file: " + std::strerror(errno));
    f << content;
    f.flush();
    if (!f) throw Error(Errc::invalid_input, path + ": write failed: " + std::strerror(errno));
  }
  out.commit();
}

}  // namespace qmotion::io
