// A registry of named options bound to struct fields: the one loader behind rosparam, YAML files
// and command-line overrides. Unknown keys and unparsable values are errors naming the key.
#ifndef HEX_SLAM_COMMON_PARAMETER_TABLE_H_
#define HEX_SLAM_COMMON_PARAMETER_TABLE_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace hex_slam {

class ParameterTable {
 public:
  void Add(const std::string& key, bool* field, const std::string& help);
  void Add(const std::string& key, int* field, const std::string& help);
  void Add(const std::string& key, std::int64_t* field, const std::string& help);
  void Add(const std::string& key, double* field, const std::string& help);
  void Add(const std::string& key, std::string* field, const std::string& help);
  // Appends every entry of `other` (whose fields must outlive this table).
  void Merge(const ParameterTable& other);

  bool Has(const std::string& key) const { return entries_.count(key) > 0; }
  // Parses `text` into the field. Returns an empty string or an error naming the key.
  std::string Set(const std::string& key, const std::string& text);
  std::string Get(const std::string& key) const;
  std::string Help(const std::string& key) const;
  std::vector<std::string> Keys() const;
  // The known key nearest to a misspelt `key` (a few edits away), or "" if none is near.
  std::string ClosestKey(const std::string& key) const;
  // "unknown parameter 'x' (did you mean 'y'?)".
  std::string UnknownKeyMessage(const std::string& key) const;

  // Sets every key of `values`; returns one message per unknown key or bad value.
  std::vector<std::string> Apply(const std::map<std::string, std::string>& values);

 private:
  using Field = std::variant<bool*, int*, std::int64_t*, double*, std::string*>;
  struct Entry {
    Field field;
    std::string help;
  };
  void Insert(const std::string& key, Field field, const std::string& help);
  std::map<std::string, Entry> entries_;
  std::size_t longest_key_ = 0;
};

}  // namespace hex_slam

#endif  // HEX_SLAM_COMMON_PARAMETER_TABLE_H_
