// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <fcntl.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "mjformation/render.hpp"

extern char** environ;

namespace mjf::render {
namespace {

// The absolute path of `name` on PATH, or "" when it is not there.
std::string FindOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  size_t start = 0;
  while (start <= dirs.size()) {
    size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    std::string dir = dirs.substr(start, end - start);
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/" + name;
    struct stat st;
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
    start = end + 1;
  }
  return "";
}

std::string DirectoryOf(const std::string& path) {
  const size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string Number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  return buf;
}

// The video's folder must exist and be writable before ffmpeg is started.
void RequireWritableDirectory(const std::string& path) {
  const std::string dir = DirectoryOf(path);
  struct stat st;
  if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    throw std::runtime_error("VideoWriter " + path + ": directory " + dir + " does not exist");
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw std::runtime_error("VideoWriter " + path + ": directory " + dir + " is not writable");
  }
}

// ffmpeg reading raw RGB frames on stdin and writing H.264 in an mp4 at `output`.
std::vector<std::string> FfmpegArguments(const std::string& ffmpeg, int width, int height,
                                         double fps, const std::string& output) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  return {ffmpeg,       "-nostdin",  "-hide_banner",
          "-loglevel",  "error",     "-y",
          "-f",         "rawvideo",  "-pix_fmt",
          "rgb24",      "-s",        size,
          "-framerate", Number(fps), "-i",
          "pipe:0",     "-vf",       "pad=ceil(iw/2)*2:ceil(ih/2)*2",
          "-c:v",       "libx264",   "-pix_fmt",
          "yuv420p",    "-preset",   "veryfast",
          "-crf",       "20",        "-threads",
          "1",          "-movflags", "+faststart",
          "-f",         "mp4",       output};
}

}  // namespace

std::string FfmpegPath() { return FindOnPath("ffmpeg"); }

std::string FfmpegMissing() {
  return "ffmpeg not found on PATH; install ffmpeg (Debian/Ubuntu: apt install ffmpeg; conda: "
         "conda install -c conda-forge ffmpeg), or render without video";
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, double fps)
    : path_(path), tmp_path_(path + ".tmp"), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || !(fps > 0) || !std::isfinite(fps)) {
    throw std::runtime_error("VideoWriter " + path + ": invalid size " + std::to_string(width) +
                             "x" + std::to_string(height) + " or fps " + Number(fps));
  }
  const std::string ffmpeg = FfmpegPath();
  if (ffmpeg.empty()) throw std::runtime_error("VideoWriter " + path + ": " + FfmpegMissing());
  RequireWritableDirectory(path);

  // ffmpeg's messages go to a temporary file, read back when it fails.
  std::string err_template = "/tmp/mjf_ffmpeg_XXXXXX";
  err_fd_ = ::mkostemp(err_template.data(), O_CLOEXEC);
  if (err_fd_ < 0) {
    throw std::runtime_error("VideoWriter " + path +
                             ": cannot create a temporary file: " + std::strerror(errno));
  }
  err_path_ = err_template;

  // A socket rather than a pipe: send(MSG_NOSIGNAL) reports a dead ffmpeg as EPIPE instead of
  // raising SIGPIPE. Both ends close on exec so that ffmpegs started by other threads do not
  // inherit this one's input (and keep it open).
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
    const int e = errno;
    ::close(err_fd_);
    ::unlink(err_path_.c_str());
    throw std::runtime_error("VideoWriter " + path + ": socketpair failed: " + std::strerror(e));
  }

  std::vector<std::string> args = FfmpegArguments(ffmpeg, width, height, fps, tmp_path_);
  // -nostdin only stops ffmpeg's interactive keys; the frames still come on pipe:0.
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, sv[1], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err_fd_, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  const int rc = ::posix_spawn(&pid_, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(sv[1]);
  if (rc != 0) {
    ::close(sv[0]);
    ::close(err_fd_);
    ::unlink(err_path_.c_str());
    pid_ = -1;
    throw std::runtime_error("VideoWriter " + path + ": cannot start " + ffmpeg + ": " +
                             std::strerror(rc));
  }
  fd_ = sv[0];
  ::shutdown(fd_, SHUT_RD);
}

std::string VideoWriter::FfmpegMessage() const {
  std::string text;
  if (err_fd_ < 0) return text;
  char buf[4096];
  ssize_t n;
  off_t offset = 0;
  while (text.size() < 4000 && (n = ::pread(err_fd_, buf, sizeof(buf), offset)) > 0) {
    text.append(buf, static_cast<size_t>(n));
    offset += n;
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

void VideoWriter::AddFrame(const unsigned char* rgb_top_down) {
  if (closed_ || fd_ < 0) throw std::runtime_error("VideoWriter " + path_ + ": already closed");
  const size_t total = static_cast<size_t>(width_) * height_ * 3;
  size_t sent = 0;
  while (sent < total) {
    const ssize_t n = ::send(fd_, rgb_top_down + sent, total - sent, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      std::string message = "VideoWriter " + path_ + ": writing frame " + std::to_string(frames_) +
                            " to ffmpeg failed (" + std::strerror(e) + ")";
      ::close(fd_);
      fd_ = -1;
      int status = 0;
      if (pid_ > 0 && ::waitpid(pid_, &status, 0) == pid_) pid_ = -1;
      const std::string ff = FfmpegMessage();
      if (!ff.empty()) message += ": " + ff;
      throw std::runtime_error(message);
    }
    sent += static_cast<size_t>(n);
  }
  ++frames_;
}

void VideoWriter::Close() {
  if (closed_) return;
  closed_ = true;
  if (fd_ >= 0) {
    ::close(fd_);  // end of input: ffmpeg finishes the file
    fd_ = -1;
  }
  int status = 0;
  bool ok = true;
  std::string why;
  if (pid_ > 0) {
    pid_t w;
    do {
      w = ::waitpid(pid_, &status, 0);
    } while (w < 0 && errno == EINTR);
    pid_ = -1;
    if (w < 0) {
      ok = false;
      why = std::string("waitpid failed: ") + std::strerror(errno);
    } else if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
      ok = false;
      why = "ffmpeg exited with status " + std::to_string(WEXITSTATUS(status));
    } else if (WIFSIGNALED(status)) {
      ok = false;
      why = "ffmpeg killed by signal " + std::to_string(WTERMSIG(status));
    }
  } else {
    ok = false;
    why = "ffmpeg had already stopped";
  }
  if (ok && frames_ == 0) {
    ok = false;
    why = "no frames were written";
  }
  const std::string ff = FfmpegMessage();
  if (err_fd_ >= 0) {
    ::close(err_fd_);
    err_fd_ = -1;
    ::unlink(err_path_.c_str());
  }
  if (ok && std::rename(tmp_path_.c_str(), path_.c_str()) != 0) {
    ok = false;
    why = "rename from " + tmp_path_ + " failed: " + std::strerror(errno);
  }
  if (!ok) {
    ::unlink(tmp_path_.c_str());
    throw std::runtime_error("VideoWriter " + path_ + ": " + why + (ff.empty() ? "" : ": " + ff));
  }
}

VideoWriter::~VideoWriter() {
  try {
    Close();
  } catch (...) {
  }
}

}  // namespace mjf::render
