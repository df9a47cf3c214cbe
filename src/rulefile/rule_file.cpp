// File access and format dispatch for the rule-file readers.
#include "fuzzypid/io/rule_file.hpp"

#include <fstream>
#include <sstream>

namespace fuzzypid::io {

std::string LoadError::to_string() const {
  return line > 0 ? file + ":" + std::to_string(line) + ": " + message : file + ": " + message;
}

namespace {

bool read_file(const std::string& path, std::string& text, LoadError& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = LoadError{path, 0, "cannot open file"};
    return false;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  text = buffer.str();
  return true;
}

bool ends_with(const std::string& s, const char* suffix) {
  const std::string t(suffix);
  return s.size() >= t.size() && s.compare(s.size() - t.size(), t.size(), t) == 0;
}

}  // namespace

bool load_fll(const std::string& path, Model& model, LoadError& error, const LoadOptions& options) {
  std::string text;
  return read_file(path, text, error) && parse_fll(text, path, model, error, options);
}

bool load_fis(const std::string& path, Model& model, LoadError& error, const LoadOptions& options) {
  std::string text;
  return read_file(path, text, error) && parse_fis(text, path, model, error, options);
}

bool load_rule_file(const std::string& path, Model& model, LoadError& error,
                    const LoadOptions& options) {
  if (ends_with(path, ".fis")) return load_fis(path, model, error, options);
  if (ends_with(path, ".fll")) return load_fll(path, model, error, options);
  error = LoadError{path, 0, "unknown rule file extension (expected .fis or .fll)"};
  return false;
}

}  // namespace fuzzypid::io
