#include "base/outcome.h"

#include <new>
#include <stdexcept>
#include <utility>

#include "base/error.h"
#include "base/interrupt.h"

namespace thaw {

namespace {

// Fields as "<length>:<bytes>", so that any bytes survive and the text is read back exactly.
void put(std::string& text, const std::string& field) {
  text += std::to_string(field.size());
  text += ':';
  text += field;
}

bool take(const std::string& text, std::size_t& at, std::string& field) {
  const std::size_t colon = text.find(':', at);
  if (colon == std::string::npos || colon == at || colon - at > 18) return false;
  std::size_t length = 0;
  for (std::size_t i = at; i < colon; ++i) {
    if (text[i] < '0' || text[i] > '9') return false;
    length = 10 * length + static_cast<std::size_t>(text[i] - '0');
  }
  if (length > text.size() - colon - 1) return false;
  field = text.substr(colon + 1, length);
  at = colon + 1 + length;
  return true;
}

}  // namespace

Outcome Outcome::user(std::string file, std::string where, std::string problem) {
  Outcome o;
  o.m_kind = Kind::user;
  o.m_file = std::move(file);
  o.m_where = std::move(where);
  o.m_problem = std::move(problem);
  return o;
}

Outcome Outcome::internal(std::string what) {
  Outcome o;
  o.m_kind = Kind::internal;
  o.m_problem = std::move(what);
  return o;
}

Outcome Outcome::interrupted() {
  Outcome o;
  o.m_kind = Kind::interrupted;
  o.m_problem = Interrupted().what();
  return o;
}

Outcome Outcome::of_current_exception() noexcept {
  try {
    try {
      throw;
    } catch (const UserError& e) {
      return user(e.file(), e.where(), e.problem());
    } catch (const Interrupted&) {
      return interrupted();
    } catch (const std::bad_alloc&) {
      return internal("out of memory");
    } catch (const std::exception& e) {
      return internal(e.what());
    } catch (...) {
      return internal("unknown exception");
    }
  } catch (...) {  // out of memory while copying the message
    Outcome o;
    o.m_kind = Kind::internal;
    return o;
  }
}

std::string Outcome::message() const {
  switch (m_kind) {
    case Kind::ok:
      return "";
    case Kind::user:
      return UserError(m_file, m_where, m_problem).what();
    case Kind::internal:
    case Kind::interrupted:
      return m_problem;
  }
  return m_problem;
}

int Outcome::exit_code() const noexcept {
  switch (m_kind) {
    case Kind::ok:
      return 0;
    case Kind::user:
      return kUserErrorExitCode;
    case Kind::internal:
      return kInternalErrorExitCode;
    case Kind::interrupted:
      return kInterruptedExitCode;
  }
  return kInternalErrorExitCode;
}

void Outcome::rethrow() const {
  switch (m_kind) {
    case Kind::ok:
      return;
    case Kind::user:
      throw UserError(m_file, m_where, m_problem);
    case Kind::internal:
      throw std::runtime_error(m_problem);
    case Kind::interrupted:
      throw Interrupted();
  }
}

std::string Outcome::to_text() const {
  std::string text;
  switch (m_kind) {
    case Kind::ok:
      return text;
    case Kind::user:
      text = "U";
      put(text, m_file);
      put(text, m_where);
      put(text, m_problem);
      return text;
    case Kind::internal:
      text = "X";
      put(text, m_problem);
      return text;
    case Kind::interrupted:
      return "I";
  }
  return text;
}

Outcome Outcome::from_text(const std::string& text) {
  if (text.empty()) return {};
  std::size_t at = 1;
  std::string a, b, c;
  if (text == "I") return interrupted();
  if (text[0] == 'X' && take(text, at, a) && at == text.size()) return internal(a);
  if (text[0] == 'U' && take(text, at, a) && take(text, at, b) && take(text, at, c) &&
      at == text.size())
    return user(a, b, c);
  return internal("not an outcome: \"" + escape_control_characters(text.substr(0, 80)) + "\"");
}

}  // namespace thaw
