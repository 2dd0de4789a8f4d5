// The shape rules of a tabulated spectrum; see wavelength_table.h.
#include "render/media/wavelength_table.h"

#include <cmath>
#include <sstream>

#include "render/spectrum/sampled_spectrum.h"

namespace thaw::render::media {

std::string table_number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

std::optional<TableProblem> wavelength_table_problem(const std::vector<double>& nm,
                                                     const std::vector<double>& values,
                                                     const TableValues& rule) {
  if (nm.size() != values.size())
    return TableProblem{"", "wavelength_nm has " + std::to_string(nm.size()) + " entries but " +
                                rule.name + " has " + std::to_string(values.size())};
  if (nm.size() < 2) return TableProblem{"", "a table needs at least two rows"};
  for (std::size_t i = 0; i + 1 < nm.size(); ++i)
    if (!(nm[i + 1] > nm[i]))
      return TableProblem{"wavelength_nm",
                          "must be strictly increasing (row " + std::to_string(i + 1) + ")"};
  if (nm.front() > kLambdaMinNm || nm.back() < kLambdaMaxNm)
    return TableProblem{"wavelength_nm",
                        "covers " + table_number(nm.front()) + "-" + table_number(nm.back()) +
                            " nm but must cover the rendered range " + table_number(kLambdaMinNm) +
                            "-" + table_number(kLambdaMaxNm) + " nm"};
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]) || values[i] < rule.minimum)
      return TableProblem{rule.name, "entry " + std::to_string(i) + " must be " +
                                         rule.minimum_words + " (got " + table_number(values[i]) +
                                         ")"};
  return std::nullopt;
}

}  // namespace thaw::render::media
