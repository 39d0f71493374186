// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#ifndef MJFORMATION_TESTS_RUNNER_PNG_UTIL_HPP_
#define MJFORMATION_TESTS_RUNNER_PNG_UTIL_HPP_

#include <png.h>

#include <string>
#include <vector>

namespace mjf::testing {

// Reads a PNG as 8-bit RGB (libpng's simplified API); empty when it cannot be read.
inline std::vector<unsigned char> ReadPng(const std::string& path, int* width, int* height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  std::vector<unsigned char> pixels;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return pixels;
  image.format = PNG_FORMAT_RGB;
  pixels.resize(PNG_IMAGE_SIZE(image));
  png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr);
  *width = static_cast<int>(image.width);
  *height = static_cast<int>(image.height);
  return pixels;
}

}  // namespace mjf::testing

#endif  // MJFORMATION_TESTS_RUNNER_PNG_UTIL_HPP_
