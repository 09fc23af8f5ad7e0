// io/src/progress.cpp
#include <algorithm>
#include <chrono>
#include <memory>
#include <qmotion/io/progress.hpp>

namespace qmotion::io {
namespace {

ProgressSink& sink() {
  static ProgressSink s;
  return s;
}

}  // namespace

void set_progress_sink(ProgressSink s) { sink() = std::move(s); }

void report_progress(const std::string& stage, double fraction) {
  if (sink()) sink()(stage, std::clamp(fraction, 0.0, 1.0));
}

ProgressSink terminal_progress_bar(std::FILE* out, double delay) {
  using Clock = std::chrono::steady_clock;
  struct State {
    std::string stage;
    Clock::time_point start, last;
    bool drawn = false;
  };
  auto st = std::make_shared<State>();
  return [out, delay, st](const std::string& stage, double f) {
    const auto now = Clock::now();
    const auto erase = [&] {
      if (st->drawn) std::fprintf(out, "\r%*s\r", 79, "");
      std::fflush(out);
      st->drawn = false;
    };
    if (stage != st->stage) {  // a new stage
      erase();
      st->stage = stage;
      st->start = now;
      st->last = now - std::chrono::seconds(1);
    }
    if (f >= 1) {
      erase();
      st->stage.clear();
      return;
    }
    const double elapsed = std::chrono::duration<double>(now - st->start).count();
    if (elapsed < delay || now - st->last < std::chrono::milliseconds(100)) return;
    st->last = now;
    const int width = 30, filled = static_cast<int>(f * width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(static_cast<std::size_t>(width), ' ');
    std::fprintf(out, "\rqmotion: %.30s [%s] %3d%%", stage.c_str(), bar.c_str(),
                 static_cast<int>(f * 100));
    std::fflush(out);
    st->drawn = true;
  };
}

}  // namespace qmotion::io
