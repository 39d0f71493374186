// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// The fuzz targets without libFuzzer (GCC builds, the regular and the sanitizer test runs): every
// file of the given folders (and files) goes through the target once, the checked-in seeds and
// the regression cases of earlier findings. A crash, a sanitizer report or an exception the
// target does not catch fails the test; so does finding no input at all (a test that ran nothing
// would pass on anything).
#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

void Collect(const std::string& path, std::vector<std::string>* files) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) {
    std::fprintf(stderr, "corpus: %s: no such file or folder\n", path.c_str());
    return;
  }
  if (!S_ISDIR(st.st_mode)) {
    files->push_back(path);
    return;
  }
  DIR* dir = opendir(path.c_str());
  if (!dir) return;
  std::vector<std::string> names;
  while (const dirent* e = readdir(dir)) {
    const std::string name = e->d_name;
    if (name != "." && name != ".." && name != "README.md") names.push_back(path + "/" + name);
  }
  closedir(dir);
  std::sort(names.begin(), names.end());  // the same order on every machine
  for (const auto& n : names) Collect(n, files);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  for (int k = 1; k < argc; ++k) Collect(argv[k], &files);
  if (files.empty()) {
    std::fprintf(stderr, "corpus: no inputs found: nothing was tested\n");
    return 1;
  }
  for (const auto& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::fprintf(stderr, "corpus: %s\n", file.c_str());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("corpus: %zu inputs ran clean\n", files.size());
  return 0;
}
