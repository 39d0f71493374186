// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// What every fuzz target shares: the input as text, a scratch file for parsers that read a
// path, and the one line that says what a target may do with an input. The contract under the
// fuzzer (docs/FUZZING.md): no crash, no hang, no sanitizer report, no unbounded allocation; a
// refusal is one of the project's input errors, each caught by its target. Any other exception
// escapes and libFuzzer reports it: a std::out_of_range is not a message a user can act on.
#ifndef MJFORMATION_TESTS_FUZZ_FUZZ_UTIL_HPP_
#define MJFORMATION_TESTS_FUZZ_FUZZ_UTIL_HPP_

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace mjf::fuzz {

inline std::string AsText(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// `text` cut at each line that is exactly `separator`: the pieces between.
inline std::vector<std::string> SplitAt(const std::string& text, const std::string& separator) {
  std::vector<std::string> parts(1);
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    if (line == separator) {
      parts.emplace_back();
    } else {
      parts.back() += line + (end < text.size() ? "\n" : "");
    }
    start = end + 1;
  }
  return parts;
}

// A folder of this process under $TMPDIR (or /tmp), made once and removed at exit: the parsers
// that read files read the input from there. Only files this target writes are ever in it.
class ScratchDir {
 public:
  ScratchDir() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/mjf_fuzz_XXXXXX";
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    if (!mkdtemp(buffer.data())) {
      std::perror("mjf fuzz: cannot make a scratch folder");
      std::abort();
    }
    path_ = buffer.data();
  }
  ~ScratchDir() {
    for (const auto& f : files_) std::remove(f.c_str());
    rmdir(path_.c_str());
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  // Writes `text` to NAME in the folder and returns its path.
  std::string Write(const std::string& name, const std::string& text) {
    const std::string file = path_ + "/" + name;
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if (!f || std::fwrite(text.data(), 1, text.size(), f) != text.size() || std::fclose(f) != 0) {
      std::perror(("mjf fuzz: cannot write " + file).c_str());
      std::abort();
    }
    bool known = false;
    for (const auto& p : files_) known |= p == file;
    if (!known) files_.push_back(file);
    return file;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<std::string> files_;
};

}  // namespace mjf::fuzz

#endif  // MJFORMATION_TESTS_FUZZ_FUZZ_UTIL_HPP_
