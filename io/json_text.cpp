// io/json_text.cpp
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

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
  // A wave of blocks at a time, their buffers reused: the text is held once and a wave
  // more, never twice.
  const std::size_t wave = std::min<std::size_t>(
      count, 4 * static_cast<std::size_t>(std::max(1, tbb::info::default_concurrency())));
  std::vector<JsonText> parts(wave);
  for (std::size_t first = 0; first < count; first += wave) {
    const std::size_t last = std::min(count, first + wave);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t b = r.begin(); b != r.end(); ++b) {
                          JsonText& t = parts[b - first];
                          t.out.clear();
                          emit(t, b * per, std::min(n, (b + 1) * per));
                        }
                      });
    std::size_t size = out.size();
    for (std::size_t b = first; b < last; ++b) size += parts[b - first].out.size();
    if (size > out.capacity()) out.reserve(std::max(size, out.capacity() + out.capacity() / 2));
    for (std::size_t b = first; b < last; ++b) out += parts[b - first].out;
  }
}

}  // namespace qmotion::io
