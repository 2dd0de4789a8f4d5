#include "sim/format/interface_history.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/format/json_error.h"
#include "base/text_file.h"

namespace thaw::sim {

const char* const kInterfacesCsvHeader =
    "step,time_s,inner_radius_m,outer_radius_m,liquid_volume_m3,ice_volume_m3,"
    "energy_balance_error";

std::string format_interfaces_csv(const std::vector<InterfaceRecord>& rows) {
  std::string out = std::string(kInterfacesCsvHeader) + "\n";
  char buf[512];
  for (const auto& r : rows) {
    std::snprintf(buf, sizeof buf, "%ld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", r.step, r.time_s,
                  r.inner_radius_m, r.outer_radius_m, r.liquid_volume_m3, r.ice_volume_m3,
                  r.energy_balance_error);
    out += buf;
  }
  return out;
}

void write_interfaces_csv(const std::filesystem::path& file,
                          const std::vector<InterfaceRecord>& rows) {
  write_file_atomic(file, format_interfaces_csv(rows));
}

namespace {
std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}
}  // namespace

std::vector<InterfaceRecord> read_interfaces_csv(const std::filesystem::path& file) {
  const std::string name = file.string();
  // text_file.h: a directory, a device or a pipe is refused by name before it is opened
  std::istringstream in(read_text_file(file, "a CSV file"));
  std::string line;
  if (!std::getline(in, line)) throw UserError(name, "line 1", "empty file, expected a CSV header");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const auto header = split_commas(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  const char* required[] = {"step",
                            "time_s",
                            "inner_radius_m",
                            "outer_radius_m",
                            "liquid_volume_m3",
                            "ice_volume_m3",
                            "energy_balance_error"};
  for (const char* key : required)
    if (!column.count(key))
      throw UserError(name, "line 1", std::string("missing column '") + key + "'");

  std::vector<InterfaceRecord> rows;
  long line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const auto cells = split_commas(line);
    const std::string where = "line " + std::to_string(line_no);
    if (cells.size() != header.size())
      throw UserError(name, where,
                      "expected " + std::to_string(header.size()) + " columns, got " +
                          std::to_string(cells.size()));
    auto number = [&](const char* key) {
      const std::string& text = cells[column[key]];
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size())
        throw UserError(name, where + ", column '" + key + "'", "not a number: '" + text + "'");
      if (!std::isfinite(v))
        throw UserError(name, where + ", column '" + key + "'",
                        "must be finite, got '" + text + "'");
      return v;
    };
    InterfaceRecord r;
    const double step = number("step");
    // 1e15 keeps the conversion to long defined (found by fuzz_interfaces_csv: 7.8e82 as a step).
    if (step < 0 || step != std::floor(step) || step > 1e15)
      throw UserError(name, where + ", column 'step'", "must be an integer in [0, 1e15]");
    r.step = static_cast<long>(step);
    r.time_s = number("time_s");
    r.inner_radius_m = number("inner_radius_m");
    r.outer_radius_m = number("outer_radius_m");
    r.liquid_volume_m3 = number("liquid_volume_m3");
    r.ice_volume_m3 = number("ice_volume_m3");
    r.energy_balance_error = number("energy_balance_error");
    for (auto [key, v] : {std::pair{"time_s", r.time_s},
                          {"inner_radius_m", r.inner_radius_m},
                          {"outer_radius_m", r.outer_radius_m}})
      if (v < 0)
        throw UserError(name, where + ", column '" + std::string(key) + "'",
                        "must not be negative");
    if (r.inner_radius_m > r.outer_radius_m)
      throw UserError(name, where, "inner_radius_m is larger than outer_radius_m");
    if (!rows.empty() && !(r.time_s > rows.back().time_s))
      throw UserError(name, where + ", column 'time_s'", "times must increase");
    rows.push_back(r);
  }
  if (rows.empty()) throw UserError(name, "", "no data rows");
  return rows;
}

ShellGeometry read_shell_geometry(const std::filesystem::path& summary_json) {
  const std::string name = summary_json.string();
  // A directory used to throw basic_filebuf's "Is a directory" (exit 3): read_text_file names it.
  const std::string text = read_text_file(summary_json, "a JSON file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw UserError(name, "", "malformed JSON: " + json_problem(e));
  }
  ShellGeometry g;
  try {
    const auto& p = j.at("parameters");
    const std::string geometry = p.at("simulation").at("geometry").get<std::string>();
    if (!parse_geometry(geometry, g.geometry))
      throw UserError(name, "parameters.simulation.geometry",
                      "unknown geometry '" + geometry + "'");
    const auto& shell = p.at("shell");
    if (g.geometry == Geometry::cylinder) g.length_m = shell.at("length_m").get<double>();
    if (g.geometry == Geometry::planar) {
      g.lateral_size_m = shell.at("lateral_size_m").get<double>();
      g.planar_symmetric = p.at("inner_boundary").at("kind").get<std::string>() == "symmetry";
    }
  } catch (const nlohmann::json::exception& e) {
    throw UserError(name, "parameters", "missing or mistyped field: " + json_problem(e));
  }
  for (double v : {g.length_m, g.lateral_size_m})
    if (!std::isfinite(v) || v < 0)
      throw UserError(name, "parameters.shell", "length/lateral size must be finite and >= 0");
  return g;
}

}  // namespace thaw::sim
