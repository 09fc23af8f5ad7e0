// io/src/isolated.cpp
#include "isolated.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <exception>
#include <qmotion/kernel/error.hpp>

namespace qmotion::io {
namespace {

// The child's answer: a tag, then (ok) the work's bytes or (error) the code and message,
// then the end mark. An answer without its end mark is a child that died writing.
constexpr char kOk = 'O', kError = 'E';
constexpr char kEnd[] = "qmotion-end";
constexpr std::size_t kEndSize = sizeof kEnd - 1;

bool write_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

void error(std::string& tag, std::string& body, Errc code, const std::string& message) {
  tag.assign(1, kError);
  body.clear();
  ByteWriter w(body);
  w.put(static_cast<int>(code));
  w.put_string(message);
}

std::string in_this_process(const std::function<void(std::string&)>& work) {
  std::string answer;
  work(answer);
  return answer;
}

[[noreturn]] void child(int fd, const std::string& path,
                        const std::function<void(std::string&)>& work) {
  // A crash ends this process quietly: the default action for the signals (not a
  // sanitizer's or fuzzer's report, whose handlers the fork copied) and no core file.
  for (const int s : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) ::signal(s, SIG_DFL);
  // Standard output is the caller's (JSON, G-code): what the parser prints goes nowhere,
  // and so do the copies of the caller's unwritten stdout buffers, should the parser flush
  // them (OpenCASCADE does), which would write the caller's text twice.
  if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) {
    ::dup2(null, STDOUT_FILENO);
    ::close(null);
  }
  const struct rlimit no_core = {0, 0};
  ::setrlimit(RLIMIT_CORE, &no_core);
  std::string tag(1, kOk), body;
  try {
    work(body);
  } catch (const Error& e) {
    error(tag, body, e.code(), e.what());
  } catch (const std::exception& e) {
    error(tag, body, Errc::invalid_input, path + ": " + e.what());
  } catch (...) {
    error(tag, body, Errc::invalid_input, path + ": the reader failed");
  }
  const bool sent = write_all(fd, tag.data(), tag.size()) &&
                    write_all(fd, body.data(), body.size()) && write_all(fd, kEnd, kEndSize);
  ::_exit(sent ? 0 : 1);
}

}  // namespace

std::size_t ByteReader::count(std::size_t item_bytes) {
  const auto n = get<std::size_t>();
  if (item_bytes > 0 && n > (in_.size() - at_) / item_bytes)
    throw Error(Errc::internal, "an isolated reader's answer is cut short");
  return n;
}

const char* ByteReader::take(std::size_t n) {
  if (n > in_.size() - at_) throw Error(Errc::internal, "an isolated reader's answer is cut short");
  const char* p = in_.data() + at_;
  at_ += n;
  return p;
}

std::string run_isolated(const std::string& path, const char* format,
                         const std::function<void(std::string& answer)>& work) {
  // Without a pipe or a child (out of processes or memory), the work runs here.
  int fds[2];  // close-on-exec: a program another thread of the caller starts keeps no end
  if (::pipe2(fds, O_CLOEXEC) != 0) return in_this_process(work);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return in_this_process(work);
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(fds[1], path, work);
  }
  ::close(fds[1]);
  std::string answer;
  char buf[1 << 16];
  for (;;) {
    const ssize_t r = ::read(fds[0], buf, sizeof buf);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) break;
    answer.append(buf, static_cast<std::size_t>(r));
  }
  ::close(fds[0]);
  int status = 0;
  pid_t waited = -1;
  do waited = ::waitpid(pid, &status, 0);
  while (waited < 0 && errno == EINTR);
  const bool whole = answer.size() >= 1 + kEndSize &&
                     answer.compare(answer.size() - kEndSize, kEndSize, kEnd) == 0;
  if (!whole) {
    std::string how = "it stopped without an answer";
    if (waited == pid && WIFSIGNALED(status)) {
      const int sig = WTERMSIG(status);
      const char* name = ::strsignal(sig);
      how =
          "it died of signal " + std::to_string(sig) + (name ? std::string(" (") + name + ")" : "");
      if (sig == SIGKILL) how += ", perhaps for want of memory";
    } else if (waited == pid && WIFEXITED(status)) {
      how = "it exited with status " + std::to_string(WEXITSTATUS(status)) + " without an answer";
    }
    throw Error(Errc::invalid_input, path + ": a damaged " + format +
                                         " file: OpenCASCADE's reader crashed on it (in a "
                                         "separate process; " +
                                         how + ")");
  }
  answer.resize(answer.size() - kEndSize);
  if (answer[0] == kError) {
    ByteReader in(answer);
    (void)in.get<char>();
    const int code = in.get<int>();
    throw Error(static_cast<Errc>(code), in.get_string());
  }
  if (answer[0] != kOk)
    throw Error(Errc::internal, path + ": an isolated reader's answer is garbled");
  answer.erase(0, 1);
  return answer;
}

}  // namespace qmotion::io
