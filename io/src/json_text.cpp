// io/src/json_text.cpp
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_text.hpp>

namespace qmotion::io {

void JsonText::blocks(std::size_t n, std::size_t numbers_each, const Emit& emit) {
  // About 8192 numbers (~0.2 MB of text) a block: a few hundred microseconds of work, far
  // above a task's cost; a long array makes dozens of blocks, so two cores stay busy.
  constexpr std::size_t kNumbersPerBlock = 8192;
  const std::size_t per =
      std::max<std::size_t>(1, kNumbersPerBlock / std::max<std::size_t>(1, numbers_each));
  if (n < 2 * per) {
    emit(*this, 0, n);
    return;
  }
  const std::size_t count = (n + per - 1) / per;
  // A wave of blocks at a time, formatted on every core, then appended (or handed to the
  // sink) in order; the buffers are reused, so the text is held once and a wave more (with
  // a sink, a wave). Handing a wave over while the next is formatted measured no faster
  // on 2 cores: the writing thread needs the same cores.
  const std::size_t wave = std::min<std::size_t>(
      count, 4 * static_cast<std::size_t>(std::max(1, tbb::info::default_concurrency())));
  std::vector<JsonText> parts(wave);
  for (std::size_t first = 0; first < count; first += wave) {
    const std::size_t k = std::min(count, first + wave) - first;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, k, 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) {
                          const std::size_t b = first + i;
                          parts[i].out.clear();
                          emit(parts[i], b * per, std::min(n, (b + 1) * per));
                        }
                      });
    if (sink) {
      finish();
      for (std::size_t i = 0; i < k; ++i) sink(parts[i].out);
      continue;
    }
    std::size_t size = out.size();
    for (std::size_t i = 0; i < k; ++i) size += parts[i].out.size();
    if (size > out.capacity()) out.reserve(std::max(size, out.capacity() + out.capacity() / 2));
    for (std::size_t i = 0; i < k; ++i) out += parts[i].out;
  }
}

void write_json_atomic(const std::string& path, const std::function<void(JsonText&)>& write) {
  AtomicWriter file(path);
  JsonText t;
  t.sink = [&file](const std::string& s) { file.append(s); };
  write(t);
  t.out += '\n';
  t.finish();
  file.commit();
}

}  // namespace qmotion::io
