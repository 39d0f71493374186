// Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "mjformation/render.hpp"

namespace mjf::render {
namespace {

struct PngError {
  std::jmp_buf jmp;
  char message[256];
};

void OnPngError(png_structp png, png_const_charp message) {
  auto* err = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(err->message, sizeof(err->message), "%s", message);
  std::longjmp(err->jmp, 1);
}

void OnPngWarning(png_structp, png_const_charp) {}

// libpng reports errors by longjmp: only trivially destructible locals live in this function.
// Returns false with a message in err->message.
bool WriteRows(std::FILE* file, const unsigned char* rgb, int width, int height, PngError* err) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, err, OnPngError, OnPngWarning);
  if (!png) {
    std::snprintf(err->message, sizeof(err->message), "png_create_write_struct failed");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(err->message, sizeof(err->message), "png_create_info_struct failed");
    return false;
  }
  if (setjmp(err->jmp)) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  // Renders are large flat areas: a fast level keeps snapshots cheap at little size cost.
  png_set_compression_level(png, 3);
  png_write_info(png, info);
  const size_t row = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    png_write_row(png, const_cast<png_bytep>(rgb + row * y));
  }
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

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
  PngError err{};
  const bool ok = WriteRows(file, rgb, width, height, &err);
  const bool flushed = std::fflush(file) == 0;
  const int saved_errno = errno;
  const bool closed = std::fclose(file) == 0;
  if (!ok || !flushed || !closed) {
    std::remove(tmp.c_str());
    throw std::runtime_error("WritePng " + path + ": " +
                             (ok ? std::string(std::strerror(saved_errno)) : err.message));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    std::remove(tmp.c_str());
    throw std::runtime_error("WritePng " + path + ": rename from " + tmp +
                             " failed: " + std::strerror(e));
  }
}

}  // namespace mjf::render
