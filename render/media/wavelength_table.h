// The shape of a tabulated spectrum (an index table, an absorption table): rows paired, at least
// two, wavelengths strictly increasing and covering the rendered range, values finite and within
// the quantity's limit. One rule for every table a medium can hold, so the index model and the
// absorption report the same problems in the same words. Knows nothing of files: the caller turns
// a problem into its UserError with the table's key.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace thaw::render::media {

struct TableProblem {
  std::string key;      // below the table's own key: "", "wavelength_nm" or the values' name
  std::string problem;  // the sentence for UserError
};

struct TableValues {
  std::string name;           // "n", "per_m"
  double minimum;             // the smallest physical value (1 for an index, 0 for absorption)
  std::string minimum_words;  // e.g. "a finite number >= 1"
};

std::optional<TableProblem> wavelength_table_problem(const std::vector<double>& wavelength_nm,
                                                     const std::vector<double>& values,
                                                     const TableValues& rule);

/// A number as the messages print it (6 significant digits).
std::string table_number(double v);

}  // namespace thaw::render::media
