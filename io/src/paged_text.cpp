// io/src/paged_text.cpp: PagedText, a file's text in an anonymous mapping (paged_text.hpp).
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/paged_text.hpp>
#include <qmotion/kernel/error.hpp>
#include <utility>

namespace qmotion::io {
namespace {

std::size_t page_bytes() {
  static const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return page;
}

/// Closes a descriptor when it goes out of scope.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

PagedText PagedText::in_string(std::string text) {
  PagedText t;
  t.fallback_ = std::move(text);
  t.fallback_.reserve(t.fallback_.size() + kReadPadding);  // the padding view() promises
  t.data_ = t.fallback_.data();
  t.size_ = t.fallback_.size();
  return t;
}

PagedText PagedText::read(const std::string& path, std::uintmax_t max_bytes) {
  PagedText t;
  Descriptor d{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  struct stat st {};
  if (d.fd < 0 || ::fstat(d.fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    // Not a regular file (or not openable: read_text_file words that): a string, read
    // in chunks up to the limit.
    return in_string(read_text_file(path, max_bytes));
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > max_bytes) refuse_file_size(path, max_bytes);
  const std::size_t page = page_bytes();
  // One byte more than the size, to see a file that grew since fstat.
  const std::size_t want = static_cast<std::size_t>(size) + 1;
  t.map_bytes_ = (want + kReadPadding + page - 1) / page * page;
  void* m =
      ::mmap(nullptr, t.map_bytes_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) {
    t.map_bytes_ = 0;
    throw Error(Errc::invalid_input, path + ": cannot map memory for the file's text");
  }
  t.map_ = static_cast<char*>(m);
  // Huge pages where the system gives them on request (Debian's default THP mode): a
  // 10^4-pose motion's text is 2800 page faults in 4 KiB pages, 6 in 2 MiB ones (eval
  // measured 0.09 -> 0.06 s). Advice only; pages given back early split as needed.
  if (t.map_bytes_ >= (std::size_t(2) << 20)) (void)::madvise(m, t.map_bytes_, MADV_HUGEPAGE);
  std::size_t got = 0;
  while (got < want) {
    const ssize_t n = ::read(d.fd, t.map_ + got, want - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error(Errc::invalid_input, path + ": read error");
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  if (got == want) {
    // The file grew while it was read: read it as a stream, with the limit checked.
    return in_string(read_text_file(path, max_bytes));
  }
  t.data_ = t.map_;
  t.size_ = got;
  return t;
}

PagedText::PagedText(PagedText&& o) noexcept { *this = std::move(o); }

PagedText& PagedText::operator=(PagedText&& o) noexcept {
  if (this == &o) return *this;
  unmap();
  const bool was_string = o.map_ == nullptr;
  map_ = std::exchange(o.map_, nullptr);
  map_bytes_ = std::exchange(o.map_bytes_, 0);
  released_ = std::exchange(o.released_, 0);
  fallback_ = std::move(o.fallback_);
  size_ = std::exchange(o.size_, 0);
  data_ = was_string ? fallback_.data() : map_;
  o.data_ = nullptr;
  return *this;
}

PagedText::~PagedText() { unmap(); }

void PagedText::unmap() noexcept {
  if (map_) ::munmap(map_, map_bytes_);
  map_ = nullptr;
  map_bytes_ = 0;
}

void PagedText::release_before(std::size_t offset) {
  if (!map_) return;
  const std::size_t page = page_bytes();
  const std::size_t end = std::min(offset, size_) / page * page;
  if (end <= released_) return;
  // MADV_DONTNEED on private anonymous pages: they leave at once and read as zeros after.
  if (::madvise(map_ + released_, end - released_, MADV_DONTNEED) == 0) released_ = end;
}

std::string PagedText::whole(const std::string& path) const {
  if (!released()) return std::string(view());
  return read_text_file(path);
}

}  // namespace qmotion::io
