// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
//
// PNG snapshots through libpng's simplified write API (png_image), written to a temporary file
// and renamed, so a snapshot is whole or absent.
#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "mjformation/render.hpp"

namespace mjf::render {

void WritePng(const std::string& path, const unsigned char* rgb, int width, int height) {
  if (!rgb || width <= 0 || height <= 0) {
    throw std::runtime_error("WritePng " + path + ": invalid image (" + std::to_string(width) +
                             "x" + std::to_string(height) + ")");
  }
  const std::string tmp = path + ".tmp";
  std::FILE* file = std::fopen(tmp.c_str(), "wb");
  if (!file) {
    throw std::runtime_error("WritePng " + path + ": cannot open " + tmp +
                             " for writing: " + std::strerror(errno));
  }
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  // Renders are large flat areas: the fast setting keeps snapshots cheap at little size cost.
  image.flags = PNG_IMAGE_FLAG_FAST;
  const bool ok = png_image_write_to_stdio(&image, file, 0, rgb, 0, nullptr) != 0;
  const std::string png_message = ok ? "" : image.message;
  png_image_free(&image);
  const bool flushed = std::fflush(file) == 0;
  const int saved_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (!ok || !flushed || !closed) {
    std::remove(tmp.c_str());
    throw std::runtime_error("WritePng " + path + ": " +
                             (ok ? std::string(std::strerror(saved_errno)) : png_message));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    std::remove(tmp.c_str());
    throw std::runtime_error("WritePng " + path + ": rename from " + tmp +
                             " failed: " + std::strerror(e));
  }
}

}  // namespace mjf::render
