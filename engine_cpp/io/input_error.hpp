// The one exception type for bad input files: it names the file and line.
#pragma once

#include <stdexcept>
#include <string>

namespace xroute {

class InputError : public std::runtime_error {
 public:
  // line 0 = the file as a whole (missing, unreadable, inconsistent).
  InputError(std::string path, int line, const std::string& message)
      : std::runtime_error(format(path, line, message)),
        path_(std::move(path)),
        line_(line),
        message_(message) {}

  const std::string& path() const { return path_; }
  int line() const { return line_; }
  const std::string& message() const { return message_; }

 private:
  static std::string format(const std::string& path, int line, const std::string& message) {
    return line > 0 ? path + ":" + std::to_string(line) + ": " + message : path + ": " + message;
  }

  std::string path_;
  int line_;
  std::string message_;
};

}  // namespace xroute
