#include "src/pipeline/run_manifest.h"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string_view>

#include "base/atomic_file.h"
#include "base/check.h"
#include "base/fnv_hash.h"
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
    m_state = fnv1a_64(std::string_view(buf, static_cast<std::size_t>(in.gcount())), m_state);
  }
  return add(std::string_view("<eof>"));
}

std::string ContentHash::hex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(m_state));
  return buf;
}

RunManifest::RunManifest(fs::path file)
    : m_file(std::move(file)), m_items_dir(m_file.parent_path() / "run_items") {
  std::ifstream in(m_file);
  if (!in) return;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& [name, s] : j.at("stages").items()) {
      Stage stage;
      stage.input_hash = s.at("input_hash").get<std::string>();
      stage.complete = s.at("complete").get<bool>();
      m_stages[name] = std::move(stage);
    }
  } catch (const nlohmann::json::exception&) {
    m_stages.clear();
  }
}

bool RunManifest::begin_stage(const std::string& stage, const std::string& input_hash) {
  Stage& s = m_stages[stage];
  if (s.input_hash == input_hash) return s.complete;
  s = Stage{input_hash, false};
  // Forget the items outright: an output rewritten under the new inputs by a run killed before
  // it marked the item must not count as done if the inputs change back.
  std::error_code ec;
  fs::remove_all(m_items_dir / stage, ec);
  save();
  return false;
}

bool RunManifest::is_complete(const std::string& stage, const std::string& input_hash) const {
  const auto it = m_stages.find(stage);
  return it != m_stages.end() && it->second.input_hash == input_hash && it->second.complete;
}

fs::path RunManifest::item_file(const std::string& stage, const std::string& item) const {
  return m_items_dir / stage / item;
}

bool RunManifest::item_done(const std::string& stage, const std::string& item) const {
  const auto it = m_stages.find(stage);
  if (it == m_stages.end() || it->second.input_hash.empty()) return false;
  // Done under these very inputs: the file holds the hash it was finished under.
  std::ifstream in(item_file(stage, item));
  std::string hash;
  return in && std::getline(in, hash) && hash == it->second.input_hash;
}

void RunManifest::mark_item_done(const std::string& stage, const std::string& item,
                                 const std::string& note) {
  const auto it = m_stages.find(stage);
  THAW_CHECK(it != m_stages.end(), "mark_item_done before begin_stage");
  THAW_CHECK(note.find('\n') == std::string::npos, "an item's note is one line");
  ensure_directory(item_file(stage, item).parent_path());
  write_file_atomic(item_file(stage, item),
                    it->second.input_hash + "\n" + (note.empty() ? "" : note + "\n"));
}

void RunManifest::mark_stage_complete(const std::string& stage) {
  m_stages[stage].complete = true;
  save();
}

void RunManifest::clear() {
  m_stages.clear();
  std::error_code ec;
  fs::remove_all(m_items_dir, ec);
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
    j["stages"][name] = {{"input_hash", s.input_hash}, {"complete", s.complete}};
  write_file_atomic(m_file, j.dump(1) + "\n");
}

}  // namespace thaw::pipeline
