// libFuzzer target for the command-line tools' strict CSV reader (apps/common/csv.hpp). The first
// byte picks the column constraint; the rest is the input. Every accepted row must hold only finite
// numbers within the constraint, line numbers must increase, and a stop with an empty error()
// must be the end of the input; an error message holds no control character.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0 || size > 1 << 16) return 0;
  const std::size_t min_columns = data[0] % 4;  // 0: no constraint
  const std::size_t max_columns = min_columns + data[0] / 64;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  fuzzypid::cli::CsvReader reader(in);
  if (min_columns != 0) reader.expect_columns(min_columns, max_columns);
  fuzzypid::cli::CsvRow row;
  std::size_t last_line = 0;
  while (reader.next(row)) {
    if (row.line <= last_line) std::abort();
    last_line = row.line;
    for (const double v : row.values)
      if (!std::isfinite(v)) std::abort();
    if (min_columns != 0 && (row.values.size() < min_columns || row.values.size() > max_columns))
      std::abort();
  }
  if (reader.error().empty() && !in.eof()) std::abort();
  // Messages quote the input escaped: no control character reaches the terminal.
  for (const char c : reader.error())
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) std::abort();
  return 0;
}
