#pragma once
// A Log whose lines a test reads back: it writes into an anonymous temporary
// file (std::tmpfile, removed when closed), and text() returns everything
// written so far.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "kinetofem/core/log.hpp"

namespace kinetofem::testing {

class CapturedLog {
 public:
  CapturedLog() : file_(std::tmpfile()), log_(Log::Level::Normal, file_) {
    if (!file_) throw std::runtime_error("CapturedLog: std::tmpfile failed");
  }
  ~CapturedLog() { std::fclose(file_); }
  CapturedLog(const CapturedLog&) = delete;
  CapturedLog& operator=(const CapturedLog&) = delete;

  const Log& log() const { return log_; }
  std::string text() const {
    std::fflush(file_);
    std::rewind(file_);
    std::string text;
    char buffer[4096];
    for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, file_)) > 0;) text.append(buffer, n);
    std::fseek(file_, 0, SEEK_END);
    return text;
  }

 private:
  std::FILE* file_;
  Log log_;
};

}  // namespace kinetofem::testing
