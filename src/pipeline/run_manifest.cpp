#include "src/pipeline/run_manifest.h"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "src/common/atomic_file.h"
#include "src/pipeline/content_hash.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

ContentHash& ContentHash::add(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return add(std::string_view(buf));
}

ContentHash& ContentHash::add_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return add(std::string_view("<missing>"));
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    const auto n = in.gcount();
    for (std::streamsize i = 0; i < n; ++i) {
      m_state ^= static_cast<unsigned char>(buf[i]);
      m_state *= 0x100000001b3ULL;
    }
  }
  return add(std::string_view("<eof>"));
}

std::string ContentHash::hex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(m_state));
  return buf;
}

RunManifest::RunManifest(fs::path file) : m_file(std::move(file)) {
  std::ifstream in(m_file);
  if (!in) return;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& [name, s] : j.at("stages").items()) {
      Stage stage;
      stage.input_hash = s.at("input_hash").get<std::string>();
      stage.complete = s.at("complete").get<bool>();
      for (const auto& item : s.at("items")) stage.items.insert(item.get<std::string>());
      m_stages[name] = std::move(stage);
    }
  } catch (const nlohmann::json::exception&) {
    m_stages.clear();
  }
}

bool RunManifest::begin_stage(const std::string& stage, const std::string& input_hash) {
  Stage& s = m_stages[stage];
  if (s.input_hash == input_hash) return s.complete;
  s = Stage{input_hash, false, {}};
  save();
  return false;
}

bool RunManifest::item_done(const std::string& stage, const std::string& item) const {
  const auto it = m_stages.find(stage);
  return it != m_stages.end() && it->second.items.count(item) > 0;
}

void RunManifest::mark_item_done(const std::string& stage, const std::string& item) {
  m_stages[stage].items.insert(item);
  save();
}

void RunManifest::mark_stage_complete(const std::string& stage) {
  m_stages[stage].complete = true;
  save();
}

void RunManifest::clear() {
  m_stages.clear();
  save();
}

std::string RunManifest::stage_hash(const std::string& stage) const {
  const auto it = m_stages.find(stage);
  return it == m_stages.end() ? std::string() : it->second.input_hash;
}

void RunManifest::save() const {
  nlohmann::json j;
  j["format"] = "thaw-run/1";
  j["stages"] = nlohmann::json::object();
  for (const auto& [name, s] : m_stages)
    j["stages"][name] = {{"input_hash", s.input_hash}, {"complete", s.complete}, {"items", s.items}};
  write_file_atomic(m_file, j.dump(1) + "\n");
}

}  // namespace thaw::pipeline
