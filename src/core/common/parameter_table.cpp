#include "hex_slam/common/parameter_table.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <type_traits>
#include <sstream>
#include <stdexcept>

namespace hex_slam {
namespace {

// Levenshtein distance (insertions, deletions, substitutions) if it is at most `limit`, else
// limit + 1. Only the band of cells within
// `limit` of the diagonal can stay within it, and a row whose every cell exceeds it ends the
// search: the cost is |a|·(2·limit + 1), not |a|·|b|.
std::size_t EditDistanceWithin(const std::string& a, const std::string& b, std::size_t limit) {
  const std::size_t over = limit + 1;
  if ((a.size() > b.size() ? a.size() - b.size() : b.size() - a.size()) > limit) return over;
  std::vector<std::size_t> row(b.size() + 1, over);
  for (std::size_t j = 0; j <= std::min(b.size(), limit); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    const std::size_t first = i > limit ? i - limit : 1;
    const std::size_t last = std::min(b.size(), i + limit);
    std::size_t diagonal = row[first - 1];
    row[first - 1] = first == 1 && i <= limit ? i : over;
    std::size_t row_min = row[first - 1];
    for (std::size_t j = first; j <= last; ++j) {
      const std::size_t above = row[j];
      std::size_t d = diagonal + (a[i - 1] != b[j - 1]);
      if (above + 1 < d) d = above + 1;
      if (row[j - 1] + 1 < d) d = row[j - 1] + 1;
      row[j] = d < over ? d : over;
      if (row[j] < row_min) row_min = row[j];
      diagonal = above;
    }
    if (row_min > limit) return over;
  }
  return row[b.size()];
}

bool ParseBool(const std::string& text, bool* out) {
  if (text == "true" || text == "True" || text == "TRUE" || text == "1") {
    *out = true;
  } else if (text == "false" || text == "False" || text == "FALSE" || text == "0") {
    *out = false;
  } else {
    return false;
  }
  return true;
}

bool ParseInt(const std::string& text, std::int64_t* out) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || *end != '\0') return false;
  *out = value;
  return true;
}

bool ParseDouble(const std::string& text, double* out) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || *end != '\0' || !std::isfinite(value)) return false;
  *out = value;
  return true;
}

}  // namespace

void ParameterTable::Insert(const std::string& key, Field field, const std::string& help) {
  if (!entries_.emplace(key, Entry{field, help}).second) {
    throw std::logic_error("ParameterTable: key registered twice: " + key);
  }
  longest_key_ = std::max(longest_key_, key.size());
}

void ParameterTable::Add(const std::string& key, bool* field, const std::string& help) {
  Insert(key, field, help);
}
void ParameterTable::Add(const std::string& key, int* field, const std::string& help) {
  Insert(key, field, help);
}
void ParameterTable::Add(const std::string& key, std::int64_t* field, const std::string& help) {
  Insert(key, field, help);
}
void ParameterTable::Add(const std::string& key, double* field, const std::string& help) {
  Insert(key, field, help);
}
void ParameterTable::Add(const std::string& key, std::string* field, const std::string& help) {
  Insert(key, field, help);
}

void ParameterTable::Merge(const ParameterTable& other) {
  for (const auto& [key, entry] : other.entries_) Insert(key, entry.field, entry.help);
}

std::string ParameterTable::Set(const std::string& key, const std::string& text) {
  const auto it = entries_.find(key);
  if (it == entries_.end()) return UnknownKeyMessage(key);
  const std::string bad = "parameter '" + key + "': cannot parse '" + text + "' as ";
  return std::visit(
      [&](auto* field) -> std::string {
        using T = std::remove_pointer_t<decltype(field)>;
        if constexpr (std::is_same_v<T, bool>) {
          return ParseBool(text, field) ? "" : bad + "a boolean";
        } else if constexpr (std::is_same_v<T, std::string>) {
          *field = text;
          return "";
        } else if constexpr (std::is_same_v<T, double>) {
          return ParseDouble(text, field) ? "" : bad + "a number";
        } else {
          std::int64_t value = 0;
          if (!ParseInt(text, &value)) return bad + "an integer";
          if (value < std::numeric_limits<T>::min() || value > std::numeric_limits<T>::max()) {
            return bad + "an integer in range";
          }
          *field = static_cast<T>(value);
          return "";
        }
      },
      it->second.field);
}

std::string ParameterTable::Get(const std::string& key) const {
  const auto it = entries_.find(key);
  if (it == entries_.end()) return "";
  return std::visit(
      [](auto* field) -> std::string {
        using T = std::remove_pointer_t<decltype(field)>;
        if constexpr (std::is_same_v<T, bool>) {
          return *field ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::string>) {
          return *field;
        } else {
          std::ostringstream s;
          s << *field;
          return s.str();
        }
      },
      it->second.field);
}

std::string ParameterTable::Help(const std::string& key) const {
  const auto it = entries_.find(key);
  return it == entries_.end() ? "" : it->second.help;
}

std::string ParameterTable::ClosestKey(const std::string& key) const {
  // Twice the longest name is no misspelling of one (and a corrupt file's kilobyte-long "key"
  // would cost a quadratic comparison with every name).
  if (key.size() > 2 * longest_key_) return "";
  // A misspelling is a few edits away; anything farther is a different word.
  const std::size_t most = std::max<std::size_t>(2, key.size() / 4);
  std::string best;
  std::size_t best_distance = most + 1;
  for (const auto& entry : entries_) {
    if (best_distance == 0) break;
    const std::size_t d = EditDistanceWithin(key, entry.first, best_distance - 1);
    if (d < best_distance) {
      best_distance = d;
      best = entry.first;
    }
  }
  return best;
}

std::string ParameterTable::UnknownKeyMessage(const std::string& key) const {
  const std::string closest = ClosestKey(key);
  return "unknown parameter '" + key + "'" +
         (closest.empty() ? std::string() : " (did you mean '" + closest + "'?)");
}

std::vector<std::string> ParameterTable::Keys() const {
  std::vector<std::string> keys;
  for (const auto& entry : entries_) keys.push_back(entry.first);
  return keys;
}

std::vector<std::string> ParameterTable::Apply(const std::map<std::string, std::string>& values) {
  // Past a few unknown keys the input is not a parameter file of ours (another tool's YAML, a
  // corrupt file): the rest are named without looking for the nearest known key.
  constexpr int kSuggestedUnknownKeys = 8;
  int unknown = 0;
  std::vector<std::string> errors;
  for (const auto& [key, text] : values) {
    if (!Has(key) && ++unknown > kSuggestedUnknownKeys) {
      errors.push_back("unknown parameter '" + key + "'");
      continue;
    }
    const std::string error = Set(key, text);
    if (!error.empty()) errors.push_back(error);
  }
  return errors;
}

}  // namespace hex_slam
