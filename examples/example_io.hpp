// What the examples share besides dstrans: strict command-line numbers and a PNG written whole or not at
// all. An engine that copies an example copies this file with it (it needs stb_image_write.h, whose
// implementation the example's main.cpp holds).
//
//   int step = 3;
//   std::string out = "engine.png";
//   if (int stop = example::engine_arguments(argc, argv, "engine", usage, step, out); stop >= 0) return stop;
//   std::string error;
//   if (!example::write_png(out, w, h, pixels, true, error)) { std::fprintf(stderr, "%s\n", error.c_str()); return 1; }
#pragma once

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include <stb/stb_image_write.h>

namespace example {

// `text` as a whole number in [lo, hi] into `out`; otherwise a message on stderr and false.
inline bool whole_number(const char* option, const char* text, int lo, int hi, int& out) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || v < lo || v > hi) {
    std::fprintf(stderr, "%s must be a whole number from %d to %d, not '%s'\n", option, lo, hi, text);
    return false;
  }
  out = int(v);
  return true;
}

// The engines' command line: [--step 0|1|2|3|4] [--out image.png], and [--validate] where `validate` is
// given. Returns -1 to go on, or the exit code to stop with (0 after --help, 2 after a bad argument).
inline int engine_arguments(int argc, char** argv, const char* name, const char* usage, int& step, std::string& out,
                            bool* validate = nullptr) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(usage, stdout);
      return 0;
    }
    if ((a == "--step" || a == "--out") && i + 1 >= argc) {
      std::fprintf(stderr, "%s: %s needs a value\n%s", name, a.c_str(), usage);
      return 2;
    }
    if (validate && a == "--validate") {
      *validate = true;
    } else if (a == "--step") {
      if (!whole_number("--step", argv[++i], 0, 4, step)) return 2;
    } else if (a == "--out") {
      out = argv[++i];
    } else {
      std::fprintf(stderr, "%s: unknown argument '%s'\n%s", name, a.c_str(), usage);
      return 2;
    }
  }
  return -1;
}

// Writes a `width` x `height` RGBA8 image (rows from the top; `flip`: from the bottom, as GL reads them)
// to `path` through a new file beside it, renamed over `path` only once written and closed, so that a
// full disk leaves no half image and nothing but a plain file is ever replaced.
inline bool write_png(const std::string& path, int width, int height, const void* rgba, bool flip, std::string& error) {
  struct stat st {};
  if (lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    error = path + ": exists and is not a plain file (not written through or replaced)";
    return false;
  }
  std::string bytes;
  stbi_flip_vertically_on_write(flip ? 1 : 0);
  const int made = stbi_write_png_to_func(
      [](void* context, void* data, int size) { static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size)); },
      &bytes, width, height, 4, rgba, width * 4);
  const std::string temporary = path + ".tmp-" + std::to_string(getpid());
  std::FILE* f = made ? std::fopen(temporary.c_str(), "wbx") : nullptr;
  if (!f) {
    error = path + ": cannot write: " + (made ? std::strerror(errno) : "the image could not be encoded");
    return false;
  }
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  const int written_errno = errno;
  if (std::fclose(f) != 0 || !written || std::rename(temporary.c_str(), path.c_str()) != 0) {
    error = path + ": cannot write: " + std::strerror(written ? errno : written_errno);
    std::remove(temporary.c_str());
    return false;
  }
  return true;
}

}  // namespace example
