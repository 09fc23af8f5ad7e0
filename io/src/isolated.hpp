// io/src/isolated.hpp: running a reader that may crash (a foreign library's parser on a
// damaged file) in a child process, and the byte stream its answer comes back in.
#pragma once
#include <cstddef>
#include <cstring>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

namespace qmotion::io {

/// Runs `work` in a forked child process and returns the bytes it appended to its
/// argument. An Error that `work` throws is thrown again here with its code and message
/// (any other exception becomes Errc::invalid_input naming `path`). When the child dies
/// instead (a signal, an exit without a whole answer), throws Errc::invalid_input naming
/// `path`, `format` and the signal: the parser crashed on the file, and this process,
/// whose memory the parser never touched, goes on. When no child can be made (fork
/// fails), `work` runs in this process.
///
/// The child starts as a copy of this process and ends with _exit (no atexit handlers, no
/// flush of this process's stdio buffers). As with any fork, a multithreaded caller must
/// not hold locks the child's work needs.
std::string run_isolated(const std::string& path, const char* format,
                         const std::function<void(std::string& answer)>& work);

/// Appends values to an answer in a fixed order; ByteReader takes them back in that order.
class ByteWriter {
 public:
  explicit ByteWriter(std::string& out) : out_(out) {}
  template <typename T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <typename T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put(v.size());
    out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put_string(const std::string& s) {
    put(s.size());
    out_.append(s);
  }

 private:
  std::string& out_;
};

/// Reads what a ByteWriter wrote. Throws Errc::internal when the bytes run out (an answer
/// cut short, which run_isolated never returns).
class ByteReader {
 public:
  explicit ByteReader(const std::string& in) : in_(in) {}
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v;
    std::memcpy(&v, take(sizeof v), sizeof v);
    return v;
  }
  template <typename T>
  std::vector<T> get_vector() {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto n = count(sizeof(T));
    std::vector<T> v(n);
    if (n > 0) std::memcpy(v.data(), take(n * sizeof(T)), n * sizeof(T));
    return v;
  }
  std::string get_string() {
    const auto n = count(1);
    return std::string(take(n), n);
  }
  bool done() const { return at_ == in_.size(); }

 private:
  std::size_t count(std::size_t item_bytes);
  const char* take(std::size_t n);
  const std::string& in_;
  std::size_t at_ = 0;
};

}  // namespace qmotion::io
