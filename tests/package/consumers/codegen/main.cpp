// Uses the installed codegen part: writes the paper's PID as a header and checks that it names the
// paper's proportional gain.
#include <cstdio>
#include <string>

#include <fuzzypid/codegen/export_header.hpp>

int main() {
  const std::string header =
      fuzzypid::codegen::export_header(fuzzypid::controller::paper_pid(), "paper", "consumer");
  std::printf("%zu bytes\n", header.size());
  return header.find("namespace paper") != std::string::npos ? 0 : 1;
}
