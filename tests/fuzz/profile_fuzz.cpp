// tests/fuzz/profile_fuzz.cpp: profile import from STEP, IGES and JSON files through
// OpenCASCADE. The first byte chooses the format, the rest is the file, written to a
// temporary file (OpenCASCADE's readers take paths).
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <qmotion/io/profiles.hpp>

#include "fuzz_util.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace qmotion;
  if (size == 0) return 0;
  static const char* const kExt[] = {".step", ".igs", ".json"};
  const auto dir = std::filesystem::temp_directory_path();
  const std::string path =
      (dir / ("qmotion-fuzz-" + std::to_string(getpid()) + kExt[data[0] % 3])).string();
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  fuzz::accept_refusals([&] { (void)io::read_profile(path, "mm"); });
  std::filesystem::remove(path);
  return 0;
}
